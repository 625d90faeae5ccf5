// Pinhole and thin-lens camera (camera.h).
#include "refracta/scene/camera.h"

#include "refracta/core/error.h"
#include "refracta/core/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace refracta {

// Throws unless both sides are in [1, kMaxImageSide].
static void check_image_size(int width, int height, const char* what) {
  if (width < 1 || height < 1) throw_invalid(what, ": size must be at least 1x1 (got ", width, "x", height, ")");
  if (width > kMaxImageSide || height > kMaxImageSide) {
    throw_invalid(what, ": sides must be at most ", kMaxImageSide, " pixels (got ", width, "x", height, ")");
  }
}

Camera::Camera(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double vfov_deg, int width,
               int height)
    : position_(position), look_at_(look_at), up_hint_(up), vfov_(vfov_deg), width_(width), height_(height) {
  check_within_reach(position, "Camera: position");
  if (!is_finite(look_at)) throw_invalid("Camera: look_at must be finite");
  if (!is_finite(up)) throw_invalid("Camera: up must be finite");
  if (!(vfov_deg > 0.0 && vfov_deg < 180.0)) {
    throw_invalid("Camera: vfov must be in (0, 180) degrees (got ", vfov_deg, ")");
  }
  // Below the narrowest lens photographic() allows (a 0.1 mm side at 100 m: 6e-5 deg) by 60x;
  // a denormal field of view (a trial's 1e-300 mm sensor) made every pixel's ray the same.
  if (vfov_deg < kNarrowestVfov) {
    throw_invalid("Camera: vfov must be at least ", kNarrowestVfov, " degrees (got ", vfov_deg, ")");
  }
  check_image_size(width, height, "Camera");
  Vec3d view = look_at - position;
  if (!is_finite(view)) view = look_at / look_at.cwiseAbs().maxCoeff();  // look_at ~1e308 away: its direction
  if (!(view.cwiseAbs().maxCoeff() > 0.0)) throw_invalid("Camera: look_at must differ from position");
  forward_ = view.stableNormalized();  // scaled first: a view 1e200 long does not overflow
  const Vec3d side = forward_.cross(up);
  if (up.norm() == 0.0 || side.norm() < 1e-9 * up.norm()) {
    throw_invalid("Camera: up must be non-zero and not parallel to the view direction");
  }
  right_ = side.normalized();
  up_ = right_.cross(forward_);
  tan_half_ = std::tan(0.5 * degrees_to_radians(vfov_deg));
}

double Camera::photographic_vfov(double focal_length_mm, double sensor_w_mm, double sensor_h_mm, int width,
                                 int height) {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!(focal_length_mm >= 0.1 && focal_length_mm <= 1e5)) {
    throw_invalid("Camera.photographic: focal_length_mm must be in [0.1, 100000] (got ", focal_length_mm, ")");
  }
  if (!positive(sensor_w_mm) || !positive(sensor_h_mm)) {
    throw_invalid("Camera.photographic: sensor_mm must be two sides > 0 [mm] (got (", sensor_w_mm, ", ",
                  sensor_h_mm, "))");
  }
  // Sensors as made: from a 1 mm endoscope chip to 20 x 24 inch film (610 mm), with room.
  if (!(std::min(sensor_w_mm, sensor_h_mm) >= 0.1 && std::max(sensor_w_mm, sensor_h_mm) <= 2000.0)) {
    throw_invalid("Camera.photographic: sensor_mm sides must be in [0.1, 2000] mm (got (", sensor_w_mm, ", ",
                  sensor_h_mm, "))");
  }
  check_image_size(width, height, "Camera");
  const bool spans_width = double(width) * sensor_h_mm >= double(height) * sensor_w_mm;
  const double image_h_mm = spans_width ? sensor_w_mm * height / width : sensor_h_mm;
  return radians_to_degrees(2.0 * std::atan(0.5 * image_h_mm / focal_length_mm));
}

std::pair<int, int> Camera::image_size(std::optional<int> width, std::optional<int> height, int default_width,
                                       int default_height, double aspect) {
  if (width && height) return {*width, *height};
  if (!width && !height) return {default_width, default_height};
  if (!(aspect > 0.0 && std::isfinite(aspect))) aspect = double(default_width) / double(default_height);
  const double other = width ? double(*width) / aspect : double(*height) * aspect;
  if (!(other < double(std::numeric_limits<int>::max()))) {
    throw_invalid("Camera: a ", width ? "width" : "height", " of ", width ? *width : *height, " makes a ",
                  width ? "height" : "width", " of ", other, " pixels at the image's shape: give both");
  }
  const int made = std::max(1, int(std::lround(other)));
  return width ? std::pair(*width, made) : std::pair(made, *height);
}

