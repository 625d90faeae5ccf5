// Small math shared by every layer: Eigen aliases and scalar helpers that work for double and
// for automatic-differentiation scalars (ceres::Jet), so one templated implementation serves both.
#pragma once

#include "refracta/core/error.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace refracta {

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
using Vec3d = Vec3<double>;

constexpr double kPi = 3.14159265358979323846;
// Scene coordinates are limited to this distance from the origin [m]: Embree works in float, and
// beyond it a coordinate loses metre precision (and Embree may assert). Straight rays, shadow rays
// and picks that must reach past any scene's far side end here too; features placed in the air
// (hot spots) lie within it.
constexpr double kSceneReach = 1e7;

// The plain double value of a scalar (the Jet's `.a` part). Specialised by the edit layer for
// ceres::Jet; a class template rather than a function so it binds at instantiation time.
template <class T>
struct ScalarValue {
  static double of(const T& x) { return static_cast<double>(x); }
};

template <class T>
inline double value_of(const T& x) {
  return ScalarValue<T>::of(x);
}

template <class T>
inline bool is_finite(const Vec3<T>& v) {
  return std::isfinite(value_of(v.x())) && std::isfinite(value_of(v.y())) &&
         std::isfinite(value_of(v.z()));
}

// Whether p is finite and within kSceneReach of the origin along every axis (the box scene
// coordinates live in).
inline bool within_reach(const Vec3d& p) { return is_finite(p) && p.cwiseAbs().maxCoeff() <= kSceneReach; }

// p itself; throws (ValueError naming `what`) unless within_reach(p).
inline const Vec3d& check_within_reach(const Vec3d& p, const char* what) {
  if (!within_reach(p)) {
    throw_invalid(what, " must be finite and within ", kSceneReach, " m of the origin (got (", p.x(), ", ", p.y(), ", ",
                  p.z(), "))");
  }
  return p;
}

inline double sqr(double x) { return x * x; }

inline double degrees_to_radians(double deg) { return deg * kPi / 180.0; }
inline double radians_to_degrees(double rad) { return rad * 180.0 / kPi; }

}  // namespace refracta
