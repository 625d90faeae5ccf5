// The isotropic Beckmann microfacet distribution (Beckmann & Spizzichino 1963; Walter et al. 2007,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR, eqs. 25-27), used by the Water
// surface (water_surface.h) because the Cox-Munk slope statistics of the sea are Gaussian.
// Local frame: z = normal.
//
//   D(m) = exp(-tan^2 theta_m / alpha^2) / (pi alpha^2 cos^4 theta_m),   int D(m) cos theta_m dm = 1.
// In slope space (p, q) = (-m_x / m_z, -m_y / m_z) this is the isotropic Gaussian
// P(p, q) = D(m) cos^4 theta_m = exp(-(p^2 + q^2) / alpha^2) / (pi alpha^2), whose variance per axis is
// alpha^2 / 2: the TOTAL mean-square slope <p^2 + q^2> is alpha^2 (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), its slope distribution of the
// Beckmann surface; checked by quadrature in tests/shading/test_water_body.py). So Cox & Munk's
// total sigma^2 = sigma_u^2 + sigma_c^2 gives alpha = sigma directly.
//
// Smith's Lambda(w) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), a = 1 / (alpha tan theta), exact
// (Walter et al. eq. 27 before its rational approximation, which Mitsuba 3 uses: < 0.35 % apart in
// G1); masking-shadowing height-correlated, G2 = 1 / (1 + Lambda(wo) + Lambda(wi)), as refracta's
// GGX (microfacet.h; Mitsuba uses the separable G1 G1).
//
// Sampling: microfacet normals are drawn from the GGX distribution of visible normals of the same
// alpha (Heitz 2018, TrowbridgeReitz::sample_wm) as a proposal, and sampling_pdf() is that
// proposal's exact density: D_Beckmann / D_GGX = exp(-x) (1 + x)^2 with x = tan^2 theta / alpha^2 is
// at most 4 / e, so the weights f cos / pdf stay bounded (Beckmann's own visible-normal sampler,
// Heitz & d'Eon 2014, needs an iterative inverse erf).
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/shading/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace refracta {

// The isotropic Beckmann microfacet distribution: D, Lambda (exact, with erf), G1 and the
// height-correlated G. alpha^2 is the total mean-square slope. Directions: (N, 3) unit vectors.
class Beckmann {
 public:
  // The same floor as GGX's (microfacet.h): narrower lobes are beyond double-precision directions.
  static constexpr double kMinAlpha = TrowbridgeReitz::kMinAlpha;

  Beckmann() = default;
  explicit Beckmann(double alpha) : alpha_(std::max(alpha, kMinAlpha)), proposal_(alpha_, alpha_) {}

  double alpha() const { return alpha_; }

  // Microfacet normals per unit solid angle and unit area.
  double D(const Vec3d& m) const {
    if (!(m.z() > 0.0)) return 0.0;  // facets face out of the surface
    const double cos2 = m.z() * m.z();
    const double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
    const double a2 = alpha_ * alpha_;
    return std::exp(-tan2 / a2) / (kPi * a2 * cos2 * cos2);
  }

  // Smith's Lambda, exact.
  double lambda(const Vec3d& w) const {
    const double cos2 = w.z() * w.z();
    if (!(cos2 > 0.0)) return std::numeric_limits<double>::infinity();
    const double sin2 = std::max(0.0, 1.0 - cos2);
    if (sin2 == 0.0) return 0.0;
    const double a = std::sqrt(cos2 / sin2) / alpha_;  // 1 / (alpha tan theta)
    if (a > 26.0) return 0.0;                             // exp(-a^2) / a below 1e-296: Lambda is 0 in double
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
  }
  double G1(const Vec3d& w) const { return 1.0 / (1.0 + lambda(w)); }
  double G(const Vec3d& wo, const Vec3d& wi) const { return 1.0 / (1.0 + lambda(wo) + lambda(wi)); }

  // A microfacet normal (z > 0) for wo from the GGX visible-normal proposal, or nullopt where
  // Beckmann's D is 0 in double (tan^2 theta / alpha^2 > ~745: the proposal's tail beyond, e.g.,
  // 82 degrees at alpha = 0.25, ~0.1 % of its samples), and the density per solid angle of m of
  // the normals it returns (0 there too, so that pdf() is the density of what sample() produces).
  std::optional<Vec3d> sample_wm(const Vec3d& wo, const Vec2d& u) const {
    const Vec3d m = proposal_.sample_wm(wo, u);
    if (D(m) == 0.0) return std::nullopt;
    return m;
  }
  double sampling_pdf(const Vec3d& wo, const Vec3d& m) const { return D(m) > 0.0 ? proposal_.D_visible(wo, m) : 0.0; }

 private:
  double alpha_ = 0.1;
  TrowbridgeReitz proposal_{0.1, 0.1};
};

}  // namespace refracta
