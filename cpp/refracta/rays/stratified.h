// Exact curved rays in a field that depends on height only (double precision).
// In such a field the ray stays in its vertical plane and n(h) cos e = beta is constant
// (Bouguer's invariant; e = elevation), so along a branch where h is monotone
//   dr/dh = beta / sqrt(n^2 - beta^2),   ds/dh = n / sqrt(n^2 - beta^2)    (per |dh|),
// with r the horizontal distance. Branches end at turning heights n(h_t) = beta, where the ray
// reverses vertically; near them the substitution h = h_t + kappa u^2 removes the inverse square
// root singularity: dr/du = 2u beta / sqrt(n^2 - beta^2) stays finite. Both integrals use adaptive
// 15-point Gauss-Kronrod panels, so paths are exact up to the quadrature tolerance. Every panel end
// becomes a path node with exact position, direction (cos e = beta/n) and field, handed to the same
// segment visitor as the Runge-Kutta integrators.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/media/ior_range.h"
#include "refracta/rays/ray_node.h"
#include "refracta/rays/trace_options.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

namespace refracta {

namespace detail {

// 15-point Kronrod nodes on [-1, 1] (positive half, centre last), its weights, and the weights of
// the embedded 7-point Gauss rule (on nodes 1, 3, 5, 7).
constexpr double kGkNodes[8] = {0.991455371120813, 0.949107912342759, 0.864864423359769,
                                0.741531185599394, 0.586087235467691, 0.405845151377397,
                                0.207784955007898, 0.0};
constexpr double kGkWeights[8] = {0.022935322010529, 0.063092092629979, 0.104790010322250,
                                  0.140653259715525, 0.169004726639267, 0.190350578064785,
                                  0.204432940075298, 0.209482141084728};
constexpr double kGaussWeights[4] = {0.129484966168870, 0.279705391489277, 0.381830050505119,
                                     0.417959183673469};

}  // namespace detail

// A duct whose gap n* - beta at its maximum is below kDuctGap n is followed as a harmonic oscillation
// (StratifiedTracer::harmonic_duct): there n - beta keeps fewer than ~3 significant digits. Maxima of n
// are looked for within kDuctReach [m] of the ray.
constexpr double kDuctGap = 1e-11;
constexpr double kDuctReach = 10.0;
// A launch this close [m] to a turning height (ahead of it or behind) starts from it
// (StratifiedTracer::start_near_turning).
constexpr double kNearTurning = 1e-6;
// [m] the first scan step of a branch leaving a turning height (doubling from there).
constexpr double kTurningFirstStep = 1e-4;

template <class Field>
class StratifiedTracer {
 public:
  StratifiedTracer(const Field& field, const TraceOptions& options)
      : field_(field), options_(options), length_(options.max_length),
        spacing_(options.stratified_spacing()),
        scan_step_(std::min(1.0, spacing_)), uniform_above_(field.uniform_above()) {}

