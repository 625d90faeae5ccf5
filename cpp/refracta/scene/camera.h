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
#include <string>
#include <vector>

namespace refracta {

// Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360): vfov is
// the vertical field of view [deg]. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred
// at (i + 0.5, j + 0.5). A photographer's camera with depth of field: Camera.photographic(...,
// f_number=) or Camera.eye_level(..., f_number=); any camera through a thin lens: with_lens.
class Camera {
 public:
  // vfov: full vertical field of view [deg] in (0, 180). Throws std::invalid_argument for NaN
  // input, a zero view direction, an up vector parallel to it, or a size < 1.
  Camera(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double vfov_deg, int width,
         int height);

  // A camera looking along `direction` at the centre of the box [lower, upper] from just far
  // enough that the box's bounding sphere fills the narrower of the two fields of view (the whole
  // box is in the image, touching its border only if the box is a cube seen along an axis).
  // Throws std::invalid_argument for an empty, non-finite or single-point box.
  static Camera framing(const Vec3d& lower, const Vec3d& upper, const Vec3d& direction, const Vec3d& up,
                        double vfov_deg, int width, int height);

  // A camera described as a photographer would: a lens of focal length f [mm] on a sensor of
  // sensor_w x sensor_h [mm] (36 x 24: full frame). The image spans the sensor's width when it is
  // relatively wider than the sensor, else its height (a crop of the other side, Blender's
  // "auto" sensor fit): vfov = 2 atan(sensor_h' / 2f), sensor_h' = sensor_w H / W in the first
  // case. Throws std::invalid_argument for a focal length or sensor side <= 0 or not finite.
  // f_number N given: a thin lens of aperture diameter A = f / N focused at focus_distance [m]
  // (unset: |look_at - position|). Throws for an f-number or focus distance <= 0 or not finite, and
  // for a focus distance without an f-number (a pinhole has no focus).
  // The vertical field of view [deg] of that fit for an image of width x height pixels (throws as
  // photographic() for the focal length, the sensor and the size).
  static double photographic_vfov(double focal_length_mm, double sensor_w_mm, double sensor_h_mm, int width,
                                  int height);
  static Camera photographic(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double focal_length_mm,
                             double sensor_w_mm, double sensor_h_mm, int width, int height,
                             std::optional<double> f_number = std::nullopt,
                             std::optional<double> focus_distance = std::nullopt);

  // A photographer standing at `ground` (the point under their feet [m]) with the lens
  // eye_height [m] above it, looking horizontally -- at the horizon of a flat Earth, which then
  // runs through the image's centre row -- toward `target` (its horizontal direction; the
  // target's own height does not tilt the camera). Lens and sensor as photographic(); focus
  // (with an f-number) at focus_distance, else at the target's horizontal distance. Throws for an
  // eye height <= 0 or not finite, or a target straight above or below the eye.
  static Camera eye_level(const Vec3d& ground, const Vec3d& target, double eye_height, double focal_length_mm,
                          double sensor_w_mm, double sensor_h_mm, int width, int height,
                          std::optional<double> f_number = std::nullopt,
                          std::optional<double> focus_distance = std::nullopt);

  // The same camera with a thin lens of aperture diameter [m] (0: a pinhole) focused at depth
  // focus_distance [m] along forward(). Throws for a negative or non-finite diameter, or a focus
  // distance <= 0 or not finite.
  Camera with_lens(double aperture_diameter, double focus_distance) const;
  double aperture_diameter() const { return 2.0 * lens_radius_; }  // [m], 0 for a pinhole
  double focus_distance() const { return focus_distance_; }         // [m], 0 for a pinhole

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

  // The same camera with every ray turned by small angles [rad] toward right() and up(): a map
  // (height, width, 2) at the pixel centres, interpolated bilinearly between them (held at the
  // border) -- the follow-up editor's non-physical "geometric noise" for shimmer. Throws
  // std::invalid_argument for a map of another size or with non-finite angles.
  Camera jittered(std::vector<float> angles) const;
  // The jitter map (empty: none).
  const std::vector<float>& jitter() const;

  const Vec3d& position() const { return position_; }
  // The constructor's look_at and up, as given (a copy rebuilt from them is bit-identical).
  const Vec3d& look_at() const { return look_at_; }
  const Vec3d& up_hint() const { return up_hint_; }
  const Vec3d& forward() const { return forward_; }
  const Vec3d& right() const { return right_; }
  const Vec3d& up() const { return up_; }         // the image's up (orthonormal to forward)
  double tan_half() const { return tan_half_; }    // tan of half the vertical field of view
  int width() const { return width_; }
  int height() const { return height_; }
  double vfov() const { return vfov_; }
  // The same view and lens at another image size (the vertical field of view is kept). A jitter
  // map is per pixel: kept at the same size; at another, std::invalid_argument (resample the map
  // and call jittered).
  Camera resized(int width, int height) const;
  // The same camera without its jitter map (a preview at another size, say).
  Camera without_jitter() const {
    Camera out = *this;
    out.jitter_.reset();
    return out;
  }
  // Angle subtended by one pixel at the image centre [rad].
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
