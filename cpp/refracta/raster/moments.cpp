// Moment bounds: the generic canonical representation and the closed 4-moment forms.
#include "refracta/raster/moments.h"

#include "refracta/core/error.h"
#include "refracta/core/math.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace refracta {

std::vector<double> bias_moments(const std::vector<double>& b, double alpha, const std::vector<double>& target) {
  if (target.size() + 1 != b.size()) throw_invalid("bias vector must have ", b.size() - 1, " entries");
  std::vector<double> out = b;
  for (size_t j = 1; j < b.size(); ++j) out[j] = (1.0 - alpha) * b[j] + alpha * target[j - 1];
  return out;
}

namespace {

using Complex = std::complex<double>;
template <class S>
using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <class S>
using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

// Solves M x = rhs for a Hermitian positive definite M (the Hankel or Toeplitz moment matrix);
// false when M is singular or indefinite.
template <class S>
bool solve_positive_definite(const Matrix<S>& m, const Vector<S>& rhs, Vector<S>* x) {
  if (!m.allFinite() || !rhs.allFinite()) return false;
  Eigen::LDLT<Matrix<S>> ldlt(m);
  const Eigen::VectorXd pivots = ldlt.vectorD().real();
  if (ldlt.info() != Eigen::Success || pivots.minCoeff() <= 1e-14 * std::max(1.0, pivots.maxCoeff())) return false;
  *x = ldlt.solve(rhs);
  return x->allFinite();
}

// Roots of sum_j a_j z^j (companion matrix). Vanishing leading coefficients are roots at
// infinity, which carry no weight: they are dropped.
template <class S>
bool polynomial_roots(const Vector<S>& a, std::vector<Complex>* roots) {
  int degree = int(a.size()) - 1;
  const double scale = a.cwiseAbs().maxCoeff();
  while (degree > 0 && std::abs(a[degree]) <= 1e-12 * scale) --degree;
  roots->clear();
  if (degree == 0) return true;
  Eigen::MatrixXcd companion = Eigen::MatrixXcd::Zero(degree, degree);
  for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -Complex(a[i]) / Complex(a[degree]);
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(companion, false);
  if (solver.info() != Eigen::Success) return false;
  for (int i = 0; i < degree; ++i) roots->push_back(solver.eigenvalues()[i]);
  return true;
}

// Weights w with sum_i w_i support_i^j = moments_j, j = 0 .. support size - 1 (Vandermonde).
template <class S>
bool support_weights(const std::vector<S>& support, const std::vector<S>& moments, Vector<S>* w) {
  const int k = int(support.size());
  Matrix<S> vandermonde(k, k);
  Vector<S> rhs(k);
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) vandermonde(j, i) = std::pow(support[i], j);
    rhs[j] = moments[j];
  }
  *w = vandermonde.fullPivLu().solve(rhs);
  return w->allFinite();
}

// Monotone in the angle of (x, y) on the unit circle, range [-1, 7) (Peters' circleToParameter).
double circle_to_parameter(double x, double y) {
  double r = std::abs(y) - std::abs(x);
  r = x < 0.0 ? 2.0 - r : r;
  return y < 0.0 ? 6.0 - r : r;
}

}  // namespace

