// Pinhole or thin-lens camera. Pixel coordinates (u, v): u to the right, v down, pixel (i, j)
// covers [i, i+1) x [j, j+1), its centre at (i + 0.5, j + 0.5). y is up in the world.
//
// Thin lens (with_lens, photographic with an f-number): the lens is a disc of diameter A
// centred on position() in the plane of right() and up(); the ray of pixel (u, v) through lens
// point p_l goes toward the point the pinhole ray meets on the plane of focus (depth d_f along
// forward()), so that plane is sharp and a point at depth d spreads over a disc of angular
// diameter A |d - d_f| / (d d_f) (pbrt-v4's PerspectiveCamera, Mitsuba 3's thinlens). The field
// of view is the pinhole's (focus at infinity, no focus breathing, as Blender, Mitsuba and pbrt).
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/sampling.h"

#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace refracta {

// The narrowest vertical field of view a camera takes [deg] (3.6 milliarcseconds).
constexpr double kNarrowestVfov = 1e-6;

// The longest image side a camera takes [pixels]: 2^24 (16.8 million), past any sensor or stitched
// panorama, and small enough that pixel arithmetic -- a raster view's guard bands of up to two sides
// each way, the last tile's end -- stays inside an int (a camera 858993460 pixels wide overflowed
// its guard band and the raster march read far outside its buffer).
constexpr int kMaxImageSide = 1 << 24;

// The cameras' defaults, where Python leaves them out: Camera(...) and Camera.framing a 45 deg
// view on a 16:9 image of 640 x 360; the photographic cameras (photographic, eye_level) a
// full-frame 36 x 24 mm sensor and an image of its shape 960 px along its longer side (960 x 640
// on it), eye_level a 50 mm lens 1.6 m above the ground (a standing adult's eye).
struct CameraDefaults {
  static constexpr double kVfov = 45.0;  // [deg]
  static constexpr int kWidth = 640, kHeight = 360;
  static constexpr double kSensorWidth = 36.0, kSensorHeight = 24.0;  // [mm]
  static constexpr int kPhotoWidth = 960, kPhotoHeight = 640;
  static constexpr double kFocalLength = 50.0;  // [mm]
  static constexpr double kEyeHeight = 1.6;     // [m]
};

// Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360; one side
// given alone, the other follows that 16:9 shape): vfov is
// the vertical field of view [deg], from 1e-6 to under 180. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred
// at (i + 0.5, j + 0.5). A photographer's camera with depth of field: Camera.photographic(...,
// f_number=) or Camera.eye_level(..., f_number=); any camera through a thin lens: with_lens.
class Camera {
 public:
  // vfov: full vertical field of view [deg] in [kNarrowestVfov, 180). Throws std::invalid_argument
  // for NaN input, a zero view direction, an up vector parallel to it, or a side < 1 or above
  // kMaxImageSide.
  Camera(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double vfov_deg, int width,
         int height);

  // Both sides of an image of which either may be left out (nullopt): a missing side follows the
  // given one at `aspect` (width / height with square pixels: the default image's, or a sensor's),
  // rounded, at least 1; both missing, the defaults (a width of 320 alone made 320 x 360 of a
  // 640 x 360 default). Throws (ValueError) for a side it makes beyond an int.
  static std::pair<int, int> image_size(std::optional<int> width, std::optional<int> height, int default_width,
                                        int default_height, double aspect);
  // The image of a photographic camera (photographic, eye_level) on a sensor of the given sides:
  // image_size at the sensor's shape; both sides missing, kPhotoWidth pixels along the sensor's
  // longer side (36 x 24 mm: 960 x 640; 24 x 36 mm: 640 x 960 and 17.3 x 13 mm: 960 x 721, not
  // a 3:2 crop of them).
  static std::pair<int, int> photographic_size(std::optional<int> width, std::optional<int> height,
                                               double sensor_w_mm, double sensor_h_mm);

