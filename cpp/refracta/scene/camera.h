// Pinhole camera. Pixel coordinates (u, v): u to the right, v down, pixel (i, j) covers
// [i, i+1) x [j, j+1), its centre at (i + 0.5, j + 0.5). y is up in the world.
#pragma once

#include "refracta/core/math.h"

#include <memory>
#include <vector>

namespace refracta {

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
  static Camera photographic(const Vec3d& position, const Vec3d& look_at, const Vec3d& up, double focal_length_mm,
                             double sensor_w_mm, double sensor_h_mm, int width, int height);

  // Unit direction of the ray through pixel coordinates (u, v) (with the jitter, if any).
  Vec3d direction(double u, double v) const;
  // (u, v, depth) of a world point through the pinhole (the jitter ignored); depth [m] along
  // the view axis, <= 0 behind the camera.
  Vec3d project(const Vec3d& point) const;

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
  // The same view at another image size (the vertical field of view is kept; no jitter).
  Camera resized(int width, int height) const { return Camera(position_, look_at_, up_hint_, vfov_, width, height); }
  // Angle subtended by one pixel at the image centre [rad].
  double pixel_angle() const;

 private:
  Vec3d position_, look_at_, up_hint_, forward_, right_, up_;
  double vfov_, tan_half_;
  int width_, height_;
  std::shared_ptr<const std::vector<float>> jitter_;  // (height, width, 2) angles [rad], or null
};

}  // namespace refracta
