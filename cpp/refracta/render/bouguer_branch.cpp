// Quadrature along a ray that cannot turn (bouguer_branch.h).
#include "refracta/render/bouguer_branch.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>

namespace refracta {

namespace {

// 8-point Gauss-Legendre on [-1, 1]: positive nodes and their weights.
constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

}  // namespace

bool BouguerBranch::at(double h, double min_sine, double* n, double* dn, double* sin_e) const {
  try {
    field_.evaluate_height(h, n, dn);
  } catch (const std::exception&) {
    return false;
  }
  if (!(*n > 0.0) || !std::isfinite(*n) || !std::isfinite(*dn)) return false;
  const double c = beta_ / *n;
  *sin_e = c < 1.0 ? std::sqrt(1.0 - c * c) : 0.0;
  return *sin_e >= min_sine;
}

namespace {

// Halving depth of the adaptive integral: 2^-30 of a height range is below a micrometre for 1000 km.
constexpr int kMaxHalvings = 30;

}  // namespace

bool BouguerBranch::integrate(double ha, double hb, double min_sine, double* run, double* length,
                              double relative_tol, double absolute_tol) const {
  // One 8-point Gauss-Legendre panel.
  auto panel = [&](double a, double b, double* r, double* l) {
    const double mid = 0.5 * (a + b), half = 0.5 * std::abs(b - a);
    double sum_run = 0.0, sum_length = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (double sign : {-1.0, 1.0}) {
        double n, dn, s;
        if (!at(mid + sign * half * kNodes[i], min_sine, &n, &dn, &s)) return false;
        // cos e / sin e and 1 / sin e, with cos e = beta / n.
        sum_run += kWeights[i] * (beta_ / n) / s;
        sum_length += kWeights[i] / s;
      }
    }
    *r = half * sum_run;
    *l = half * sum_length;
    return true;
  };
  if (!(relative_tol > 0.0)) return panel(ha, hb, run, length);
  // The whole panel, its rates kept in path order (x from -1 to 1, as the ends ha, hb).
  double rate_run[10], rate_length[10], at_h[10];
  {
    const double mid = 0.5 * (ha + hb), half = 0.5 * (hb - ha);
    double sum_run = 0.0, sum_length = 0.0;
    at_h[0] = ha, at_h[9] = hb;
    for (int k = 0; k < 8; ++k) {
      const int i = k < 4 ? 3 - k : k - 4;
      at_h[k + 1] = mid + half * (k < 4 ? -kNodes[i] : kNodes[i]);
    }
    for (int k = 0; k < 10; ++k) {
      double n, dn, sine;
      if (!at(at_h[k], min_sine, &n, &dn, &sine)) return false;
      rate_run[k] = (beta_ / n) / sine, rate_length[k] = 1.0 / sine;
      if (k == 0 || k == 9) continue;
      const int i = k <= 4 ? 4 - k : k - 5;
      sum_run += kWeights[i] * rate_run[k];
      sum_length += kWeights[i] * rate_length[k];
    }
    *run = std::abs(half) * sum_run;
    *length = std::abs(half) * sum_length;
  }
  const double total_run = std::max(*run, 1e-300), total_length = std::max(*length, 1e-300);
  const double width = std::abs(hb - ha);
  // The whole panel is kept where the trapezoid rule over its nodes and both ends agrees with it
  // to the tolerance (the trapezoid's error is second order: their difference bounds the panel's
  // own error): a ray rising smoothly from the objects' tops (the cold sea's shadow rays, 165 m
  // to 7 km: the run to well under the 239 m a quarter pixel allows) costs 10 evaluations
  // instead of the whole panel's and its halves' 24. Elsewhere the halving below.
  {
    double trapezoid_run = 0.0, trapezoid_length = 0.0;
    for (int k = 0; k < 9; ++k) {
      const double gap = std::abs(at_h[k + 1] - at_h[k]);
      trapezoid_run += 0.5 * gap * (rate_run[k] + rate_run[k + 1]);
      trapezoid_length += 0.5 * gap * (rate_length[k] + rate_length[k + 1]);
    }
    if (std::abs(trapezoid_run - *run) <= std::max(relative_tol * total_run, absolute_tol) &&
        std::abs(trapezoid_length - *length) <= std::max(relative_tol * total_length, absolute_tol)) {
      return true;
    }
  }
  // Adaptive: halve a panel until its halves agree with it; the tolerance is shared out by width.
  std::function<bool(double, double, double, double, int, double*, double*)> refine =
      [&](double a, double b, double whole_run, double whole_length, int depth, double* r, double* l) {
        const double m = 0.5 * (a + b);
        double r1, l1, r2, l2;
        if (!panel(a, m, &r1, &l1) || !panel(m, b, &r2, &l2)) return false;
        const double fraction = std::abs(b - a) / width, share = fraction * relative_tol;
        const double absolute = fraction * absolute_tol;
        if (depth >= kMaxHalvings || (std::abs(r1 + r2 - whole_run) <= std::max(share * total_run, absolute) &&
                                      std::abs(l1 + l2 - whole_length) <= std::max(share * total_length, absolute))) {
          *r = r1 + r2, *l = l1 + l2;
          return true;
        }
        double ra, la, rb, lb;
        if (!refine(a, m, r1, l1, depth + 1, &ra, &la) || !refine(m, b, r2, l2, depth + 1, &rb, &lb)) return false;
        *r = ra + rb, *l = la + lb;
        return true;
      };
  return refine(ha, hb, *run, *length, 0, run, length);
}

