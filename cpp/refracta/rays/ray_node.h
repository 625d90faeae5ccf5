// A point on a curved ray and the continuous path between two of them.
// The ray equations in arc-length form (Born & Wolf ch. 3): dx/ds = v/n, dv/ds = grad n, with
// |v| = n. A RayNode holds the state and the field there; a PathSegment is the quintic Hermite
// interpolant of two nodes using x, x' = v/n and x'' = (grad n - (grad n . t) t)/n at both ends,
// so events (crossing a height, closest approach) are solved on the continuous path, inside a
// step, with O(h^6) accuracy, by every integrator alike.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/core/polynomial_roots.h"
#include "refracta/media/ior_range.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refracta {

template <class T>
struct RayNode {
  T s = T(0.0);                        // arc length from the start [m]
  Vec3<T> x = Vec3<T>::Zero();         // position [m]
  Vec3<T> v = Vec3<T>::Zero();         // ray vector n t, |v| = n
  T n = T(1.0);                        // refractive index at x
  Vec3<T> grad = Vec3<T>::Zero();      // grad n at x [1/m]

  Vec3<T> tangent() const { return v / n; }  // dx/ds
  // d^2x/ds^2 = d(v/n)/ds = grad/n - v (grad . v)/n^3.
  Vec3<T> curvature() const { return grad / n - v * (grad.dot(v) / (n * n * n)); }
};

// Evaluates the field at x and builds the node; throws NumericalError for n <= 0 or non-finite.
template <class T, class Field>
RayNode<T> make_node(const Field& field, const T& s, const Vec3<T>& x, const Vec3<T>& v,
                     int64_t* evaluations) {
  RayNode<T> node{s, x, v, T(0.0), Vec3<T>::Zero()};
  field.evaluate(x, &node.n, &node.grad);
  ++*evaluations;
  if (!usable_ior(value_of(node.n)) || !is_finite(node.grad)) {
    throw_numerical("ray reached n = ", value_of(node.n), " (grad n = (", value_of(node.grad.x()),
                    ", ", value_of(node.grad.y()), ", ", value_of(node.grad.z()), ")) at (",
                    value_of(x.x()), ", ", value_of(x.y()), ", ", value_of(x.z()),
                    ") m; the refractive index must be finite and > 0 (in [", kMinIor, ", ", kMaxIor, "]) along the path");
  }
  if (!is_finite(x) || !is_finite(v)) {
    throw_numerical("ray state became non-finite at arc length ", value_of(s), " m");
  }
  return node;
}

template <class T>
class PathSegment {
 public:
  PathSegment(const RayNode<T>& a, const RayNode<T>& b) : s0_(a.s), length_(b.s - a.s) {
    const T& h = length_;
    const Vec3<T> d0 = a.tangent() * h, d1 = b.tangent() * h;
    const Vec3<T> k0 = a.curvature() * (h * h), k1 = b.curvature() * (h * h);
    c_[0] = a.x;
    c_[1] = d0;
    c_[2] = k0 * T(0.5);
    c_[3] = (b.x - a.x) * T(10.0) - d0 * T(6.0) - d1 * T(4.0) - k0 * T(1.5) + k1 * T(0.5);
    c_[4] = (a.x - b.x) * T(15.0) + d0 * T(8.0) + d1 * T(7.0) + k0 * T(1.5) - k1;
    c_[5] = (b.x - a.x) * T(6.0) - d0 * T(3.0) - d1 * T(3.0) - k0 * T(0.5) + k1 * T(0.5);
  }

  const T& start() const { return s0_; }
  const T& length() const { return length_; }

  // Position at the fraction u in [0, 1] of the segment.
  Vec3<T> position(const T& u) const {
    return c_[0] + u * (c_[1] + u * (c_[2] + u * (c_[3] + u * (c_[4] + u * c_[5]))));
  }
  // dx/du and d^2x/du^2.
  Vec3<T> velocity(const T& u) const {
    return c_[1] + u * (c_[2] * T(2.0) + u * (c_[3] * T(3.0) + u * (c_[4] * T(4.0) + u * c_[5] * T(5.0))));
  }
  Vec3<T> acceleration(const T& u) const {
    return c_[2] * T(2.0) + u * (c_[3] * T(6.0) + u * (c_[4] * T(12.0) + u * c_[5] * T(20.0)));
  }
  // normal . x(u) - offset as the coefficients of its quintic in u (plain values).
  std::array<double, 6> across(const Vec3d& normal, double offset) const {
    std::array<double, 6> g{};
    for (size_t k = 0; k < 6; ++k) {
      g[k] = value_of(c_[k].x()) * normal.x() + value_of(c_[k].y()) * normal.y() + value_of(c_[k].z()) * normal.z();
    }
    g[0] -= offset;
    return g;
  }

 private:
  T s0_, length_;
  Vec3<T> c_[6];
};