  // A camera that shows a whole scene (or box): it looks along ``direction`` (default: down
  // onto the box from its +x, +y, +z side) at the centre of the scene's box, from the distance at
  // which the bounding sphere fills the narrower of the two fields of view (the whole box is in the
  // image, touching its border only if the box is a cube seen along an axis). A scene's box holds
  // its objects: flat horizontal surfaces (add_ground's 20 km square, a water plane) count only
  // when the scene has nothing else.
  //
  //     scene.add_obj("city.obj", texture_dirs=["textures"])
  //     camera = refracta.Camera.framing(scene, width=800, height=450)
  //
  // scene_or_bounds: a Scene or (lower, upper) corners (3,) [m]; vfov [deg]. ValueError for an
  // empty, non-finite or single-point box.
  static Camera framing(const Vec3d& lower, const Vec3d& upper, const Vec3d& direction, const Vec3d& up,
                        double vfov_deg, int width, int height);

  // The vertical field of view [deg] Camera.photographic gives an image of width x height pixels
  // (the image spans the sensor's width when relatively wider than the sensor, else its height).
  static double photographic_vfov(double focal_length_mm, double sensor_w_mm, double sensor_h_mm, int width,
                                  int height);
  // A camera described by its lens and sensor: focal_length_mm on a sensor of
  // sensor_mm = (width, height) [mm] (full frame 36 x 24; APS-C about 23.5 x 15.6). The image spans
  // the sensor's width when it is relatively wider than the sensor, else its height (a crop of the
  // other side, Blender's "auto" sensor fit); vfov follows as 2 atan(h / 2f). A 300 mm telephoto
  // on full frame at 960 x 640 sees 4.58 deg vertically:
  //
  //     camera = refracta.Camera.photographic((0, 5, 0), (28000, 5, 0), 300.0, width=960, height=640)
  //
  // position, look_at [m]; up as for Camera.
  //
  // Depth of field: with f_number N a thin lens of aperture diameter A = f / N, focused at
  // focus_distance [m] (None: the distance to look_at); None: a pinhole, everything sharp. A point at
  // depth d [m] then blurs to the thin-lens circle of confusion ``c = A f abs(d - d_f) / (d (d_f - f))``
  // on the sensor; the image keeps the field of view of focus at infinity (no focus breathing, as
  // Blender, Mitsuba and pbrt), so in pixels c (d_f - f) / d_f x width / (sensor width used) [mm].
  // Each pixel sample takes its own lens point; through a field those rays are traced from the lens
  // (not served by the eye's table), which costs what table=False costs. Only the ray-traced methods
  // ('straight', 'curved') render it. ValueError for a focal length outside [0.1, 100000] mm, a
  // sensor side outside [0.1, 2000] mm, an f_number or focus_distance <= 0 or NaN, or a
  // focus_distance without an f_number (a pinhole has no focus).
  static Camera photographic(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double focal_length_mm,
                             double sensor_w_mm, double sensor_h_mm, int width, int height,
                             std::optional<double> f_number = std::nullopt,
                             std::optional<double> focus_distance = std::nullopt);

  // A photographer's view: standing at ``eye`` (the ground point under the feet [m]) with the
  // lens eye_height [m] above it (1.6: a standing adult), the camera level, aimed at the horizon in
  // the horizontal direction of ``target`` (the target's own height does not tilt it). Over flat
  // ground the horizon runs through the image's centre row, where mirages are: a hot road's "wet"
  // band and the inverted images under cars sit just below it (Camera.framing's 45 deg aerial view
  // shows none of them). Over a curved Earth the sea horizon dips sqrt(2 h / R) below it (0.041 deg
  // at 1.6 m). Lens, sensor, f_number and focus_distance as for Camera.photographic (focus by
  // default at the target's horizontal distance). ValueError for an eye height <= 0 or not finite,
  // or a target straight above or below the eye:
  //
  //     camera = refracta.Camera.eye_level((0, 0, 0), (0, 0, -200), eye_height=1.6, focal_length_mm=200)
  static Camera eye_level(const Vec3d& ground, const Vec3d& target, double eye_height, double focal_length_mm,
                          double sensor_w_mm, double sensor_h_mm, int width, int height,
                          std::optional<double> f_number = std::nullopt,
                          std::optional<double> focus_distance = std::nullopt);