  template <class Visitor>
  TraceEnd<double> trace(const Vec3d& x0, const Vec3d& t0, Visitor&& visit) {
    out_ = TraceEnd<double>{};
    s_ = r_ = 0.0;
    reached_end_ = false;
    origin_ = x0;
    const double cos_e0 = std::hypot(t0.x(), t0.z()), sin_e0 = t0.y();
    horizontal_ = cos_e0 > 0.0 ? Vec3d(t0.x() / cos_e0, 0.0, t0.z() / cos_e0) : Vec3d(1, 0, 0);
    double n0, dn0;
    eval(x0.y(), &n0, &dn0);
    beta_ = n0 * cos_e0;
    // n0 - beta = n0 (1 - cos e0), written without cancellation.
    const double gap0 = n0 * sin_e0 * sin_e0 / (1.0 + cos_e0);
    launch_h_ = x0.y(), launch_gap_ = gap0, launch_slope_ = dn0;
    launch_slope_dr_ = cos_e0 > 0.0 ? sin_e0 / cos_e0 : 0.0;
    // Below every n the path can meet (with the margin of an elevation of 0.57 deg at the floor,
    // as the renderer's cannot-turn test), beta has no turning height: scan in whole panels.
    constexpr double kClearOfTurning = 0.99995;  // sqrt(1 - 0.01^2)
    scan_ = options_.ior_floor && beta_ < *options_.ior_floor * kClearOfTurning ? spacing_ : scan_step_;
    last_ = node(0.0, 0.0, x0.y(), n0, dn0, sin_e0);
    stopped_ = false;

    auto visitor = [&](const RayNode<double>& a, const RayNode<double>& b) { return visit(a, b); };
    visit_ = visitor;
    // At or below the stop height a path ends where it descends; a level one that the air bends
    // upward (n rising with height, a hot road's) leaves it, as rk45's does.
    const bool descends = sin_e0 < 0.0 || (sin_e0 == 0.0 && !(dn0 > 0.0));
    if (options_.stop_height && x0.y() <= *options_.stop_height && descends) {
      out_.stop = TraceStop::kStopHeight;
    } else if (sin_e0 == 0.0 && dn0 == 0.0) {
      straight_horizontal(n0);
    } else {
      double h = x0.y();
      bool turning = sin_e0 == 0.0;
      double direction = turning ? (dn0 > 0.0 ? 1.0 : -1.0) : (sin_e0 > 0.0 ? 1.0 : -1.0);
      if (turning) set_turning_point(h);
      // Launched nearly level by a shallow duct's maximum (toward which n rises): its oscillation.
      if (gap0 <= kDuctGap * n0 && dn0 != 0.0 && harmonic_duct(h, launch_slope_dr_, dn0 > 0.0 ? 1.0 : -1.0, true)) {
        out_.end = last_;
        return out_;
      }
      if (!turning && dn0 != 0.0 && launch_gap_ <= kNearTurning * std::abs(dn0)) {
        start_near_turning(h, direction, dn0, &h, &turning, &direction);
      }
      while (!done()) {
        if (!branch(&h, &turning, &direction)) break;
      }
    }
    out_.end = last_;
    return out_;
  }

 private:
  // One evaluation of n(h), dn/dh.
  void eval(double h, double* n, double* dn) {
    // Every unit of the tracer's work evaluates the field; a panel's refinement or a duct's scan
    // can run long between nodes, so Ctrl-C is polled here (every 64 evaluations: a CustomField's
    // take ~10 us each, a table's ~10 ns).
    if ((out_.evaluations & 63) == 0) poll_cancel(options_.cancel);
    field_.evaluate_height(h, n, dn);
    ++out_.evaluations;
    if (!usable_ior(*n) || !std::isfinite(*dn)) {
      throw_numerical("ray reached n = ", *n, " (dn/dh = ", *dn, ") at height ", h,
                      " m; the refractive index must be finite and > 0 (in [", kMinIor, ", ", kMaxIor, "]) along the path");
    }
  }

  RayNode<double> node(double s, double r, double h, double n, double dn, double sin_e) const {
    const double cos_e = std::min(beta_ / n, 1.0);
    RayNode<double> out;
    out.s = s;
    out.x = Vec3d(origin_.x() + r * horizontal_.x(), h, origin_.z() + r * horizontal_.z());
    out.n = n;
    out.v = n * (cos_e * horizontal_ + Vec3d(0.0, sin_e, 0.0));
    out.grad = Vec3d(0.0, dn, 0.0);
    return out;
  }

  bool done() const { return stopped_ || out_.stop != TraceStop::kMaxLength || reached_end_; }

