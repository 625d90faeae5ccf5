// The one stepping loop of the curved-ray integrators (rk4, rk45), templated on the scalar so it
// also runs with ceres::Jet for editing. It launches with v0 = n(x0) t0, advances with a stepper,
// ends the path at max_length exactly or where it descends through stop_height (located on the
// continuous segment, not at a vertex), and hands every accepted segment to a visitor
// `bool visit(const RayNode<T>& a, const RayNode<T>& b)` that returns false to stop.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/media/local_region.h"
#include "refracta/rays/ray_node.h"
#include "refracta/rays/trace_options.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace detail {

// The right-hand side of the ray equations at a state: (dx/ds, dv/ds) = (v/n, grad n).
template <class T>
struct RayRate {
  Vec3<T> dx, dv;
};

template <class T>
RayRate<T> rate(const RayNode<T>& node) {
  return {node.v / node.n, node.grad};
}

template <class T, class Field>
RayNode<T> node_at(const Field& field, const T& s, const RayNode<T>& a, const T& h,
                   const Vec3<T>& dx, const Vec3<T>& dv, int64_t* evaluations) {
  return make_node(field, T(s), Vec3<T>(a.x + h * dx), Vec3<T>(a.v + h * dv), evaluations);
}

}  // namespace detail

// Classic fourth-order Runge-Kutta with a fixed step (the original editor's integrator).
template <class T, class Field>
class Rk4Stepper {
 public:
  explicit Rk4Stepper(double step) : step_(step) {}

  // The last step takes all that is left when it is at most a step and a sliver: the summed arc
  // length falls short of max_length by round-off (a trial: 99.9999999999986 of 100 m with step 0.1
  // m), and the sliver's own step overran max_steps.
  RayNode<T> advance(const Field& field, const RayNode<T>& a, double remaining, int64_t* evals) {
    return step_fixed(field, a, T(remaining <= step_ * (1.0 + kSliver) ? remaining : step_), evals);
  }

  // One step of exactly h (also used to land on an event inside a step).
  RayNode<T> step_fixed(const Field& field, const RayNode<T>& a, const T& h, int64_t* evals) const {
    using detail::node_at;
    const auto k1 = detail::rate(a);
    const auto n2 = node_at(field, a.s, a, T(0.5) * h, k1.dx, k1.dv, evals);
    const auto k2 = detail::rate(n2);
    const auto n3 = node_at(field, a.s, a, T(0.5) * h, k2.dx, k2.dv, evals);
    const auto k3 = detail::rate(n3);
    const auto n4 = node_at(field, a.s, a, h, k3.dx, k3.dv, evals);
    const auto k4 = detail::rate(n4);
    const Vec3<T> dx = (k1.dx + T(2.0) * k2.dx + T(2.0) * k3.dx + k4.dx) / T(6.0);
    const Vec3<T> dv = (k1.dv + T(2.0) * k2.dv + T(2.0) * k3.dv + k4.dv) / T(6.0);
    return node_at(field, T(a.s + h), a, h, dx, dv, evals);
  }

 private:
  static constexpr double kSliver = 1e-9;  // of a step: far above the sum's round-off, far below a step
  double step_;
};

// Dormand-Prince 5(4) (Hairer, Norsett & Wanner, Solving ODEs I, II.5) with first-same-as-last.
// Error control aims at the global position error `tol` [m] over the path: each step's local
// position error plus its direction error carried over the remaining length must stay below
// tol * h / max_length (error per unit step), so the contributions add up to about tol.
// Optional: first_step [m] (> 0; default min(max_step, max_length, 1 m)); carry [m], the farthest a
// direction error is carried (default the remaining length): a caller whose path leaves the
// error-prone air within `carry` and is held to an angle beyond it (a pixel's footprint grows with
// the path) needs the direction only to that angle, not to its position at max_length.
template <class T, class Field>
class Rk45Stepper {
 public:
  Rk45Stepper(double tol, double max_step, double max_length, double first_step = 0.0,
              double carry = std::numeric_limits<double>::infinity())
      : tol_(tol), max_step_(max_step), max_length_(max_length),
        h_(first_step > 0.0 ? std::min({first_step, max_step, max_length}) : std::min({max_step, max_length, 1.0})),
        carry_(carry) {}

  // Steps no longer than step_within_regions allows in `regions` (which must outlive the stepper;
  // empty: no limit).
  void keep_within(const std::vector<LocalRegion>* regions) { regions_ = regions; }

  // A step accepted right after a rejection does not grow the next (Hairer, Norsett & Wanner,
  // Solving ODEs I, II.4: facmax = 1). For paths into air whose error grows along them (a hot
  // spot's surface layer, e^(-h/depth) at a fixed step): there steps grew 5x, were rejected and
  // shrank again, 8.8 times a leg. Not for every trace: where the error estimate is round-off (a
  // 10 000 km editing pair near its eye), rejections are noise and the steps must grow past them.
  void hold_after_rejection() { hold_after_rejection_ = true; }

