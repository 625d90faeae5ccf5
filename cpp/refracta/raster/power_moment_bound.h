// The canonical-representation bound of moments.h (canonical_bound) for one fixed moment vector
// queried at many depths: what MBOIT needs per pixel (the same biased moments for every fragment
// of the pixel, MOMENTS.md 4.1 pass 2). The Hankel matrix B is factorised once, at construction;
// each query is then allocation-free:
//   c = B^-1 (1, z_f, .., z_f^n)   -- the kernel polynomial K(z_f, z) = sum_j c_j z^j,
//   its roots z_1 .. z_n            -- closed form for 4 moments (a quadratic), Laguerre's method
//                                      (exact for real-rooted polynomials) for 6 and 8,
//   the weights w_i = 1 / K(z_i, z_i), the Christoffel numbers of the canonical representation
//                                     (Akhiezer, "The classical moment problem", ch. 2; Peters et
//                                     al., JCGT 2017: its atoms are z_f and the roots of K(z_f, .)),
//                                     so no Vandermonde solve.
// The same results as canonical_bound (same pivot test for a singular B, same fallback
// L = 0, w0 = 1, same dropping of vanishing leading coefficients) to round-off;
// tests/raster/test_oit.py compares the two.
#pragma once

#include "refracta/raster/moments.h"

namespace refracta {

class PowerMomentBound {
 public:
  static constexpr int kMaxMoments = 8;
  // b holds b_0 .. b_m (b_0 = 1, already biased), m = 4, 6 or 8.
  PowerMomentBound(const double* b, int m);

  MomentBound at(double z_f) const;
  bool singular() const { return singular_; }  // every query returns the fallback

 private:
  // K(x, y) = v(x)^T B^-1 v(y) with v(x) = (1, x, .., x^n).
  double kernel_diagonal(double x) const;

  int n_ = 0;
  bool singular_ = true;
  double inverse_[kMaxMoments / 2 + 1][kMaxMoments / 2 + 1] = {};  // B^-1 (symmetric)
};

}  // namespace refracta