// Whether sum_k g[k] u^k may be 0 on [0, 1]: each term u^k lies in [0, 1], so the sum lies within
// g[0] plus its other coefficients' negative (or positive) parts; most segments end here.
inline bool may_vanish(const std::array<double, 6>& g) {
  double low = g[0], high = g[0];
  for (size_t k = 1; k < 6; ++k) (g[k] < 0.0 ? low : high) += g[k];
  return low <= 0.0 && high >= 0.0;
}

// First u in (0, 1] where normal . x(u) - offset changes sign from the start's sign (or reaches
// 0), or -1: the roots of the segment's quintic (core/polynomial_roots.h), so a path dipping
// across the plane and back within one segment is caught however briefly; refined by Newton in T
// (its steps carry the derivatives of a Jet).
template <class T>
T first_plane_crossing(const PathSegment<T>& seg, const Vec3d& normal, double offset) {
  const std::array<double, 6> g = seg.across(normal, offset);
  if (g[0] == 0.0 || !may_vanish(g)) return T(-1.0);
  const PolynomialRoots<6> roots = polynomial_roots(g, 0.0, 1.0);
  double root = -1.0;
  for (size_t i = 0; i < roots.count && root < 0.0; ++i) {
    if (roots.at[i] > 0.0) root = roots.at[i];
  }
  if (root < 0.0) return T(-1.0);
  const double lo = root * (1.0 - 1e-12), hi = root * (1.0 + 1e-12);
  T u(root);
  for (int it = 0; it < 2; ++it) {
    const Vec3<T> p = seg.position(u), dp = seg.velocity(u);
    const T gap = p.x() * normal.x() + p.y() * normal.y() + p.z() * normal.z() - T(offset);
    const T rate = dp.x() * normal.x() + dp.y() * normal.y() + dp.z() * normal.z();
    if (value_of(rate) == 0.0) break;
    const T next = u - gap / rate;
    if (value_of(next) < lo - 1e-12 || value_of(next) > hi + 1e-12) break;
    u = next;
  }
  return u;
}

// The plain double values of a node (the Jet's value parts).
template <class T>
RayNode<double> node_values(const RayNode<T>& a) {
  auto v = [](const Vec3<T>& x) { return Vec3d(value_of(x.x()), value_of(x.y()), value_of(x.z())); };
  return {value_of(a.s), v(a.x), v(a.v), value_of(a.n), v(a.grad)};
}

// A lower bound on the distance from q to the path between nodes a and b: the curve stays
// within its bulge (from arc length vs chord) of the chord. Lets searches skip segments.
inline double segment_distance_bound(const RayNode<double>& a, const RayNode<double>& b, const Vec3d& q) {
  const double chord = (b.x - a.x).norm(), length = b.s - a.s;
  const double bulge = 0.5 * std::sqrt(std::max(length * length - chord * chord, 0.0)) + 1e-9;
  return (0.5 * (a.x + b.x) - q).norm() - 0.5 * chord - bulge;
}

// u in [0, 1] of the point of the segment closest to q (global over the segment: the best of
// the ends and of Newton on (x(u) - q) . x'(u) = 0 from 9 starts), and its squared distance.
inline double closest_on_segment(const PathSegment<double>& seg, const Vec3d& q, double* distance2) {
  auto dist2 = [&](double u) { return (seg.position(u) - q).squaredNorm(); };
  double best_u = 0.0, best = dist2(0.0);
  for (int start = 0; start <= 8; ++start) {
    double u = start / 8.0;
    for (int it = 0; it < 30; ++it) {
      const Vec3d e = seg.position(u) - q, dp = seg.velocity(u), ddp = seg.acceleration(u);
      const double g = e.dot(dp), dg = dp.dot(dp) + e.dot(ddp);
      if (!(dg > 0.0)) break;
      const double next = std::clamp(u - g / dg, 0.0, 1.0);
      const bool done = std::abs(next - u) < 1e-15;
      u = next;
      if (done) break;
    }
    const double d = dist2(u);
    if (d < best) best = d, best_u = u;
  }
  if (dist2(1.0) < best) best = dist2(1.0), best_u = 1.0;
  *distance2 = best;
  return best_u;
}

// The closest point's u found in double, carried into T by one Newton step on
// (x(u) - q) . x'(u) = 0 so that it has the derivatives of the interior optimum (an end point,
// u = 0 or 1, keeps a constant u).
template <class T>
T refine_closest(const PathSegment<T>& seg, const Vec3<T>& q, double u_value) {
  T u(u_value);
  if (u_value > 0.0 && u_value < 1.0) {
    const Vec3<T> p = seg.position(u), dp = seg.velocity(u), ddp = seg.acceleration(u);
    const T g = (p - q).dot(dp), dg = dp.dot(dp) + (p - q).dot(ddp);
    if (value_of(dg) > 0.0) u = u - g / dg;
  }
  return u;
}

}  // namespace refracta