std::pair<int, int> Camera::photographic_size(std::optional<int> width, std::optional<int> height,
                                              double sensor_w_mm, double sensor_h_mm) {
  const double aspect = sensor_w_mm / sensor_h_mm;
  if (!width && !height) (aspect >= 1.0 ? width : height) = CameraDefaults::kPhotoWidth;
  return image_size(width, height, CameraDefaults::kPhotoWidth, CameraDefaults::kPhotoHeight, aspect);
}

Camera Camera::photographic(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double focal_length_mm,
                            double sensor_w_mm, double sensor_h_mm, int width, int height,
                            std::optional<double> f_number, std::optional<double> focus_distance) {
  // Lenses as made: f/0.5 is the limit of a lens in air (N >= 1 / (2 sin 90 deg)), f/10000 a
  // pinhole's order; focal lengths from a 0.1 mm phone lens to 100 m (a telescope's); focus
  // within the scene's reach (a trial's 1e300 m focus turned every lens ray to NaN, and a 1e-6
  // f-number made a 50 km aperture).
  if (f_number && !(*f_number >= 0.5 && *f_number <= 1e4)) {
    throw_invalid("Camera.photographic: f_number must be in [0.5, 10000] (got ", *f_number, ")");
  }
  if (focus_distance && !(*focus_distance > 0.0 && *focus_distance <= kSceneReach)) {
    throw_invalid("Camera.photographic: focus_distance must be in (0, ", kSceneReach, "] m (got ", *focus_distance,
                  ")");
  }
  if (focus_distance && !f_number) {
    throw_invalid("Camera.photographic: focus_distance needs f_number (a pinhole has no focus)");
  }
  const double vfov = photographic_vfov(focal_length_mm, sensor_w_mm, sensor_h_mm, width, height);
  // A thin lens images only what lies beyond its focal length (1/f = 1/s + 1/s'): nearer, no focus.
  if (focus_distance && !(*focus_distance > 1e-3 * focal_length_mm)) {
    throw_invalid("Camera.photographic: focus_distance must exceed the focal length (", 1e-3 * focal_length_mm,
                  " m) (got ", *focus_distance, ")");
  }
  Camera camera(position, look_at, up, vfov, width, height);
  if (!f_number) return camera;
  // The aperture's diameter A = f / N [m]; focus by default where the camera looks (which must lie
  // beyond the focal length too: eye_level's target 1e-9 m away rendered wholly blurred).
  // (At most the scene's reach, as with_lens takes: a look_at 5e7 m away is a direction.)
  const double focus = focus_distance.value_or(std::min((look_at - position).norm(), kSceneReach));
  if (!(focus > 1e-3 * focal_length_mm)) {
    throw_invalid("Camera.photographic: the camera looks at a point ", focus, " m away, nearer than the focal length (",
                  1e-3 * focal_length_mm, " m), where a lens cannot focus: give focus_distance");
  }
  return camera.with_lens(1e-3 * focal_length_mm / *f_number, focus);
}

Camera Camera::eye_level(const Vec3d& ground, const Vec3d& target, double eye_height, double focal_length_mm,
                         double sensor_w_mm, double sensor_h_mm, int width, int height,
                         std::optional<double> f_number, std::optional<double> focus_distance) {
  if (!is_finite(ground)) throw_invalid("Camera.eye_level: eye must be finite");
  if (!is_finite(target)) throw_invalid("Camera.eye_level: target must be finite");
  if (!(eye_height > 0.0) || !std::isfinite(eye_height)) {
    throw_invalid("Camera.eye_level: eye_height must be > 0 [m] and finite (got ", eye_height, ")");
  }
  const Vec3d position = ground + Vec3d(0.0, eye_height, 0.0);
  // Level: the target's horizontal direction, at the eye's height.
  const Vec3d level(target.x() - ground.x(), 0.0, target.z() - ground.z());
  if (!(level.norm() > 0.0)) throw_invalid("Camera.eye_level: target must not be straight above or below the eye");
  if (f_number && !focus_distance && !(level.norm() > 1e-3 * focal_length_mm)) {
    throw_invalid("Camera.eye_level: the target is ", level.norm(), " m away, nearer than the focal length (",
                  1e-3 * focal_length_mm, " m), where a lens cannot focus: give focus_distance");
  }
  try {
    return photographic(position, position + level, Vec3d::UnitY(), focal_length_mm, sensor_w_mm, sensor_h_mm, width,
                        height, f_number, focus_distance);
  } catch (const std::invalid_argument& error) {  // the lens's and sensor's checks, named as the call made
    const std::string message = error.what(), made = "Camera.photographic:";
    if (message.rfind(made, 0) != 0) throw;
    throw std::invalid_argument("Camera.eye_level:" + message.substr(made.size()));
  }
}