  void emit(const RayNode<double>& next) {
    if (out_.steps >= options_.max_steps) {  // e.g. a long climb scanned metre by metre
      throw_numerical("stratified: the path needs more than max_steps = ", options_.max_steps, " nodes (at arc length ",
                      s_, " m of ", length_, " m, height ", next.x.y(), " m)");
    }
    if (!visit_(last_, next)) {
      out_.stop = TraceStop::kVisitor;
      stopped_ = true;
    }
    last_ = next;
    ++out_.steps;
  }

  void straight_horizontal(double n0) {
    const int64_t count = std::max<int64_t>(1, int64_t(std::ceil(length_ / spacing_)));  // <= max_steps
    for (int64_t i = 1; i <= count && !done(); ++i) {
      const double s = length_ * i / count;
      emit(node(s, s, origin_.y(), n0, 0.0, 0.0));
    }
    reached_end_ = true;
  }

  // Rising from the last node at or above uniform_above: n is constant there, the rest of the path
  // is the straight line along the last direction, exact as one node at max_length.
  void straight_to_end() {
    const double rest = length_ - s_, n = last_.n;
    const double sin_e = std::sqrt(std::max(n - beta_, 0.0) * (n + beta_)) / n, cos_e = std::min(beta_ / n, 1.0);
    s_ = length_;
    r_ += rest * cos_e;
    emit(node(s_, r_, last_.x.y() + rest * sin_e, n, 0.0, sin_e));
    reached_end_ = true;
  }

  // A ray about a maximum of n whose gap there, n* - beta, is within a few thousand ulps of round-off
  // (a duct too shallow for Bouguer's invariant to place the turning heights): dn/dh, accurate there,
  // can. Near the maximum h*, n = n* - k (h - h*)^2 / 2, and the invariant differentiated along r
  // gives h'' = n n'(h) / beta^2 = -omega^2 (h - h*), omega^2 = n k / beta^2: the ray oscillates
  // harmonically, h = h* + a cos(omega (r - r_t)) + (h'_t / omega) sin(omega (r - r_t)) from height
  // h_t = h* + a and slope h'_t = dh/dr, with ds/dr = n / beta = 1 to within that gap.
  // `dir`: the way toward the maximum. With `only_if_exact`, follows the ray only where n's cubic and
  // quartic terms (k measured over the oscillation's span against k at the maximum) move it by less
  // than tol over the rest of the path, and returns whether it did; without, it always follows it
  // (the ray turns within round-off: nothing else can) or throws NumericalError.
  bool harmonic_duct(double h_t, double slope_dr, double dir, bool only_if_exact) {
    auto slope = [&](double h) {
      double n, dn;
      eval(h, &n, &dn);
      return dn;
    };
    const double slope_t = slope(h_t);
    double near = h_t, far = h_t;
    bool bracketed = slope_t == 0.0;
    for (double width = 1e-9; width <= kDuctReach && !bracketed; width *= 4.0) {
      far = h_t + dir * width;
      bracketed = (slope(far) > 0.0) != (slope_t > 0.0);
      if (!bracketed) near = far;
    }
    if (!bracketed) {
      if (only_if_exact) return false;
      throw_numerical("stratified: cannot resolve a duct at h = ", h_t, " m (the ray turns back and forth within "
                      "n's round-off, but no maximum of n lies within ", kDuctReach, " m; trace='rk45' follows it)");
    }
    double lo = near, hi = far;  // slope(lo) has slope_t's sign
    for (int it = 0; it < 200 && std::abs(hi - lo) > 1e-15 * (1.0 + std::abs(lo)); ++it) {
      const double mid = 0.5 * (lo + hi);
      ((slope(mid) > 0.0) == (slope_t > 0.0) ? lo : hi) = mid;
    }
    const double h_max = 0.5 * (lo + hi), offset = h_t - h_max;
    const double k = (slope(h_max - 1e-6) - slope(h_max + 1e-6)) / 2e-6;
    double n_max, dn_max;
    eval(h_max, &n_max, &dn_max);
    if (!(k > 0.0)) {
      if (only_if_exact) return false;
      throw_numerical("stratified: cannot resolve a duct at h = ", h_t, " m (n's maximum at ", h_max,
                      " m is flat to round-off; trace='rk45' follows it)");
    }
    const double omega = std::sqrt(n_max * k) / beta_;
    const double amplitude = std::hypot(offset, slope_dr / omega);
    if (only_if_exact) {
      if (0.5 * k * amplitude * amplitude > kDuctGap * n_max) return false;  // Bouguer resolves it
      // k over the span, each side: a quartic term changes omega, a cubic one shifts the centre.
      const double span = std::max(amplitude, 1e-6);
      const double k_above = -slope(h_max + span) / span, k_below = slope(h_max - span) / span;
      const double stray = amplitude * (std::abs(0.5 * (k_above + k_below) / k - 1.0) * omega * (length_ - s_) +
                                        std::abs(k_above - k_below) / k);
      if (!(stray <= options_.tol)) return false;
    }
    const double r_t = r_, s_t = s_;
    const int64_t count = std::max<int64_t>(1, int64_t(std::ceil((length_ - s_t) / spacing_)));
    for (int64_t i = 1; i <= count && !done(); ++i) {
      s_ = s_t + (length_ - s_t) * i / count;
      r_ = r_t + (s_ - s_t);
      const double phase = omega * (r_ - r_t), c = std::cos(phase), sn = std::sin(phase);
      const double h = h_max + offset * c + slope_dr / omega * sn, dh_dr = -offset * omega * sn + slope_dr * c;
      double n, dn;
      eval(h, &n, &dn);
      emit(node(s_, r_, h, n, dn, dh_dr / std::sqrt(1.0 + dh_dr * dh_dr)));
    }
    reached_end_ = true;
    return true;
  }