  // The same view through a thin lens of aperture_diameter [m] (0: a pinhole) focused on the plane
  // at depth focus_distance [m] along forward() (Camera.photographic's f_number gives f / N).
  // ValueError for a negative or non-finite diameter, or a focus distance <= 0 or not finite.
  Camera with_lens(double aperture_diameter, double focus_distance) const;
  // The thin lens's aperture diameter [m] (f / N), 0 for a pinhole.
  double aperture_diameter() const { return 2.0 * lens_radius_; }
  // The depth [m] of the plane in focus, 0 for a pinhole.
  double focus_distance() const { return focus_distance_; }

  // The ray of pixel coordinates (u, v) through the lens point lens_u in [0, 1)^2 (mapped to the
  // disc by Shirley & Chiu's concentric map): its origin on the lens and its unit direction. A
  // pinhole: position() and direction(u, v).
  struct LensRay {
    Vec3d origin, direction;
  };
  LensRay lens_ray(double u, double v, const Vec2d& lens_u) const;

  // Unit direction of the ray through pixel coordinates (u, v) (with the jitter, if any).
  Vec3d direction(double u, double v) const;
  // direction(u, v) of pixel coordinates given by a caller (ValueError unless both are finite).
  Vec3d pixel_direction(double u, double v) const;
  // (u, v, depth) of a world point through the pinhole (the jitter ignored); depth [m] along
  // the view axis, <= 0 behind the camera.
  Vec3d project(const Vec3d& point) const;
  std::vector<Vec3d> project(std::vector<Vec3d> points) const;  // each point's (u, v, depth)

  // The same camera with every ray turned by small angles [rad] toward the image's right and up: a
  // map (height, width, 2) at the pixel centres, bilinear between them (held at the border).
  // Non-physical "geometric noise" (the follow-up editor's cheap shimmer); project() ignores it.
  // ValueError for a map of another size or with non-finite angles.
  Camera jittered(std::vector<float> angles) const;
  // The jitter map (empty: none).
  const std::vector<float>& jitter() const;

  const Vec3d& position() const { return position_; }
  // The constructor's look_at and up, as given (a copy rebuilt from them is bit-identical).
  const Vec3d& look_at() const { return look_at_; }
  // The up vector given to the constructor.
  const Vec3d& up_hint() const { return up_hint_; }
  const Vec3d& forward() const { return forward_; }
  const Vec3d& right() const { return right_; }
  const Vec3d& up() const { return up_; }         // the image's up (orthonormal to forward)
  double tan_half() const { return tan_half_; }    // tan of half the vertical field of view
  int width() const { return width_; }
  int height() const { return height_; }
  double vfov() const { return vfov_; }
  // The same view and lens at another image size (vertical field of view kept). A jittered camera
  // keeps its angle map at the same size; at another, ValueError (resize the map, then call
  // jittered; or camera.without_jitter().resized(...)).
  Camera resized(int width, int height) const;
  // The same camera without its jitter map (None: unchanged; a preview at another size, say).
  Camera without_jitter() const {
    Camera out = *this;
    out.jitter_.reset();
    return out;
  }
  // The angle [rad] one pixel subtends at the image centre (vertical field of view / height).
  double pixel_angle() const;

  // A camera from its pickled parts: the constructor's arguments, the jitter map (empty: none) and
  // the lens (aperture_diameter 0: a pinhole); its rays are bit-identical to the original's.
  static Camera restore(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double vfov_deg, int width,
                        int height, std::vector<float> jitter, double aperture_diameter, double focus_distance);
  // "Camera(position=(x, y, z), look_at=(...), up=(...), vfov=..., size=WxH[, aperture_diameter=...,
  // focus_distance=...])".
  std::string describe() const;

 private:
  Vec3d position_, look_at_, up_hint_, forward_, right_, up_;
  double vfov_, tan_half_;
  int width_, height_;
  double lens_radius_ = 0.0, focus_distance_ = 0.0;  // [m]; 0: a pinhole
  std::shared_ptr<const std::vector<float>> jitter_;  // (height, width, 2) angles [rad], or null
};

}  // namespace refracta