Camera Camera::with_lens(double aperture_diameter, double focus_distance) const {
  // The widest lens photographic() makes is 200 m (100 m at f/0.5); a kilometre allows any
  // synthetic aperture without rays starting far from the camera (a trial's 1e8 m lens was then
  // reported as a max_length too long for "a camera 100000001.5 m out").
  constexpr double kWidestAperture = 1e3;  // [m]
  if (!(aperture_diameter >= 0.0 && aperture_diameter <= kWidestAperture)) {
    throw_invalid("Camera: aperture_diameter must be in [0, ", kWidestAperture, "] m (got ", aperture_diameter, ")");
  }
  if (!(focus_distance > 0.0 && focus_distance <= kSceneReach)) {
    throw_invalid("Camera: focus_distance must be in (0, ", kSceneReach, "] m (got ", focus_distance, ")");
  }
  Camera out = *this;
  out.lens_radius_ = 0.5 * aperture_diameter;
  out.focus_distance_ = aperture_diameter > 0.0 ? focus_distance : 0.0;
  return out;
}

Camera::LensRay Camera::lens_ray(double u, double v, const Vec2d& lens_u) const {
  const Vec3d d = direction(u, v);
  if (lens_radius_ == 0.0) return {position_, d};
  // The pinhole ray meets the plane of focus at depth d_f; the lens point's ray goes there.
  const Vec2d disc = lens_radius_ * sample_uniform_disk_concentric(lens_u);
  const Vec3d offset = disc.x() * right_ + disc.y() * up_;
  const Vec3d focus = (focus_distance_ / d.dot(forward_)) * d;  // from position_
  return {position_ + offset, (focus - offset).normalized()};
}

Camera Camera::framing(const Vec3d& lower, const Vec3d& upper, const Vec3d& direction, const Vec3d& up,
                       double vfov_deg, int width, int height) {
  if (!is_finite(lower) || !is_finite(upper) || (upper - lower).minCoeff() < 0.0) {
    throw_invalid("Camera.framing: bounds must be finite with lower <= upper (an empty scene has none)");
  }
  if (!is_finite(direction) || direction.norm() == 0.0) throw_invalid("Camera.framing: direction must be finite and non-zero");
  if (is_finite(up) && up.norm() > 0.0 && !(up.normalized().cross(direction.normalized()).norm() > 1e-9)) {
    throw_invalid("Camera.framing: direction (", direction.x(), ", ", direction.y(), ", ", direction.z(),
                  ") must not be parallel to up (", up.x(), ", ", up.y(), ", ", up.z(),
                  "): give another up, e.g. (0, 0, -1) to look straight down");
  }
  if (!(vfov_deg > 0.0 && vfov_deg < 180.0)) {
    throw_invalid("Camera.framing: vfov must be in (0, 180) degrees (got ", vfov_deg, ")");
  }
  check_image_size(width, height, "Camera.framing");
  const Vec3d centre = 0.5 * (lower + upper);
  const double radius = 0.5 * (upper - lower).norm();  // of the bounding sphere
  if (!(radius > 0.0)) throw_invalid("Camera.framing: the bounds are a single point");
  // The sphere subtends half-angle asin(r / d): fit it to the narrower half field of view.
  const double half_v = 0.5 * degrees_to_radians(vfov_deg);
  const double half_h = std::atan(std::tan(half_v) * width / height);
  const double distance = radius / std::sin(std::min(half_v, half_h));
  const Vec3d position = centre - distance * direction.normalized();
  if (!within_reach(position)) {  // said here: the constructor would blame a position the caller never gave
    throw_invalid("Camera.framing: a vfov of ", vfov_deg, " deg frames the bounds from ", distance,
                  " m away, beyond the scene's reach (", kSceneReach, " m): give a wider vfov");
  }
  return Camera(position, centre, up, vfov_deg, width, height);
}