bool BouguerBranch::integrate(double ha, double sin_a, double hb, double sin_b, double min_sine, Stretch* out) const {
  const double mid = 0.5 * (ha + hb), half = 0.5 * (hb - ha);
  // Samples in path order: a, the eight nodes, b.
  double h[10], sine[10], cos_e[10];
  h[0] = ha, sine[0] = sin_a, h[9] = hb, sine[9] = sin_b;
  double sum_run = 0.0, sum_length = 0.0;
  for (int k = 0; k < 8; ++k) {
    const int i = k < 4 ? 3 - k : k - 4;          // node index, from -1 towards +1
    const double x = k < 4 ? -kNodes[i] : kNodes[i];
    double n, dn;
    h[k + 1] = mid + half * x;
    if (!at(h[k + 1], min_sine, &n, &dn, &sine[k + 1])) return false;
    cos_e[k + 1] = beta_ / n;
    sum_run += kWeights[i] * cos_e[k + 1] / sine[k + 1];
    sum_length += kWeights[i] / sine[k + 1];
  }
  cos_e[0] = std::sqrt(std::max(0.0, 1.0 - sin_a * sin_a));
  cos_e[9] = std::sqrt(std::max(0.0, 1.0 - sin_b * sin_b));
  out->run = std::abs(half) * sum_run;
  out->length = std::abs(half) * sum_length;
  // The trapezoid rule over the same ten samples: it agrees with Gauss-Legendre to its own
  // (second-order) error where the rates are smooth, and differs by the layer's area where a
  // layer thinner than the node spacing sits between samples.
  double trapezoid_run = 0.0, trapezoid_length = 0.0, turning = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double gap = std::abs(h[k + 1] - h[k]);
    trapezoid_length += 0.5 * gap * (1.0 / sine[k + 1] + 1.0 / sine[k]);
    trapezoid_run += 0.5 * gap * (cos_e[k + 1] / sine[k + 1] + cos_e[k] / sine[k]);
    turning += std::abs(sine[k + 1] * cos_e[k] - cos_e[k + 1] * sine[k]);  // sin of the step in e
  }
  out->error = std::max(std::abs(trapezoid_run - out->run), std::abs(trapezoid_length - out->length));
  out->turning = turning;
  return true;
}

}  // namespace refracta
