// An orthonormal frame around a unit vector (the shading frame: z = normal), built without
// branches by Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (JCGT 6(1)).
// Every file that needs a basis from a direction uses this one.
#pragma once

#include "refracta/core/math.h"

#include <cmath>

namespace refracta {

struct Frame {
  Vec3d s{1.0, 0.0, 0.0}, t{0.0, 1.0, 0.0}, n{0.0, 0.0, 1.0};

  Frame() = default;
  Frame(const Vec3d& s_, const Vec3d& t_, const Vec3d& n_) : s(s_), t(t_), n(n_) {}

  // A right-handed frame (s, t, n) with n = the given unit vector.
  static Frame from_z(const Vec3d& n) {
    const double sign = std::copysign(1.0, n.z());
    const double a = -1.0 / (sign + n.z()), b = n.x() * n.y() * a;
    return Frame(Vec3d(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x()),
                 Vec3d(b, sign + n.y() * n.y() * a, -n.y()), n);
  }
  // A frame with n the given unit normal and s along the part of `tangent` orthogonal to it
  // (falls back to from_z when the tangent is parallel to n or zero).
  static Frame from_normal_tangent(const Vec3d& n, const Vec3d& tangent) {
    const Vec3d s = tangent - n * n.dot(tangent);
    const double len = s.norm();
    if (!(len > 1e-12)) return from_z(n);
    const Vec3d s_unit = s / len;
    return Frame(s_unit, n.cross(s_unit), n);
  }

  Vec3d to_local(const Vec3d& v) const { return Vec3d(s.dot(v), t.dot(v), n.dot(v)); }
  Vec3d from_local(const Vec3d& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

}  // namespace refracta