  // --- the integrand in either variable -------------------------------------------------------
  // A panel variable w maps to a height: plain panels h = w; u-panels h = centre + side w^2 around
  // a turning height. rates() gives dr/dw, ds/dw (per |dw|) and n - beta at w.
  struct Variable {
    bool substituted = false;
    double centre = 0.0, side = 1.0;  // for u-panels
    // A height where n - beta is known accurately (the launch point or a turning height), and
    // dn/dh there: n - beta nearby is taken from it when the plain difference loses digits.
    double ref_h = 0.0, ref_gap = 0.0, ref_slope = 0.0;
    double height(double w) const { return substituted ? centre + side * w * w : w; }
  };

  // n - beta at height h (n, dn there), from var's reference where the plain difference loses digits;
  // dh: h - var.ref_h where the caller knows it more exactly than the difference of the two.
  double gap_at(const Variable& var, double h, double n, double dn, std::optional<double> exact_dh = std::nullopt) {
    double d = n - beta_;
    if (d < 1e-6 * n) {
      // n - beta is a difference of two numbers near 1 (absolute error ~4e-16): below 1e-6 it
      // keeps fewer than 10 digits. ref_gap + (n(h) - n(ref)) with the integral of dn/dh by
      // Simpson's rule does not cancel; its error is below the trapezoid-midpoint discrepancy.
      // Take whichever error is smaller.
      double n_mid, dn_mid;
      const double dh = exact_dh ? *exact_dh : h - var.ref_h;
      eval(var.ref_h + 0.5 * dh, &n_mid, &dn_mid);
      const double simpson_error = std::abs(dh * (var.ref_slope - 2.0 * dn_mid + dn)) / 12.0;
      if (simpson_error < 4e-16 * n) d = dh / 6.0 * (var.ref_slope + 4.0 * dn_mid + dn) + var.ref_gap;
    }
    return d;
  }

  // In a u-panel about a turning height, h - h_t is side w^2 exactly: near h_t the height itself
  // rounds to h_t (its ulp, 1.4e-14 m at 100 m, is w^2 for w ~ 1e-7), where n - beta would be 0.
  static std::optional<double> exact_offset(const Variable& var, double w) {
    if (var.substituted && var.ref_h == var.centre) return var.side * w * w;
    return std::nullopt;
  }

