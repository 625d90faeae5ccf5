// The rough dielectric interface of Walter et al. 2007 ("Microfacet Models for Refraction through
// Rough Surfaces", EGSR, eqs. 20-21) in pbrt-v4's DielectricBxDF / Mitsuba 3's roughdielectric form,
// over any isotropic or anisotropic microfacet distribution that offers D, G, sample_wm (a visible-
// normal sampler; an optional result where it can fail) and sampling_pdf (that sampler's density):
// microfacet.h's TrowbridgeReitz (GGX; RoughDielectric) and beckmann.h's Beckmann (Water).
//   reflection     f_r = D(h) G(wo, wi) F(wo.h) / (4 |cos_o cos_i|),
//   transmission   f_t = D(m) G (1 - F(wo.m)) |wi.m| |wo.m| / (|cos_i cos_o| (wi.m + wo.m / eta')^2),
//                  divided by eta'^2 when transporting radiance,
// with the generalised half vector m = normalize(eta' wi + wo), eta' = eta_t / eta_i from wo's side.
// The values are per channel: each of the four channels may have its own relative index (water's
// dispersion per hero wavelength or RGB channel); directions are sampled with one index,
// eta_sampling: visible normal, then reflection with probability F(wo.m), refraction otherwise.
#pragma once

#include "refracta/shading/fresnel.h"
#include "refracta/shading/material_util.h"

#include <optional>

namespace refracta {

template <class Distribution>
class RoughDielectricLobe final : public Bsdf {
 public:
  RoughDielectricLobe(const Spectrum& eta, double eta_sampling, const Distribution& distribution)
      : eta_(eta), eta_sampling_(eta_sampling), distribution_(distribution) {}

  Spectrum f(const Vec3d& wo, const Vec3d& wi, TransportMode mode) const override {
    Spectrum f = Spectrum::Zero();
    if (wo.z() * wi.z() > 0.0) {  // reflection: the half vector does not depend on the index
      double etap;
      Vec3d h;
      if (!half_vector(wo, wi, 1.0, &etap, &h)) return f;
      const double base = distribution_.D(h) * distribution_.G(wo, wi) / std::abs(4.0 * wi.z() * wo.z());
      for (int c = 0; c < kSpectrumSamples; ++c) f[c] = base * fresnel_dielectric(wo.dot(h), eta_[c]);
      return f;
    }
    for (int c = 0; c < kSpectrumSamples; ++c) f[c] = transmission(wo, wi, eta_[c], mode);
    return f;
  }

  double pdf(const Vec3d& wo, const Vec3d& wi, TransportMode) const override {
    double etap;
    Vec3d m;
    if (!half_vector(wo, wi, eta_sampling_, &etap, &m)) return 0.0;
    const double r = fresnel_dielectric(wo.dot(m), eta_sampling_);
    if (wo.z() * wi.z() > 0.0) return distribution_.sampling_pdf(wo, m) / (4.0 * std::abs(wo.dot(m))) * r;
    return distribution_.sampling_pdf(wo, m) * std::abs(wi.dot(m)) / sqr(wi.dot(m) + wo.dot(m) / etap) * (1.0 - r);
  }

  std::optional<BsdfSample> sample(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const override {
    if (wo.z() == 0.0) return std::nullopt;
    const std::optional<Vec3d> sampled = distribution_.sample_wm(wo, u);
    if (!sampled) return std::nullopt;
    const Vec3d& m = *sampled;
    BsdfSample s;
    if (uc < fresnel_dielectric(wo.dot(m), eta_sampling_)) {
      s.wi = reflect(wo, m);
      if (!same_hemisphere(wo, s.wi)) return std::nullopt;
      s.flags = kBsdfReflection | kBsdfGlossy;
    } else {
      double etap;
      if (!refract(wo, m, eta_sampling_, &etap, &s.wi) || same_hemisphere(wo, s.wi) || s.wi.z() == 0.0) return std::nullopt;
      s.flags = kBsdfTransmission | kBsdfGlossy;
      s.eta = etap;
    }
    s.pdf = pdf(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f(wo, s.wi, mode);
    s.weight = s.f * std::abs(s.wi.z()) / s.pdf;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfTransmission | kBsdfGlossy; }

  // The transmission lobe's f at one relative index (0 for pairs on one side).
  double transmission(const Vec3d& wo, const Vec3d& wi, double eta, TransportMode mode) const {
    double etap;
    Vec3d m;
    if (!half_vector(wo, wi, eta, &etap, &m)) return 0.0;
    const double F = fresnel_dielectric(wo.dot(m), eta);
    const double denominator = sqr(wi.dot(m) + wo.dot(m) / etap) * wi.z() * wo.z();
    double ft = distribution_.D(m) * (1.0 - F) * distribution_.G(wo, wi) * std::abs(wi.dot(m) * wo.dot(m) / denominator);
    if (mode == TransportMode::kRadiance) ft /= etap * etap;
    return ft;
  }

 private:
  static double sqr(double x) { return x * x; }
  // The generalised half vector for relative index eta on the normal's side; false for
  // configurations no microfacet produces (grazing directions, back-facing microfacets).
  static bool half_vector(const Vec3d& wo, const Vec3d& wi, double eta, double* etap, Vec3d* m) {
    const double cos_o = wo.z(), cos_i = wi.z();
    if (cos_o == 0.0 || cos_i == 0.0) return false;
    const bool reflection = cos_o * cos_i > 0.0;
    *etap = reflection ? 1.0 : (cos_o > 0.0 ? eta : 1.0 / eta);
    Vec3d h = wi * *etap + wo;
    if (h.squaredNorm() == 0.0) return false;
    h.normalize();
    if (h.z() < 0.0) h = -h;
    if (h.dot(wi) * cos_i < 0.0 || h.dot(wo) * cos_o < 0.0) return false;
    *m = h;
    return true;
  }
  Spectrum eta_;
  double eta_sampling_;
  Distribution distribution_;
};

}  // namespace refracta
