// The moment math shared by moment shadow maps and moment-based OIT (shared/MOMENTS.md).
// Canonical representation (Peters et al., JCGT 2017, Algorithm 1): for normalised power moments
// b_0 = 1, b_1 .. b_2n of a depth distribution and a query depth z_f, the distribution with n + 1
// atoms, one at z_f, that matches b_0 .. b_2n. Its mass strictly in front of z_f, L, is the sharp
// lower bound of Z(z < z_f) over all distributions with these moments; w0 (its mass at z_f) gives
// the upper bound L + w0. MSM returns L, MBOIT L + beta w0.
#pragma once

#include <array>
#include <complex>
#include <vector>

namespace refracta {

struct MomentBound {
  double lower = 0.0;     // L
  double at_query = 0.0;  // w0, the mass at z_f
  bool fallback = false;  // the Hankel matrix was singular or the roots not real: see below
};

// b holds b_0 .. b_2n (b_0 = 1; biased already). Fallback when B is not positive definite, a
// root is not real, or anything is not finite: lower = 1 if z_f > b_1 else 0... replaced by the
// caller's choice; here: L = 0, w0 = 1 (MBOIT then returns beta, exact for a single atom at z_f).
MomentBound canonical_bound(const std::vector<double>& b, double z_f);

// The same bound for trigonometric moments c_0 = 1, c_1 .. c_n = E[e^(i j phi)] of angles in
// [0, 2 pi - pi/10] (MBOIT, MOMENTS.md 4.3), at the query angle phi0: Toeplitz solve, roots on the
// unit circle; roots in the wrapping zone count partly in front (a linear ramp). Not clamped.
MomentBound trigonometric_bound(const std::vector<std::complex<double>>& c, double phi0);

// (1 - alpha) b + alpha b* on b_1 .. b_m.
std::vector<double> bias_moments(const std::vector<double>& b, double alpha, const std::vector<double>& target);

// Shadow intensity S = mass in front of z_f, from b_1..b_4 (biased), I3D 2015 Algorithm 3
// (Hamburger: support on the real line), clamped to [0, 1]; VSM when the Hankel matrix is singular.
double hamburger_4msm(const std::array<double, 4>& b, double z_f);
// Hausdorff 4MSM: support in [lo, hi] ([0, 1] or [-1, 1]); sharper than Hamburger when a root
// leaves the interval (MOMENTS.md 2.4).
double hausdorff_4msm(const std::array<double, 4>& b, double z_f, double lo, double hi);
// Variance shadow maps (Donnelly & Lauritzen 2006): 1 - Chebyshev-Cantelli bound.
double vsm_shadow(double b1, double b2, double z_f, double min_variance);

}  // namespace refracta
