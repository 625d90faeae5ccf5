// Quadrature along a ray that cannot turn (bouguer_branch.h).
#include "refracta/render/bouguer_branch.h"

#include <cmath>
#include <exception>

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

bool BouguerBranch::integrate(double ha, double hb, double min_sine, double* run, double* length) const {
  const double mid = 0.5 * (ha + hb), half = 0.5 * std::abs(hb - ha);
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
  *run = half * sum_run;
  *length = half * sum_length;
  return true;
}

}  // namespace refracta
