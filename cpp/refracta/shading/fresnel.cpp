// The hemispherical Fresnel reflectance by Gauss-Legendre quadrature (fresnel.h).
#include "refracta/shading/fresnel.h"

#include <array>

namespace refracta {

namespace {

constexpr int kLegendreOrder = 32;

// Nodes and weights of Gauss-Legendre quadrature on [-1, 1] by Newton's method on P_n.
struct Legendre {
  std::array<double, kLegendreOrder> x{}, w{};
  Legendre() {
    const int n = kLegendreOrder;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = 0.0;
        for (int j = 1; j <= n; ++j) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
        }
        dp = n * (z * p0 - p1) / (z * z - 1.0);
        const double step = p0 / dp;
        z -= step;
        if (std::abs(step) < 1e-15) break;
      }
      x[i] = z;
      w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

}  // namespace

double fresnel_diffuse_reflectance(double eta) {
  static const Legendre rule;
  // Below the critical cosine (eta < 1) F = 1 and contributes mu_c^2.
  const double mu_c = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.0;
  double sum = mu_c * mu_c;
  // mu = mu_c + (1 - mu_c) t^2 removes the square-root behaviour of F just above the critical angle.
  for (int i = 0; i < kLegendreOrder; ++i) {
    const double t = 0.5 * (1.0 + rule.x[i]);
    const double mu = mu_c + (1.0 - mu_c) * t * t, dmu_dt = 2.0 * (1.0 - mu_c) * t;
    sum += 0.5 * rule.w[i] * 2.0 * fresnel_dielectric(mu, eta) * mu * dmu_dt;
  }
  return sum;
}

namespace {

double checked_eta(double eta) {
  if (!(eta > 0.0) || !std::isfinite(eta)) throw_invalid("eta must be finite and > 0 (got ", eta, ")");
  return eta;
}

double checked_cos_i(double cos_i) {
  if (!(std::abs(cos_i) <= 1.0)) throw_invalid("cos_i must be in [-1, 1] (got ", cos_i, ")");
  return cos_i;
}

}  // namespace

double checked_fresnel_dielectric(double cos_i, double eta) {
  checked_eta(eta);
  return fresnel_dielectric(checked_cos_i(cos_i), eta);
}

double checked_fresnel_conductor(double cos_i, double eta, double k) {
  checked_eta(eta);
  if (!(k >= 0.0) || !std::isfinite(k)) throw_invalid("k must be finite and >= 0 (got ", k, ")");
  return fresnel_complex(checked_cos_i(cos_i), std::complex<double>(eta, k));
}

double checked_fresnel_diffuse_reflectance(double eta) { return fresnel_diffuse_reflectance(checked_eta(eta)); }

}  // namespace refracta