  void rates(const Variable& var, double w, double* dr, double* ds, double* gap) {
    const double h = var.height(w);
    double n, dn;
    eval(h, &n, &dn);
    const double d = gap_at(var, h, n, dn, exact_offset(var, w));
    *gap = d;
    const double q = std::sqrt(std::max(d, 1e-300) * (n + beta_));
    const double jacobian = var.substituted ? 2.0 * std::abs(w) : 1.0;
    *dr = jacobian * beta_ / q;
    *ds = jacobian * n / q;
  }

  struct PanelSums {
    double r = 0, s = 0, error = 0, min_gap = 1e300;
  };

  PanelSums gauss_kronrod(const Variable& var, double wa, double wb) {
    const double half = 0.5 * std::abs(wb - wa), mid = 0.5 * (wa + wb);
    PanelSums sums;
    double gauss_r = 0, gauss_s = 0;
    for (int i = 0; i < 8; ++i) {
      const int signs = i == 7 ? 1 : 2;
      for (int k = 0; k < signs; ++k) {
        const double w = mid + (k ? -1 : 1) * half * detail::kGkNodes[i];
        double dr, ds, gap;
        rates(var, w, &dr, &ds, &gap);
        sums.min_gap = std::min(sums.min_gap, gap);
        sums.r += detail::kGkWeights[i] * dr;
        sums.s += detail::kGkWeights[i] * ds;
        if (i % 2 == 1) {
          gauss_r += detail::kGaussWeights[i / 2] * dr;
          gauss_s += detail::kGaussWeights[i / 2] * ds;
        }
      }
    }
    sums.r *= half, sums.s *= half;
    sums.error = half * std::max(std::abs(sums.r / half - gauss_r), std::abs(sums.s / half - gauss_s));
    return sums;
  }

  // Integrates the panel [wa, wb] adaptively and emits its nodes in path order. Returns false if
  // a turning point lies inside (n <= beta at a quadrature node): the caller shortens the panel.
  bool integrate(const Variable& var, double wa, double wb, double direction, int depth = 0) {
    if (done()) return true;
    const PanelSums sums = gauss_kronrod(var, wa, wb);
    if (sums.min_gap <= 0.0 && !var.substituted) return false;
    // About a turning height n - beta grows away from it; a negative gap there means the turning
    // height taken (one within n's round-off of beta) is not the ray's: refuse rather than return
    // a path of that integral's poles.
    if (sums.min_gap < 0.0 || !std::isfinite(sums.s)) {
      throw_numerical("stratified: lost the turning height near h = ", var.centre, " m (n - beta there is within n's "
                      "round-off over more than ", kDuctReach, " m); trace='rk45' follows the ray");
    }
    const bool too_long = sums.s > spacing_;
    // Error per unit length, floored at what round-off in n - beta allows (a relative 1e-16 of n
    // over the smallest gap): asking for less only splits panels to chase noise.
    const double noise = 2.2e-16 * sums.s * (beta_ + 1.0) / std::max(sums.min_gap, 1e-300);
    const bool inaccurate =
        sums.error > std::max(options_.tol * std::max(sums.s / length_, 1e-6), noise);
    const bool splittable = depth < 30 && std::abs(wb - wa) > 1e-12 * (1 + std::abs(wa));
    // Held to tol between the nodes too, or to the positions' own round-off where that is coarser
    // (a path far from the origin): beyond it the halves would only split on noise.
    const bool loose = options_.hold_between_nodes && splittable && !too_long && !inaccurate &&
                       s_ + sums.s < length_ &&
                       interpolation_error(var, wa, wb, direction, sums) >
                           std::max(options_.between_nodes ? options_.between_nodes->at(s_) : options_.tol,
                                    1e-15 * (last_.x.norm() + sums.s));
    if ((too_long || inaccurate || loose) && splittable) {
      const double mid = 0.5 * (wa + wb);
      if (!integrate(var, wa, mid, direction, depth + 1)) return false;
      return integrate(var, mid, wb, direction, depth + 1);
    }
    if (s_ + sums.s >= length_) {
      finish_inside(var, wa, wb, direction, sums);
      return true;
    }
    s_ += sums.s;
    r_ += sums.r;
    emit_at(var, wb, direction);
    return true;
  }