  RayNode<T> advance(const Field& field, const RayNode<T>& a, double remaining, int64_t* evals) {
    for (int attempt = 0;; ++attempt) {
      double hv = std::min(h_, remaining);
      if (regions_ && !regions_->empty()) {
        const Vec3d x(value_of(a.x.x()), value_of(a.x.y()), value_of(a.x.z()));
        const Vec3d v(value_of(a.v.x()), value_of(a.v.y()), value_of(a.v.z()));
        hv = step_within_regions(*regions_, x, v.normalized(), hv);
      }
      double err_x, err_v;
      RayNode<T> b;
      try {
        b = dormand_prince(field, a, T(hv), evals, &err_x, &err_v);
      } catch (const NumericalError&) {
        // A trial step whose stages reach where the field is undefined (below its modelled range,
        // beyond a stop height the step would have crossed) is too long, like one whose error is:
        // shrink it. At the smallest step the path itself has got there.
        if (hv <= kMinStep * max_length_ || attempt > 200) throw;
        h_ = 0.2 * hv;
        continue;
      }
      const double carried = std::min(std::max(remaining - hv, 0.0), carry_) / value_of(b.n);
      const double allowed = tol_ * hv / max_length_;
      double error = (err_x + err_v * carried) / allowed;
      if (std::isnan(error)) error = std::numeric_limits<double>::infinity();  // shrink, never NaN steps
      // Error per unit step scales as h^4: step factor error^(-1/4), safety 0.9, within [0.2, 5]
      // (two square roots: pow was 2.5 % of a hot-spot render).
      double factor = error == 0.0 ? 5.0 : std::clamp(0.9 / std::sqrt(std::sqrt(error)), 0.2, 5.0);
      const bool at_min_step = hv <= kMinStep * max_length_;
      if (error <= 1.0 || at_min_step) {
        if (hold_after_rejection_ && attempt > 0) factor = std::min(factor, 1.0);
        // A few minimum steps carry the ray across a discontinuity of the field; a long run of
        // them means the field is singular here (n -> 0, an infinite gradient).
        // Tiny accepted steps shrinking toward a point (a Zeno sequence) mean the same.
        // Only steps the error control shrank count: a small largest step asked for is no sign.
        min_steps_in_a_row_ = hv <= kTinyStep * max_length_ && hv < max_step_ ? min_steps_in_a_row_ + 1 : 0;
        if (min_steps_in_a_row_ > 1000) {
          // Also a tolerance finer than double precision: each step may err by tol h / max_length,
          // while rounding the position alone errs by ~1e-16 |x| (a trial's tol 1e-8 over 40 km).
          throw_numerical("rk45: step size collapsed at (", value_of(a.x.x()), ", ", value_of(a.x.y()),
                          ", ", value_of(a.x.z()), ") m where n = ", value_of(a.n), " and |grad n| = ",
                          value_of(a.grad.norm()), " 1/m; the field is singular there, or tol = ", tol_,
                          " m over max_length = ", max_length_,
                          " m is finer than double precision resolves there (loosen tol or shorten max_length)");
        }
        h_ = std::min(hv * factor, max_step_);
        return b;
      }
      h_ = hv * std::min(factor, 0.9);
      if (attempt > 200) {
        throw_numerical("rk45: step size collapsed at arc length ", value_of(a.s), " m");
      }
    }
  }

  // One step of exactly h (also used to land on an event inside a step).
  RayNode<T> step_fixed(const Field& field, const RayNode<T>& a, const T& h, int64_t* evals) const {
    double err_x, err_v;
    return dormand_prince(field, a, h, evals, &err_x, &err_v);
  }

