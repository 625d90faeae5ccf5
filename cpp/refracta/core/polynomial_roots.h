// The real roots of a polynomial in an interval, none missed: the interval is cut where the
// derivative vanishes (its roots found the same way, down to a line), so the polynomial is
// monotone on each piece and has a root there exactly when its ends differ in sign; bisection
// finds it. Sampling at a fixed number of points (the earlier way) misses a dip through zero
// narrower than the spacing: a ray grazing the ground for 80 m in a 3 km step.
#pragma once

#include <array>
#include <cstddef>

namespace refracta {

// sum_k c[k] x^k by Horner's rule.
template <size_t N>
double polynomial_value(const std::array<double, N>& c, double x) {
  double value = c[N - 1];
  for (size_t k = N - 1; k-- > 0;) value = value * x + c[k];
  return value;
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
      double x0 = a, x1 = b;  // monotone here: one sign change, kept between x0 and x1
      // 53 + log2(1 / root) halvings for a root in [0, 1] (86 at 1e-10); the cap only stops roots
      // below ~1e-44 from being resolved further, far below any length in a scene.
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (x0 + x1);
        if (mid <= x0 || mid >= x1) break;
        const double fm = polynomial_value(c, mid);
        if (fm == 0.0) {
          x0 = x1 = mid;
          break;
        }
        if ((fm > 0.0) == (fa > 0.0)) x0 = mid; else x1 = mid;
      }
      add(x1);
    }
    a = b, fa = fb;
  }
  return out;
}

}  // namespace refracta