  // How far the path between the nodes a panel [wa, wb] would end on lies from what is read between
  // them (PathSegment's quintic through their positions, directions and curvatures: crossings,
  // sample, the renderers' chords), at the panel's middle: the panels' quadrature alone left 75 m
  // between nodes across a hot road's layer, 1.4e-4 m off the path at tol 1e-6.
  double interpolation_error(const Variable& var, double wa, double wb, double direction, const PanelSums& whole) {
    const double mid = 0.5 * (wa + wb);
    const PanelSums half = gauss_kronrod(var, wa, mid);
    if (!(half.min_gap > 0.0) || !(whole.s > 0.0)) return 0.0;
    const RayNode<double> b = node_at(var, wb, direction, s_ + whole.s, r_ + whole.r);
    const RayNode<double> m = node_at(var, mid, direction, s_ + half.s, r_ + half.r);
    return (PathSegment<double>(last_, b).position(half.s / whole.s) - m.x).norm();
  }

  // The node at var's w, s and r given.
  RayNode<double> node_at(const Variable& var, double w, double direction, double s, double r) {
    const double h = var.height(w);
    double n, dn;
    eval(h, &n, &dn);
    const double gap = gap_at(var, h, n, dn, exact_offset(var, w));
    return node(s, r, h, n, dn, direction * std::sqrt(std::max(gap, 0.0) * (n + beta_)) / n);
  }

  // A node at var's w: its direction from n - beta as the panels integrate it (gap_at), so that
  // beside a turning height, where the plain difference is round-off, the node's slope is the path's.
  void emit_at(const Variable& var, double w, double direction) { emit(node_at(var, w, direction, s_, r_)); }

  // The path reaches max_length inside [wa, wb]: find w with s(w) = max_length by Newton.
  void finish_inside(const Variable& var, double wa, double wb, double direction,
                     const PanelSums& whole) {
    const double target = length_ - s_;
    double w = wa + (wb - wa) * std::clamp(target / whole.s, 0.0, 1.0);
    PanelSums part;
    for (int it = 0; it < 30; ++it) {
      part = gauss_kronrod(var, wa, w);
      const double residual = part.s - target;
      if (std::abs(residual) <= 1e-3 * options_.tol) break;
      double dr, ds, gap;
      rates(var, w, &dr, &ds, &gap);
      const double sign = wb > wa ? 1.0 : -1.0;
      const double next = w - sign * residual / ds;
      w = sign > 0 ? std::clamp(next, wa, wb) : std::clamp(next, wb, wa);
    }
    s_ = length_;
    r_ += part.r;
    emit_at(var, w, direction);
    reached_end_ = true;
  }

  // Root of n(h) = beta in (h_pos, h_neg], g(h_pos) > 0 >= g(h_neg): Newton kept in the bracket.
  // The gap from var's reference where n - beta loses digits (gap_at): a near-level launch's whole
  // gap can lie below n's round-off.
  double turning_height(const Variable& var, double h_pos, double h_neg) {
    double lo = h_pos, hi = h_neg, h = 0.5 * (lo + hi);
    for (int it = 0; it < 100 && std::abs(hi - lo) > 1e-13 * (1.0 + std::abs(h)); ++it) {
      double n, dn;
      eval(h, &n, &dn);
      const double g = gap_at(var, h, n, dn);
      if (g == 0.0) break;
      if (g > 0.0) lo = h; else hi = h;
      const double newton = dn != 0.0 ? h - g / dn : h;
      const bool inside = (newton - lo) * (newton - hi) < 0.0;
      h = inside ? newton : 0.5 * (lo + hi);
    }
    return h;
  }