 private:
  // One Dormand-Prince step and the max-norm errors of the embedded 4th-order solution.
  static RayNode<T> dormand_prince(const Field& field, const RayNode<T>& a, const T& h, int64_t* evals,
                                   double* err_x, double* err_v) {
    using detail::node_at;
    static constexpr double a21 = 1.0 / 5;
    static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
    static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
    static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                            a54 = -212.0 / 729;
    static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                            a64 = 49.0 / 176, a65 = -5103.0 / 18656;
    static constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192,
                            b5 = -2187.0 / 6784, b6 = 11.0 / 84;
    static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920,
                            e5 = -17253.0 / 339200, e6 = 22.0 / 525, e7 = -1.0 / 40;
    const auto k1 = detail::rate(a);
    auto stage = [&](const Vec3<T>& dx, const Vec3<T>& dv) {
      return detail::rate(node_at(field, a.s, a, h, dx, dv, evals));
    };
    const auto k2 = stage(a21 * k1.dx, a21 * k1.dv);
    const auto k3 = stage(a31 * k1.dx + a32 * k2.dx, a31 * k1.dv + a32 * k2.dv);
    const auto k4 = stage(a41 * k1.dx + a42 * k2.dx + a43 * k3.dx,
                          a41 * k1.dv + a42 * k2.dv + a43 * k3.dv);
    const auto k5 = stage(a51 * k1.dx + a52 * k2.dx + a53 * k3.dx + a54 * k4.dx,
                          a51 * k1.dv + a52 * k2.dv + a53 * k3.dv + a54 * k4.dv);
    const auto k6 = stage(a61 * k1.dx + a62 * k2.dx + a63 * k3.dx + a64 * k4.dx + a65 * k5.dx,
                          a61 * k1.dv + a62 * k2.dv + a63 * k3.dv + a64 * k4.dv + a65 * k5.dv);
    const Vec3<T> dx = b1 * k1.dx + b3 * k3.dx + b4 * k4.dx + b5 * k5.dx + b6 * k6.dx;
    const Vec3<T> dv = b1 * k1.dv + b3 * k3.dv + b4 * k4.dv + b5 * k5.dv + b6 * k6.dv;
    RayNode<T> b = node_at(field, T(a.s + h), a, h, dx, dv, evals);
    const auto k7 = detail::rate(b);  // first same as last: the next step's k1
    const Vec3<T> ex = h * (e1 * k1.dx + e3 * k3.dx + e4 * k4.dx + e5 * k5.dx + e6 * k6.dx + e7 * k7.dx);
    const Vec3<T> ev = h * (e1 * k1.dv + e3 * k3.dv + e4 * k4.dv + e5 * k5.dv + e6 * k6.dv + e7 * k7.dv);
    *err_x = *err_v = 0.0;
    for (int i = 0; i < 3; ++i) {
      *err_x = std::max(*err_x, std::abs(value_of(ex[i])));
      *err_v = std::max(*err_v, std::abs(value_of(ev[i])));
    }
    return b;
  }

  static constexpr double kMinStep = 1e-12;   // relative to max_length: below it, accept
  static constexpr double kTinyStep = 1e-9;   // relative to max_length: 1000 in a row = singular
  double tol_, max_step_, max_length_, h_, carry_;
  const std::vector<LocalRegion>* regions_ = nullptr;
  bool hold_after_rejection_ = false;
  int min_steps_in_a_row_ = 0;
};

// Traces from x0 along the unit direction t0 with `stepper`, calling visit on each segment.
template <class T, class Field, class Stepper, class Visitor>
TraceEnd<T> march(const Field& field, const Vec3<T>& x0, const Vec3<T>& t0,
                  const TraceOptions& options, Stepper& stepper, Visitor&& visit) {
  TraceEnd<T> out;
  RayNode<T> node = make_node(field, T(0.0), x0, Vec3<T>::Zero().eval(), &out.evaluations);
  node.v = node.n * t0;  // launch with |v0| = n(x0) (ORACLES.md: not a unit v0)
  const double length = options.max_length;
  const Vec3d up(0.0, 1.0, 0.0);
  while (true) {
    const double remaining = length - value_of(node.s);
    if (remaining <= 1e-12 * length) {
      out.stop = TraceStop::kMaxLength;
      break;
    }
    poll_cancel(options.cancel);  // and the flags in force on this thread (core/parallel.h)
    if (out.steps >= options.max_steps) {
      throw_numerical("ray needed more than max_steps = ", options.max_steps, " steps");
    }
    RayNode<T> next = stepper.advance(field, node, remaining, &out.evaluations);
    ++out.steps;
    // A ray on the stop height whose step goes below it (launched down or level from the plane)
    // stops where it is, as the stratified tracer's; the crossing test below looks only for
    // crossings from above.
    if (options.stop_height && value_of(node.x.y()) == *options.stop_height &&
        value_of(next.x.y()) < *options.stop_height) {
      out.stop = TraceStop::kStopHeight;
      break;
    }
    bool stopped_at_height = false;
    if (options.stop_height &&
        value_of(node.x.y()) > *options.stop_height) {
      const PathSegment<T> segment(node, next);
      const T u = first_plane_crossing(segment, up, *options.stop_height);
      if (value_of(u) >= 0.0) {
        // The interpolant locates the crossing; a step of exactly that length from the segment's
        // start gives the integrator's own state there, and Newton on the height lands on it.
        T h = u * segment.length();
        for (int it = 0; it < 4; ++it) {
          next = stepper.step_fixed(field, node, h, &out.evaluations);
          const T miss = next.x.y() - T(*options.stop_height);
          const T rate_y = next.v.y() / next.n;
          if (std::abs(value_of(miss)) <= 1e-13 * (1.0 + std::abs(*options.stop_height)) ||
              value_of(rate_y) >= 0.0) {
            break;
          }
          h -= miss / rate_y;
        }
        stopped_at_height = true;
      }
    }
    if (!visit(node, next)) {
      out.stop = TraceStop::kVisitor;
      node = next;
      break;
    }
    node = next;
    if (stopped_at_height) {
      out.stop = TraceStop::kStopHeight;
      break;
    }
  }
  out.end = node;
  return out;
}

}  // namespace refracta
