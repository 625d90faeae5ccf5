// The real roots of a polynomial in an interval, none missed: the interval is cut where the
// derivative vanishes (its roots found the same way, down to a line), so the polynomial is
// monotone on each piece and has a root there exactly when its ends differ in sign; bisection
// finds it. Sampling at a fixed number of points (the earlier way) misses a dip through zero
// narrower than the spacing: a ray grazing the ground for 80 m in a 3 km step.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace refracta {

// sum_k c[k] x^k by Horner's rule.
template <size_t N>
double polynomial_value(const std::array<double, N>& c, double x) {
  double value = c[N - 1];
  for (size_t k = N - 1; k-- > 0;) value = value * x + c[k];
  return value;
}

// Whether sum_k c[k] x^k keeps one sign over [lo, hi], so has no root there: its range by Horner's
// rule in interval arithmetic (which can only widen it), held off 0 by far more than the rounding of
// any evaluation (Horner's error is below 2N ulps of sum_k |c[k]| |x|^k; the margin is 1e-12 of it).
template <size_t N>
bool keeps_sign(const std::array<double, N>& c, double lo, double hi) {
  double low = c[N - 1], high = c[N - 1], magnitude = std::abs(c[N - 1]);
  const double reach = std::max(std::abs(lo), std::abs(hi));
  for (size_t k = N - 1; k-- > 0;) {
    const double a = low * lo, b = low * hi, p = high * lo, q = high * hi;
    low = std::min({a, b, p, q}) + c[k];
    high = std::max({a, b, p, q}) + c[k];
    magnitude = magnitude * reach + std::abs(c[k]);
  }
  const double margin = 1e-12 * magnitude;
  return low > margin || high < -margin;
}

// Where sum_k c[k] x^k, monotone on [a, b] with f(a) = fa and f(b) of the other sign, changes sign:
// a bracket of adjacent doubles, as bisection alone closes (the two agree within the band of
// rounding around the root, a few ulps), and the end past a returned (or a double where f is 0).
// Each step takes Newton's point inside the bracket and probes one step beyond it: converging
// quadratically, Newton's error is far below its step, so the probe lands past the root and the
// bracket closes from both ends (about ten evaluations where bisection needs 53 + log2(1 / root)).
// Bisection wherever a step did not halve the bracket.
template <size_t N>
double sign_change(const std::array<double, N>& c, double a, double fa, double b) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double x0 = a, x1 = b;  // f(x0) has fa's sign, f(x1) not
  auto inside = [&](double x) { return x > x0 && x < x1; };
  auto keep = [&](double x, double f) {
    if ((f > 0.0) == (fa > 0.0)) x0 = x; else x1 = x;
  };
  double x = 0.5 * (x0 + x1);
  // Every step shrinks the bracket and at least every other one halves it: the cap is never
  // reached (halving alone splits the whole range of doubles in ~2100 steps).
  for (int it = 0; it < 4400 && inside(x); ++it) {
    const double width = x1 - x0;
    double f = c[N - 1], df = 0.0;
    for (size_t k = N - 1; k-- > 0;) df = df * x + f, f = f * x + c[k];
    if (f == 0.0) return x;
    keep(x, f);
    const double next = x - f / df;
    if (inside(next)) {
      const double step = std::max(std::abs(next - x), 2.0 * kEps * std::abs(next));
      const double probe = next + (next > x ? step : -step);
      if (inside(probe)) {
        const double fp = polynomial_value(c, probe);
        if (fp == 0.0) return probe;
        keep(probe, fp);
      }
    }
    x = inside(next) && x1 - x0 <= 0.5 * width ? next : 0.5 * (x0 + x1);
  }
  return x1;
}

// Roots found by polynomial_roots: at most N - 1, in increasing order.
template <size_t N>
struct PolynomialRoots {
  std::array<double, N> at{};  // the first `count` entries
  size_t count = 0;
};

// The roots in [lo, hi] of sum_k c[k] x^k (degree N - 1) where it changes sign or is exactly 0,
// in increasing order, each to the bisection's resolution (adjacent doubles). A root of even
// multiplicity that touches 0 without reaching it is not reported.
template <size_t N>
PolynomialRoots<N> polynomial_roots(const std::array<double, N>& c, double lo, double hi) {
  PolynomialRoots<N> out;
  // No sign change anywhere: every evaluation below would share one sign (the common case of a
  // path segment far from a plane), so nothing to find.
  if (keeps_sign(c, lo, hi)) return out;
  auto add = [&](double x) {
    if (out.count == 0 || out.at[out.count - 1] != x) out.at[out.count++] = x;
  };
  // lo, the derivative's roots inside (lo, hi) -- at most N - 2, as its degree is N - 2 -- and hi.
  std::array<double, N> cuts{};
  size_t cut_count = 0;
  cuts[cut_count++] = lo;
  if constexpr (N > 2) {
    std::array<double, N - 1> derivative{};
    for (size_t k = 1; k < N; ++k) derivative[k - 1] = double(k) * c[k];
    // A derivative that keeps its sign has no roots: the recursion would find none (above).
    const PolynomialRoots<N - 1> turns = polynomial_roots(derivative, lo, hi);
    for (size_t i = 0; i < turns.count; ++i) {
      if (turns.at[i] > cuts[cut_count - 1] && turns.at[i] < hi) cuts[cut_count++] = turns.at[i];
    }
  }
  if (hi > cuts[cut_count - 1] || cut_count == 1) cuts[cut_count++] = hi;
  double a = cuts[0], fa = polynomial_value(c, a);
  if (fa == 0.0) add(a);
  for (size_t i = 1; i < cut_count; ++i) {
    const double b = cuts[i], fb = polynomial_value(c, b);
    if (fb == 0.0) {
      add(b);
    } else if (fa != 0.0 && (fa > 0.0) != (fb > 0.0)) {
      add(sign_change(c, a, fa, b));
    }
    a = b, fa = fb;
  }
  return out;
}

}  // namespace refracta