  // n - beta is zero at a turning height by definition; the root finder's residual is round-off,
  // and carrying it would swamp n(h) - n(h_t) right next to h_t.
  void set_turning_point(double h_t) {
    double n, dn;
    eval(h_t, &n, &dn);
    turning_gap_ = 0.0;
    turning_slope_ = dn;
  }

  // A launch within kNearTurning of a turning height h_t (n - beta = |dn/dh| |h - h_t| to first
  // order): a scan from it would meet the inverse square root singularity right beside the start,
  // which the panels' halving cannot isolate (and n - beta there is below n's round-off). The path
  // near h_t in the u-substitution instead: ahead (n falls along the motion) the ray reaches h_t
  // and turns there; behind (n rises) it left h_t, and goes on from the launch's u to the turning
  // branch's first step (1e-4 m from h_t). Updates *h, *turning and *direction for the scan.
  void start_near_turning(double h0, double motion, double dn0, double* h, bool* turning, double* direction) {
    const bool ahead = motion * dn0 < 0.0;
    Variable launch;
    launch.ref_h = launch_h_, launch.ref_gap = launch_gap_, launch.ref_slope = launch_slope_;
    double ht = h0 + (ahead ? motion : -motion) * launch_gap_ / std::abs(dn0);
    for (int it = 0; it < 4; ++it) {  // Newton on the exact gap from the linear estimate
      double n, dn;
      eval(ht, &n, &dn);
      if (dn == 0.0) break;
      ht -= gap_at(launch, ht, n, dn) / dn;
    }
    set_turning_point(ht);
    if (ahead) {
      integrate_near_turning(ht, h0, true, motion);
      last_.v = last_.n * Vec3d(last_.v.x(), 0.0, last_.v.z()).normalized();
      *h = ht, *turning = true, *direction = -motion;
      return;
    }
    Variable var;
    var.substituted = true;
    var.centre = ht, var.side = motion;
    var.ref_h = ht, var.ref_gap = turning_gap_, var.ref_slope = turning_slope_;
    integrate(var, std::sqrt(std::abs(h0 - ht)), std::sqrt(kTurningFirstStep), motion);
    *h = ht + motion * kTurningFirstStep, *turning = false, *direction = motion;
  }

  // u-panel from height ha to the turning height ht (towards = true), or from ht out to hb.
  bool integrate_near_turning(double ht, double h_other, bool towards, double direction) {
    Variable var;
    var.substituted = true;
    var.centre = ht;
    var.side = h_other > ht ? 1.0 : -1.0;
    var.ref_h = ht, var.ref_gap = turning_gap_, var.ref_slope = turning_slope_;
    const double u = std::sqrt(std::abs(h_other - ht));
    return towards ? integrate(var, u, 0.0, direction) : integrate(var, 0.0, u, direction);
  }

