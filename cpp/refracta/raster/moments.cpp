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

MomentBound canonical_bound(const std::vector<double>& b, double z_f) {
  const int m = int(b.size()) - 1;
  if (m < 2 || m % 2 != 0) throw_invalid("canonical_bound needs b_0 .. b_2n (got ", b.size(), " moments)");
  const int n = m / 2;
  MomentBound fallback{0.0, 1.0, true};
  Eigen::MatrixXd hankel(n + 1, n + 1);
  for (int j = 0; j <= n; ++j) {
    for (int k = 0; k <= n; ++k) hankel(j, k) = b[j + k];
  }
  if (!hankel.allFinite() || !std::isfinite(z_f)) return fallback;
  Eigen::VectorXd rhs(n + 1);
  for (int j = 0; j <= n; ++j) rhs[j] = std::pow(z_f, j);
  // 1. Solve B q = (1, z_f, .., z_f^n) (LDL^T; B must be positive definite).
  Eigen::LDLT<Eigen::MatrixXd> ldlt(hankel);
  const Eigen::VectorXd pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || pivots.minCoeff() <= 1e-14 * std::max(1.0, pivots.maxCoeff())) return fallback;
  const Eigen::VectorXd q = ldlt.solve(rhs);
  // 2. Roots of sum q_j z^j: the other support points. A vanishing leading coefficient means
  //    roots at infinity (weight 0): drop them.
  int degree = n;
  const double scale = q.cwiseAbs().maxCoeff();
  while (degree > 0 && std::abs(q[degree]) <= 1e-12 * scale) --degree;
  std::vector<double> support = {z_f};
  if (degree > 0) {
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
    for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
    for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -q[i] / q[degree];
    Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
    if (solver.info() != Eigen::Success) return fallback;
    for (int i = 0; i < degree; ++i) {
      const std::complex<double> root = solver.eigenvalues()[i];
      if (std::abs(root.imag()) > 1e-7 * (1.0 + std::abs(root.real()))) return fallback;
      support.push_back(root.real());
    }
  }
  // 3. Weights from sum_i w_i z_i^j = b_j, j = 0 .. (support size - 1) (Vandermonde).
  const int k = int(support.size());
  Eigen::MatrixXd vandermonde(k, k);
  Eigen::VectorXd moments(k);
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) vandermonde(j, i) = std::pow(support[i], j);
    moments[j] = b[j];
  }
  const Eigen::VectorXd w = vandermonde.fullPivLu().solve(moments);
  if (!w.allFinite()) return fallback;
  // 4. The bound: the mass strictly in front of z_f.
  MomentBound out;
  out.at_query = std::clamp(w[0], 0.0, 1.0);
  double lower = 0.0;
  for (int i = 1; i < k; ++i) {
    if (support[i] < z_f) lower += w[i];
  }
  out.lower = std::clamp(lower, 0.0, 1.0);
  return out;
}

double vsm_shadow(double b1, double b2, double z_f, double min_variance) {
  if (z_f <= b1) return 0.0;
  const double variance = std::max(b2 - b1 * b1, min_variance);
  const double d = z_f - b1;
  return std::clamp(1.0 - variance / (variance + d * d), 0.0, 1.0);
}

double hamburger_4msm(const std::array<double, 4>& b, double z_f) {
  const double b1 = b[0], b2 = b[1], b3 = b[2], b4 = b[3];
  // LDL^T of the 3x3 Hankel matrix (MOMENTS.md 2.3 step 2).
  const double d22 = b2 - b1 * b1;
  const double l32_d22 = b3 - b1 * b2;
  const double d33_d22 = (b4 - b2 * b2) * d22 - l32_d22 * l32_d22;
  if (!(d22 > 1e-12) || !(d33_d22 > 1e-24) || !std::isfinite(d33_d22)) {
    return vsm_shadow(b1, b2, z_f, 1e-12);  // singular: the two-moment bound is still a lower bound
  }
  const double l32 = l32_d22 / d22, d33 = d33_d22 / d22;
  // Solve B c = (1, z_f, z_f^2) (step 3).
  double y2 = z_f - b1;
  const double y3 = z_f * z_f - b2 - l32 * y2;
  y2 /= d22;
  const double c3 = y3 / d33;
  const double c2 = y2 - l32 * c3;
  const double c1 = 1.0 - b1 * c2 - b2 * c3;
  // Roots of c1 + c2 z + c3 z^2 (step 4), ordered.
  const double p = c2 / c3, q = c1 / c3;
  const double disc = p * p / 4.0 - q;
  if (!(disc >= 0.0) || !std::isfinite(disc)) return vsm_shadow(b1, b2, z_f, 1e-12);
  const double r = std::sqrt(disc);
  const double z2 = -p / 2.0 - r, z3 = -p / 2.0 + r;
  // Step 5 (paper Algorithm 3, with the corrected 1 - w at z_f).
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
  // Roots of the Hamburger solution inside [0, 1]?
  const double d22 = u[1] - u[0] * u[0];
  const double l32 = (u[2] - u[0] * u[1]) / d22;
  const double d33 = (u[3] - u[1] * u[1]) - (u[2] - u[0] * u[1]) * l32;
  double y2 = zf - u[0];
  const double y3 = zf * zf - u[1] - l32 * y2;
  y2 /= d22;
  const double c3 = y3 / d33, c2 = y2 - l32 * c3, c1 = 1.0 - u[0] * c2 - u[1] * c3;
  const double pp = c2 / c3, qq = c1 / c3, disc = pp * pp / 4 - qq;
  if (!(disc >= 0.0) || !std::isfinite(disc) || !(zf > 0.0 && zf < 1.0)) return s_hamburger;
  const double z2 = -pp / 2 - std::sqrt(disc), z3 = -pp / 2 + std::sqrt(disc);
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
