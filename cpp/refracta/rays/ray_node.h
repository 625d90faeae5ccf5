// A point on a curved ray and the continuous path between two of them.
// The ray equations in arc-length form (Born & Wolf ch. 3): dx/ds = v/n, dv/ds = grad n, with
// |v| = n. A RayNode holds the state and the field there; a PathSegment is the quintic Hermite
// interpolant of two nodes using x, x' = v/n and x'' = (grad n - (grad n . t) t)/n at both ends,
// so events (crossing a height, closest approach) are solved on the continuous path, inside a
// step, with O(h^6) accuracy, by every integrator alike.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
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

 private:
  T s0_, length_;
  Vec3<T> c_[6];
};

// First u in [0, 1] where normal . x(u) - offset changes sign from the start's sign, or -1.
// Sampled at 16 points so that a path dipping across the plane and back within one segment is
// still caught; refined by bisection then Newton (the Newton steps in T carry derivatives).
template <class T>
T first_plane_crossing(const PathSegment<T>& seg, const Vec3d& normal, double offset) {
  auto f = [&](double u) {
    const Vec3<T> p = seg.position(T(u));
    return value_of(p.x()) * normal.x() + value_of(p.y()) * normal.y() +
           value_of(p.z()) * normal.z() - offset;
  };
  const double f0 = f(0.0);
  if (f0 == 0.0) return T(-1.0);
  constexpr int kSamples = 16;
  double lo = 0.0, hi = -1.0;
  for (int i = 1; i <= kSamples; ++i) {
    const double u = double(i) / kSamples;
    if ((f(u) > 0.0) != (f0 > 0.0)) {
      hi = u;
      break;
    }
    lo = u;
  }
  if (hi < 0.0) return T(-1.0);
  for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((f(mid) > 0.0) == (f0 > 0.0)) lo = mid; else hi = mid;
  }
  T u(hi);
  for (int it = 0; it < 2; ++it) {
    const Vec3<T> p = seg.position(u), dp = seg.velocity(u);
    const T g = p.x() * normal.x() + p.y() * normal.y() + p.z() * normal.z() - T(offset);
    const T dg = dp.x() * normal.x() + dp.y() * normal.y() + dp.z() * normal.z();
    if (value_of(dg) == 0.0) break;
    const T next = u - g / dg;
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