  // Follows one monotone branch from *h in *direction; on reaching a turning height updates the
  // state for the next branch and returns true.
  bool branch(double* h_start, bool* turning_start, double* direction) {
    const double dir = *direction;
    double h_prev = *h_start, delta = *turning_start ? kTurningFirstStep : scan_;
    bool from_turning = *turning_start;
    const double start_turning_gap = turning_gap_, start_turning_slope = turning_slope_;
    Variable plain;
    if (from_turning) {
      plain.ref_h = *h_start, plain.ref_gap = turning_gap_, plain.ref_slope = turning_slope_;
    } else {
      plain.ref_h = launch_h_, plain.ref_gap = launch_gap_, plain.ref_slope = launch_slope_;
    }
    for (int iteration = 0; !done(); ++iteration) {
      if (iteration > 10'000'000) throw_numerical("stratified: no progress near h = ", h_prev, " m");
      if (dir > 0.0 && h_prev >= uniform_above_ && !from_turning) {  // uniform above: straight on
        straight_to_end();
        return false;
      }
      const double budget = length_ - s_ + 1e-9;
      double h_next = h_prev + dir * std::min(delta, budget);
      if (dir > 0.0 && h_prev < uniform_above_ && h_next > uniform_above_) h_next = uniform_above_;
      bool at_stop = false;
      if (dir < 0.0 && options_.stop_height && h_next <= *options_.stop_height) {
        h_next = *options_.stop_height;
        at_stop = true;
      }
      double n_next, dn_next;
      eval(h_next, &n_next, &dn_next);
      // From the launch's or the turning point's exact gap where n - beta loses digits: a ray
      // launched within 4.5e-8 rad of level has n - beta ~1e-15 all along in uniform air.
      const double gap_next = gap_at(plain, h_next, n_next, dn_next);
      // Within round-off of beta (8 ulps of n) where n falls along the motion: the turning height
      // is here, to within noise / |dn/dh|; scanning on would creep toward it forever.
      const bool at_turning =
          gap_next > 0.0 && gap_next <= 8 * 2.2e-16 * n_next && dir * dn_next < 0.0 && !from_turning;
      if (gap_next <= 0.0 || at_turning) {
        if (from_turning) {  // a second turning point within one scan step: look closer
          if (delta < 1e-12) {
            harmonic_duct(*h_start, 0.0, dir, false);
            return false;
          }
          delta *= 0.25;
          continue;
        }
        const double ht = at_turning ? h_next : turning_height(plain, h_prev, h_next);
        set_turning_point(ht);
        if (!integrate_near_turning(ht, h_prev, true, dir)) {
          delta *= 0.25;
          continue;
        }
        if (done()) return false;
        *h_start = ht;
        *turning_start = true;
        *direction = -dir;
        last_.v = last_.n * Vec3d(last_.v.x(), 0.0, last_.v.z()).normalized();
        return true;
      }
      bool ok;
      if (from_turning) {
        turning_gap_ = start_turning_gap, turning_slope_ = start_turning_slope;
        ok = integrate_near_turning(*h_start, h_next, false, dir);
      } else {
        ok = integrate(plain, h_prev, h_next, dir);
      }
      if (!ok) {  // a turning point hides inside the panel
        delta *= 0.25;
        continue;
      }
      if (done()) return false;
      if (at_stop) {
        out_.stop = TraceStop::kStopHeight;
        return false;
      }
      h_prev = h_next;
      from_turning = false;
      // Next scan step: approaching a turning point (n falling along the motion), aim 1.5x past
      // its linear prediction so it is bracketed; otherwise grow the step.
      delta = std::min(scan_, 2.0 * delta);
      if (dir * dn_next < 0.0) delta = std::min(delta, std::max(1.5 * gap_next / std::abs(dn_next), 1e-9));
    }
    return false;
  }

  const Field& field_;
  const TraceOptions& options_;
  double length_, spacing_, scan_step_;
  double scan_ = 1.0;  // this path's scan step [m]: scan_step_, or spacing_ when it cannot turn
  Vec3d origin_, horizontal_;
  double beta_ = 0.0, s_ = 0.0, r_ = 0.0;
  double turning_gap_ = 0.0, turning_slope_ = 0.0;
  double launch_h_ = 0.0, launch_gap_ = 0.0, launch_slope_ = 0.0;
  double launch_slope_dr_ = 0.0;  // dh/dr at the launch: tan of its elevation
  bool stopped_ = false, reached_end_ = false;
  RayNode<double> last_;
  double uniform_above_;  // the field's: n is constant above it [m]
  TraceEnd<double> out_;
  std::function<bool(const RayNode<double>&, const RayNode<double>&)> visit_;
};

}  // namespace refracta