MomentBound canonical_bound(const std::vector<double>& b, double z_f) {
  const int m = int(b.size()) - 1;
  if (m < 2 || m % 2 != 0) throw_invalid("canonical_bound needs b_0 .. b_2n (got ", b.size(), " moments)");
  const int n = m / 2;
  const MomentBound fallback{0.0, 1.0, true};
  if (!std::isfinite(z_f)) return fallback;
  // 1. Solve B q = (1, z_f, .., z_f^n) with the Hankel matrix B = (b_{j+k}).
  Eigen::MatrixXd hankel(n + 1, n + 1);
  Eigen::VectorXd rhs(n + 1), q;
  for (int j = 0; j <= n; ++j) {
    for (int k = 0; k <= n; ++k) hankel(j, k) = b[j + k];
    rhs[j] = std::pow(z_f, j);
  }
  if (!solve_positive_definite<double>(hankel, rhs, &q)) return fallback;
  // 2. The roots of sum q_j z^j are the other support points; they must be real.
  std::vector<Complex> roots;
  if (!polynomial_roots<double>(q, &roots)) return fallback;
  std::vector<double> support = {z_f};
  for (const Complex& root : roots) {
    if (std::abs(root.imag()) > 1e-7 * (1.0 + std::abs(root.real()))) return fallback;
    support.push_back(root.real());
  }
  // 3. Their weights, and the mass strictly in front of z_f. The weight of atom z is the
  // Christoffel number 1 / K(z, z), K(z, z) = v(z)^T B^-1 v(z) (Akhiezer, "The classical moment
  // problem", ch. 2), equal to the Vandermonde solve's weights but well conditioned when a root
  // lies far outside the depth range (a near-vanishing leading coefficient: the Vandermonde
  // matrix then holds z^n ~ 1e16 and its solve loses every digit).
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(hankel);
  Eigen::VectorXd w(support.size());
  for (size_t i = 0; i < support.size(); ++i) {
    Eigen::VectorXd v(n + 1);
    for (int j = 0; j <= n; ++j) v[j] = std::pow(support[i], j);
    w[Eigen::Index(i)] = 1.0 / v.dot(ldlt.solve(v));
  }
  if (!w.allFinite()) return fallback;
  MomentBound out;
  out.at_query = std::clamp(w[0], 0.0, 1.0);
  double lower = 0.0;
  for (size_t i = 1; i < support.size(); ++i) {
    if (support[i] < z_f) lower += w[Eigen::Index(i)];
  }
  out.lower = std::clamp(lower, 0.0, 1.0);
  return out;
}

MomentBound trigonometric_bound(const std::vector<Complex>& c, double phi0) {
  constexpr double kWrap = kPi / 10.0;  // wrapping-zone angle theta
  const double p_b = circle_to_parameter(std::cos(2.0 * kPi - kWrap), std::sin(2.0 * kPi - kWrap));
  const double ramp_scale = 1.0 / (7.0 - p_b), ramp_offset = 1.0 - 7.0 / (7.0 - p_b);
  const MomentBound fallback{0.0, 1.0, true};
  const int n = int(c.size()) - 1;
  // 1. Toeplitz matrix M_jk = c_(j-k), c_(-k) = conj(c_k); solve M x = (1, u0, .., u0^n).
  Eigen::MatrixXcd toeplitz(n + 1, n + 1);
  Eigen::VectorXcd rhs(n + 1), x;
  const Complex u0 = std::polar(1.0, phi0);
  for (int j = 0; j <= n; ++j) {
    for (int k = 0; k <= n; ++k) toeplitz(j, k) = j >= k ? c[j - k] : std::conj(c[k - j]);
    rhs[j] = std::pow(u0, j);
  }
  if (!solve_positive_definite<Complex>(toeplitz, rhs, &x)) return fallback;
  // 2. Roots of sum conj(x_k) u^k, on the unit circle (normalised against round-off).
  std::vector<Complex> roots;
  if (!polynomial_roots<Complex>(x.conjugate(), &roots)) return fallback;
  std::vector<Complex> support = {u0};
  for (const Complex& root : roots) support.push_back(root / std::abs(root));
  // 3. Weights; roots before the query count in front, those in the wrapping zone partly.
  Eigen::VectorXcd w;
  if (!support_weights<Complex>(support, c, &w)) return fallback;
  const double p0 = circle_to_parameter(u0.real(), u0.imag());
  MomentBound out;
  out.at_query = w[0].real();
  for (size_t i = 1; i < support.size(); ++i) {
    const double p = circle_to_parameter(support[i].real(), support[i].imag());
    out.lower += w[i].real() * ((p < p0 ? 1.0 : 0.0) + std::clamp(p * ramp_scale + ramp_offset, 0.0, 1.0));
  }
  if (!std::isfinite(out.lower) || !std::isfinite(out.at_query)) return fallback;
  return out;
}

double vsm_shadow(double b1, double b2, double z_f, double min_variance) {
  if (z_f <= b1) return 0.0;
  const double variance = std::max(b2 - b1 * b1, min_variance);
  const double d = z_f - b1;
  return std::clamp(1.0 - variance / (variance + d * d), 0.0, 1.0);
}