Vec3d Camera::direction(double u, double v) const {
  const double x = (2.0 * u / width_ - 1.0) * tan_half_ * width_ / height_;
  const double y = (1.0 - 2.0 * v / height_) * tan_half_;
  // Pixels far outside the image: scaled by the largest component before normalising (its square
  // would overflow), up to where 2u/width itself overflows.
  const double scale = std::max({1.0, std::abs(x), std::abs(y)});
  if (!std::isfinite(scale)) {
    throw_invalid("Camera: pixel (", u, ", ", v, ") is too far outside the ", width_, "x", height_,
                  " image to give a ray direction");
  }
  constexpr double kSquareSafe = 1e150;  // |x|^2 stays far below the double range
  const Vec3d d = scale < kSquareSafe ? Vec3d((forward_ + x * right_ + y * up_).normalized())
                                      : Vec3d((forward_ / scale + (x / scale) * right_ + (y / scale) * up_).normalized());
  if (!jitter_) return d;
  // Bilinear in the pixel-centre grid, held at the border.
  const double fu = std::clamp(u - 0.5, 0.0, width_ - 1.0), fv = std::clamp(v - 0.5, 0.0, height_ - 1.0);
  const int i0 = std::min(int(fu), width_ - 1), j0 = std::min(int(fv), height_ - 1);
  const int i1 = std::min(i0 + 1, width_ - 1), j1 = std::min(j0 + 1, height_ - 1);
  const double a = fu - i0, b = fv - j0;
  const std::vector<float>& m = *jitter_;
  auto at = [&](int i, int j, int k) { return double(m[(size_t(j) * width_ + i) * 2 + k]); };
  double angle[2];
  for (int k = 0; k < 2; ++k) {
    angle[k] = (1 - a) * (1 - b) * at(i0, j0, k) + a * (1 - b) * at(i1, j0, k) + (1 - a) * b * at(i0, j1, k) +
               a * b * at(i1, j1, k);
  }
  // Turned by the small angles about up() and right(): the right/up components of the unit vector.
  const Vec3d side = right_ - d * d.dot(right_), rise = up_ - d * d.dot(up_);
  return (d + angle[0] * side.normalized() + angle[1] * rise.normalized()).normalized();
}

std::vector<Vec3d> Camera::project(std::vector<Vec3d> points) const {
  for (Vec3d& p : points) p = project(p);
  return points;
}

Vec3d Camera::pixel_direction(double u, double v) const {
  if (!std::isfinite(u) || !std::isfinite(v)) throw_invalid("u and v must be finite");
  return direction(u, v);
}

Camera Camera::restore(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double vfov_deg, int width,
                       int height, std::vector<float> jitter, double aperture_diameter, double focus_distance) {
  Camera camera(position, look_at, up, vfov_deg, width, height);
  if (!jitter.empty()) camera = camera.jittered(std::move(jitter));
  if (aperture_diameter != 0.0) camera = camera.with_lens(aperture_diameter, focus_distance);  // checks a bad lens
  return camera;
}

std::string Camera::describe() const {
  const std::string lens = aperture_diameter() > 0.0
                               ? concat(", aperture_diameter=", aperture_diameter(), ", focus_distance=", focus_distance_)
                               : std::string();
  auto triple = [](const Vec3d& v) { return concat("(", v.x(), ", ", v.y(), ", ", v.z(), ")"); };
  return concat("Camera(position=", triple(position_), ", look_at=", triple(look_at_), ", up=", triple(up_hint_),
                ", vfov=", vfov_, ", size=", width_, "x", height_, lens, ")");
}

Camera Camera::resized(int width, int height) const {
  if (jitter_ && (width != width_ || height != height_)) {
    throw_invalid("Camera.resized: this camera is jittered, and its angle map is ", height_, " x ", width_,
                  " pixels: resize the map and call jittered on the resized camera");
  }
  Camera out(position_, look_at_, up_hint_, vfov_, width, height);
  out.lens_radius_ = lens_radius_, out.focus_distance_ = focus_distance_;
  out.jitter_ = jitter_;
  return out;
}

Camera Camera::jittered(std::vector<float> angles) const {
  if (angles.size() != size_t(width_) * height_ * 2) {
    throw_invalid("Camera.jittered: the angle map must be (height, width, 2) = (", height_, ", ", width_,
                  ", 2) (got ", angles.size(), " values)");
  }
  for (float a : angles) {
    if (!std::isfinite(a)) throw_invalid("Camera.jittered: angles must be finite");
  }
  Camera out = *this;
  out.jitter_ = std::make_shared<const std::vector<float>>(std::move(angles));
  return out;
}

const std::vector<float>& Camera::jitter() const {
  static const std::vector<float> kNone;
  return jitter_ ? *jitter_ : kNone;
}

Vec3d Camera::project(const Vec3d& point) const {
  const Vec3d d = point - position_;
  if (d.isZero(0.0)) {
    throw_invalid("Camera.project: the point (", point.x(), ", ", point.y(), ", ", point.z(),
                  ") is the camera's own position and has no image");
  }
  const double depth = d.dot(forward_);
  const double x = d.dot(right_) / depth, y = d.dot(up_) / depth;
  const double u = 0.5 * width_ * (1.0 + x / (tan_half_ * width_ / height_));
  const double v = 0.5 * height_ * (1.0 - y / tan_half_);
  return Vec3d(u, v, depth);
}

double Camera::pixel_angle() const { return 2.0 * std::atan(tan_half_) / height_; }

}  // namespace refracta
