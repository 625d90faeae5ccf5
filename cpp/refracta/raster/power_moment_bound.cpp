// PowerMomentBound: the Hankel matrix factorised once, each query a kernel polynomial's real roots.
#include "refracta/raster/power_moment_bound.h"

#include "refracta/core/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

// B^-1 from the LDL^T of the (n+1) x (n+1) Hankel matrix, with canonical_bound's test for a
// singular or indefinite B (a pivot <= 1e-14 of the largest). False: singular.
template <int N>
bool invert_hankel(const double* b, double (*inverse)[PowerMomentBound::kMaxMoments / 2 + 1]) {
  Eigen::Matrix<double, N, N> hankel;
  for (int j = 0; j < N; ++j) {
    for (int k = 0; k < N; ++k) hankel(j, k) = b[j + k];
  }
  if (!hankel.allFinite()) return false;
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(hankel);
  const Eigen::Matrix<double, N, 1> pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || pivots.minCoeff() <= 1e-14 * std::max(1.0, pivots.maxCoeff())) return false;
  const Eigen::Matrix<double, N, N> inv = ldlt.solve(Eigen::Matrix<double, N, N>::Identity());
  if (!inv.allFinite()) return false;
  for (int j = 0; j < N; ++j) {
    for (int k = 0; k < N; ++k) inverse[j][k] = 0.5 * (inv(j, k) + inv(k, j));
  }
  return true;
}

// sum_j a_j x^j and its first two derivatives (Horner), degree d.
void evaluate(const double* a, int d, double x, double* p, double* dp, double* ddp) {
  *p = a[d], *dp = 0.0, *ddp = 0.0;
  for (int j = d - 1; j >= 0; --j) {
    *ddp = *ddp * x + 2.0 * *dp;
    *dp = *dp * x + *p;
    *p = *p * x + a[j];
  }
}

// The real roots of a_0 + a_1 x + a_2 x^2 (a_2 != 0), ascending; the numerically stable form
// (no cancellation between -a_1 and the square root). Complex roots whose imaginary part is
// below canonical_bound's tolerance count as a double root. False: complex roots.
bool quadratic_roots(double a0, double a1, double a2, double* r) {
  const double half_p = 0.5 * a1 / a2, q = a0 / a2;
  double disc = half_p * half_p - q;
  if (!(disc >= 0.0)) {
    if (!(std::sqrt(-disc) <= 1e-7 * (1.0 + std::abs(half_p)))) return false;
    disc = 0.0;
  }
  const double s = std::sqrt(disc);
  const double big = half_p > 0.0 ? -half_p - s : -half_p + s;  // the root of larger magnitude
  const double small = big != 0.0 ? q / big : 0.0;
  r[0] = std::min(big, small), r[1] = std::max(big, small);
  return std::isfinite(r[0]) && std::isfinite(r[1]);
}

// All roots of a real-rooted polynomial of degree d <= 4 (a_d != 0), in descending order found:
// Laguerre's method from above the Cauchy bound converges monotonically to the largest root of a
// polynomial with only real roots (Householder, "The numerical treatment of a single nonlinear
// equation", 1970, sec. 4.5); deflate and repeat, the last two from the quadratic; each root
// polished by one Newton step on the undeflated polynomial. False: no convergence or complex roots.
bool real_roots(const double* a, int d, double* roots) {
  double work[PowerMomentBound::kMaxMoments / 2 + 1];
  std::copy(a, a + d + 1, work);
  int degree = d, found = 0;
  double bound = 0.0;
  for (int j = 0; j < d; ++j) bound = std::max(bound, std::abs(a[j] / a[d]));
  double x = 1.0 + bound;  // above every root (Cauchy)
  while (degree > 2) {
    // Converged when the step is below 1e-13 of |x| (rounding in p keeps later steps at a few
    // ulps, so a tighter test can stall); one at 1e-9 after 80 iterations still counts.
    bool converged = false;
    double step = 0.0;
    for (int iteration = 0; iteration < 80; ++iteration) {
      double p, dp, ddp;
      evaluate(work, degree, x, &p, &dp, &ddp);
      if (p == 0.0) {
        converged = true;
        break;
      }
      const double g = dp / p, h = g * g - ddp / p;
      const double s = std::sqrt(std::max((degree - 1) * (degree * h - g * g), 0.0));
      const double denominator = g >= 0.0 ? g + s : g - s;
      if (denominator == 0.0 || !std::isfinite(denominator)) break;
      step = degree / denominator;
      x -= step;
      if (std::abs(step) <= 1e-13 * std::max(1.0, std::abs(x))) {
        converged = true;
        break;
      }
    }
    converged = converged || std::abs(step) <= 1e-9 * std::max(1.0, std::abs(x));
    if (!converged || !std::isfinite(x)) return false;
    roots[found++] = x;
    // Deflate: work / (z - x).
    double carry = work[degree];
    for (int j = degree - 1; j >= 0; --j) {
      const double next = work[j] + x * carry;
      work[j] = carry;
      carry = next;
    }
    --degree;
  }
  if (degree == 2) {
    if (!quadratic_roots(work[0], work[1], work[2], roots + found)) return false;
    found += 2;
  } else if (degree == 1) {
    roots[found++] = -work[0] / work[1];
  }
  for (int i = 0; i < found; ++i) {
    double p, dp, ddp;
    evaluate(a, d, roots[i], &p, &dp, &ddp);
    if (dp != 0.0 && std::isfinite(p / dp)) roots[i] -= p / dp;
    if (!std::isfinite(roots[i])) return false;
  }
  return true;
}

}  // namespace

