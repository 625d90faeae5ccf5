// The camera of an edit whose orientation and field of view are solved with the air (matching a
// photograph): a pair with a pixel destination launches its light along the pixel's ray of the
// camera turned by (yaw, pitch, roll) and with vertical field of view vfov. The map from pixel to
// direction is templated on the scalar, so ceres::Jet differentiates it with the trace.
//
// Parameters (degrees), in this order after the field's:
//   camera_yaw    about the start camera's up: positive turns the view to the right;
//   camera_pitch  about its (yawed) right: positive tilts the view up;
//   camera_roll   about its (yawed, pitched) forward: positive turns the camera's up toward its
//                 right (the scene then appears turned counter-clockwise in the image);
//   camera_vfov   the full vertical field of view.
// yaw, pitch and roll are offsets from the start camera (0 at the start); vfov starts at its vfov.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/camera.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace refracta {

class CameraRig {
 public:
  static constexpr int kCount = 4;
  // The parameter names, in order.
  static const std::array<const char*, kCount>& names();
  // Index in names(), or -1.
  static int index_of(const std::string& name);

  // Throws std::invalid_argument for a jittered camera (its rays do not follow the pinhole map).
  explicit CameraRig(const Camera& camera);

  const Camera& start() const { return start_; }
  // (0, 0, 0, vfov): the start camera's values.
  std::array<double, kCount> start_values() const;
  // The default search box of parameter k: yaw within half the horizontal field of view either
  // way, pitch within half the vertical one (a feature farther off was not in the photograph),
  // roll within +-kRollBound, vfov within a factor of 2 of the start's (and inside (0, 180)).
  std::pair<double, double> default_bounds(int k) const;
  // The widest box the map takes for parameter k: angles within +-180 deg, vfov inside (0, 180).
  static std::pair<double, double> widest_bounds(int k);
  // Throws std::invalid_argument unless [lower, upper] is finite, ordered and within widest_bounds(k).
  static void check_bounds(int k, double lower, double upper);

  // The camera at these values (position, size and lens of the start).
  Camera camera(const double* values) const;

  // Unit direction of pixel (u, v)'s ray for values (yaw, pitch, roll, vfov) [deg]; at the start
  // values it equals Camera::direction(u, v).
  template <class T>
  Vec3<T> direction(double u, double v, const T* values) const {
    using std::tan;
    const double w = start_.width(), h = start_.height();
    const T tan_half = tan(values[3] * (0.5 * kPi / 180.0));
    const Vec3<T> d = turned(T((2.0 * u / w - 1.0) * w / h) * tan_half, T(1.0 - 2.0 * v / h) * tan_half, T(1.0), values);
    return d / d.norm();
  }

  // The start camera's local vector (x, y, z) along (right, up, forward), turned by values' yaw,
  // pitch and roll, in the scene frame: roll about forward first, then pitch about right, then
  // yaw about up (intrinsically: yaw, then pitch about the yawed right, then roll about the new
  // forward).
  template <class T>
  Vec3<T> turned(const T& x, const T& y, const T& z, const T* values) const {
    using std::cos;
    using std::sin;
    const double to_rad = kPi / 180.0;
    const T cr = cos(values[2] * to_rad), sr = sin(values[2] * to_rad);
    const T x1 = cr * x + sr * y, y1 = cr * y - sr * x;
    const T cp = cos(values[1] * to_rad), sp = sin(values[1] * to_rad);
    const T y2 = cp * y1 + sp * z, z2 = cp * z - sp * y1;
    const T cy = cos(values[0] * to_rad), sy = sin(values[0] * to_rad);
    const T x3 = cy * x1 + sy * z2, z3 = cy * z2 - sy * x1;
    return start_.right().cast<T>() * x3 + start_.up().cast<T>() * y2 + start_.forward().cast<T>() * z3;
  }

 private:
  Camera start_;
};

}  // namespace refracta