namespace {

// The Hamburger 4MSM solution for b_1..b_4 at z_f (I3D 2015, MOMENTS.md 2.3 steps 2-4): the two
// support points z2 <= z3 besides z_f. False when the Hankel matrix is singular.
bool hamburger_roots(const std::array<double, 4>& b, double z_f, double* z2, double* z3) {
  const double b1 = b[0], b2 = b[1], b3 = b[2], b4 = b[3];
  // LDL^T of the 3x3 Hankel matrix.
  const double d22 = b2 - b1 * b1;
  const double l32_d22 = b3 - b1 * b2;
  const double d33_d22 = (b4 - b2 * b2) * d22 - l32_d22 * l32_d22;
  if (!(d22 > 1e-12) || !(d33_d22 > 1e-24) || !std::isfinite(d33_d22)) return false;
  const double l32 = l32_d22 / d22, d33 = d33_d22 / d22;
  // Solve B c = (1, z_f, z_f^2).
  double y2 = z_f - b1;
  const double y3 = z_f * z_f - b2 - l32 * y2;
  y2 /= d22;
  const double c3 = y3 / d33;
  const double c2 = y2 - l32 * c3;
  const double c1 = 1.0 - b1 * c2 - b2 * c3;
  // Roots of c1 + c2 z + c3 z^2, ordered.
  const double p = c2 / c3, q = c1 / c3;
  const double disc = p * p / 4.0 - q;
  if (!(disc >= 0.0) || !std::isfinite(disc)) return false;
  *z2 = -p / 2.0 - std::sqrt(disc);
  *z3 = -p / 2.0 + std::sqrt(disc);
  return true;
}

}  // namespace

double hamburger_4msm(const std::array<double, 4>& b, double z_f) {
  const double b1 = b[0], b2 = b[1];
  double z2, z3;
  // Singular: the two-moment bound is still a lower bound.
  if (!hamburger_roots(b, z_f, &z2, &z3)) return vsm_shadow(b1, b2, z_f, 1e-12);
  // Paper Algorithm 3, with the corrected 1 - w at z_f.
  double s;
  if (z_f <= z2) {
    s = 0.0;
  } else if (z_f <= z3) {
    s = (z_f * z3 - b1 * (z_f + z3) + b2) / ((z3 - z2) * (z_f - z2));
  } else {
    s = 1.0 - (z2 * z3 - b1 * (z2 + z3) + b2) / ((z_f - z2) * (z_f - z3));
  }
  return std::isfinite(s) ? std::clamp(s, 0.0, 1.0) : vsm_shadow(b1, b2, z_f, 1e-12);
}

double hausdorff_4msm(const std::array<double, 4>& b, double z_f, double lo, double hi) {
  // The Hamburger solution is feasible on [lo, hi] when its roots lie inside; otherwise the
  // 4-atom solution on {lo, z_f, z_free, hi} (MOMENTS.md 2.4), computed here for any interval by
  // mapping it to [0, 1].
  const double width = hi - lo;
  std::array<double, 4> u;  // moments of (z - lo) / width
  const double b1 = b[0], b2 = b[1], b3 = b[2], b4 = b[3];
  u[0] = (b1 - lo) / width;
  u[1] = (b2 - 2 * lo * b1 + lo * lo) / (width * width);
  u[2] = (b3 - 3 * lo * b2 + 3 * lo * lo * b1 - lo * lo * lo) / (width * width * width);
  u[3] = (b4 - 4 * lo * b3 + 6 * lo * lo * b2 - 4 * lo * lo * lo * b1 + lo * lo * lo * lo) / std::pow(width, 4);
  const double zf = (z_f - lo) / width;
  const double s_hamburger = hamburger_4msm(u, zf);
  double z2, z3;
  if (!hamburger_roots(u, zf, &z2, &z3) || !(zf > 0.0 && zf < 1.0)) return s_hamburger;
  if (z2 >= 0.0 && z3 <= 1.0) return s_hamburger;
  const double z_free = ((u[2] - u[1]) * zf + u[2] - u[3]) / ((u[1] - u[0]) * zf + u[1] - u[2]);
  const double w1f = zf > z_free ? 1.0 : 0.0;
  const double s = (u[1] - u[0] + (u[2] - u[0] - (z_free + 1) * (u[1] - u[0])) * (z_free - w1f - zf) /
                                      (zf * (zf - z_free))) /
                       (z_free - w1f) +
                   1.0 - u[0];
  return std::isfinite(s) ? std::clamp(s, 0.0, 1.0) : s_hamburger;
}

}  // namespace refracta