PowerMomentBound::PowerMomentBound(const double* b, int m) {
  if (m != 4 && m != 6 && m != 8) throw_invalid("PowerMomentBound: moments must be 4, 6 or 8 (got ", m, ")");
  n_ = m / 2;
  singular_ = !(n_ == 2 ? invert_hankel<3>(b, inverse_) : n_ == 3 ? invert_hankel<4>(b, inverse_) : invert_hankel<5>(b, inverse_));
}

double PowerMomentBound::kernel_diagonal(double x) const {
  double v[kMaxMoments / 2 + 1], sum = 0.0;
  v[0] = 1.0;
  for (int j = 1; j <= n_; ++j) v[j] = v[j - 1] * x;
  for (int j = 0; j <= n_; ++j) {
    double row = 0.0;
    for (int k = 0; k <= n_; ++k) row += inverse_[j][k] * v[k];
    sum += v[j] * row;
  }
  return sum;
}

MomentBound PowerMomentBound::at(double z_f) const {
  const MomentBound fallback{0.0, 1.0, true};
  if (singular_ || !std::isfinite(z_f)) return fallback;
  // The kernel polynomial c = B^-1 v(z_f); K(z_f, z_f) = v(z_f) . c.
  double v[kMaxMoments / 2 + 1], c[kMaxMoments / 2 + 1];
  v[0] = 1.0;
  for (int j = 1; j <= n_; ++j) v[j] = v[j - 1] * z_f;
  double k_ff = 0.0, scale = 0.0;
  for (int j = 0; j <= n_; ++j) {
    c[j] = 0.0;
    for (int k = 0; k <= n_; ++k) c[j] += inverse_[j][k] * v[k];
    k_ff += v[j] * c[j];
    scale = std::max(scale, std::abs(c[j]));
  }
  // Vanishing leading coefficients are roots at infinity, with no weight (as canonical_bound).
  int degree = n_;
  while (degree > 0 && std::abs(c[degree]) <= 1e-12 * scale) --degree;
  double roots[kMaxMoments / 2];
  bool real = true;
  if (degree == 1) {
    roots[0] = -c[0] / c[1];
  } else if (degree == 2) {
    real = quadratic_roots(c[0], c[1], c[2], roots);  // 4 moments: the closed form
  } else if (degree > 2) {
    real = real_roots(c, degree, roots);
  }
  if (!real || !(k_ff > 0.0)) return fallback;
  // Christoffel numbers: the weight of atom z is 1 / K(z, z).
  MomentBound out;
  out.at_query = std::clamp(1.0 / k_ff, 0.0, 1.0);
  double lower = 0.0;
  for (int i = 0; i < degree; ++i) {
    if (roots[i] < z_f) lower += 1.0 / kernel_diagonal(roots[i]);
  }
  if (!std::isfinite(lower)) return fallback;
  out.lower = std::clamp(lower, 0.0, 1.0);
  return out;
}

}  // namespace refracta
