// Smooth and rough conductors (shared/SHADING.md section 3). The complex index eta + i k of the
// metal (relative to vacuum, divided by the outside medium's index at the hit) gives the exact
// unpolarised Fresnel reflectance (fresnel_complex); with eta and k unset the surface is a
// perfect reflector, F = 1. Two-sided.
//   Conductor(): a perfect mirror, f = F delta(wi - reflect(wo)) / |cos theta_i| (the lecture's
//     f = K_s delta / cos theta); sample() returns the mirror direction with weight F.
//   RoughConductor(alpha_u, alpha_v): Trowbridge-Reitz (GGX) reflection (microfacet.h),
//     f = D(h) G(wo, wi) F(wo.h) / (4 cos theta_o cos theta_i), height-correlated G, sampled by
//     visible normals, pdf = D_wo(h) / (4 |wo.h|).
#pragma once

#include "refracta/shading/fresnel.h"
#include "refracta/shading/material_util.h"
#include "refracta/shading/microfacet.h"

#include <optional>

namespace refracta {

// Fresnel of a conductor, or F = 1 when `perfect`.
struct ConductorFresnel {
  bool perfect = true;
  Spectrum eta = Spectrum::Ones(), k = Spectrum::Zero();
  Spectrum operator()(double cos_i) const { return perfect ? Spectrum(Spectrum::Ones()) : fresnel_complex(cos_i, eta, k); }
};

class ConductorBsdf final : public TwoSidedReflection<ConductorBsdf> {
 public:
  explicit ConductorBsdf(const ConductorFresnel& fresnel) : fresnel_(fresnel) {}
  Spectrum f_up(const Vec3d&, const Vec3d&, TransportMode) const { return Spectrum::Zero(); }
  double pdf_up(const Vec3d&, const Vec3d&, TransportMode) const { return 0.0; }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double, const Vec2d&, TransportMode) const {
    BsdfSample s;
    s.wi = Vec3d(-wo.x(), -wo.y(), wo.z());
    s.weight = fresnel_(wo.z());
    s.f = s.weight / wo.z();
    s.pdf = 1.0;
    s.flags = kBsdfReflection | kBsdfSpecular;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfSpecular; }

 private:
  ConductorFresnel fresnel_;
};

class RoughConductorBsdf final : public TwoSidedReflection<RoughConductorBsdf> {
 public:
  RoughConductorBsdf(const TrowbridgeReitz& distribution, const ConductorFresnel& fresnel)
      : distribution_(distribution), fresnel_(fresnel) {}
  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    const Vec3d hv = wo + wi;
    if (!(wi.z() > 0.0) || hv.squaredNorm() == 0.0) return Spectrum::Zero();
    const Vec3d h = hv.normalized();
    return fresnel_(wo.dot(h)) * (distribution_.D(h) * distribution_.G(wo, wi) / (4.0 * wo.z() * wi.z()));
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    const Vec3d hv = wo + wi;
    if (!(wi.z() > 0.0) || hv.squaredNorm() == 0.0) return 0.0;
    const Vec3d h = hv.normalized();
    return distribution_.D_visible(wo, h) / (4.0 * std::abs(wo.dot(h)));
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double, const Vec2d& u, TransportMode mode) const {
    const Vec3d m = distribution_.sample_wm(wo, u);
    BsdfSample s;
    s.wi = reflect(wo, m);
    if (!(s.wi.z() > 0.0)) return std::nullopt;
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    s.flags = kBsdfReflection | kBsdfGlossy;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfGlossy; }

 private:
  TrowbridgeReitz distribution_;
  ConductorFresnel fresnel_;
};

// Shared by the conductor materials: the optional complex index and its description.
class ConductorIndex {
 public:
  ConductorIndex(const std::optional<Vec3d>& eta, const std::optional<Vec3d>& k) : eta_rgb_(eta), k_rgb_(k) {
    if (k && !eta) throw_invalid("k needs eta too (got k = ", describe_rgb(*k), " without eta)");
    if (eta) eta_ = checked_unbounded(*eta, "eta", true);
    if (k) k_ = checked_unbounded(*k, "k", false);
  }
  ConductorFresnel at(const MaterialContext& context) const {
    ConductorFresnel f;
    if (!eta_rgb_) return f;
    f.perfect = false;
    f.eta = eta_.sample(*context.lambda) / context.eta_outside;
    f.k = k_rgb_ ? Spectrum(k_.sample(*context.lambda) / context.eta_outside) : Spectrum(Spectrum::Zero());
    if (!context.lambda->spectral) f.eta[3] = 1.0;  // the unused channel: keep the division finite
    return f;
  }
  const std::optional<Vec3d>& eta() const { return eta_rgb_; }
  const std::optional<Vec3d>& k() const { return k_rgb_; }
  std::string describe() const {
    if (!eta_rgb_) return "F=1";
    return concat("eta=", describe_rgb(*eta_rgb_), k_rgb_ ? concat(", k=", describe_rgb(*k_rgb_)) : "");
  }

 private:
  std::optional<Vec3d> eta_rgb_, k_rgb_;
  Color eta_, k_;
};

// A smooth metal mirror with the exact complex Fresnel reflectance of eta + i k (numbers or (r, g,
// b), relative to vacuum). eta and k unset: a perfect mirror, F = 1; eta without k: k = 0.
class Conductor final : public Material {
 public:
  // eta, k unset: a perfect mirror (F = 1); eta without k: k = 0.
  Conductor(const std::optional<Vec3d>& eta = std::nullopt, const std::optional<Vec3d>& k = std::nullopt) : index_(eta, k) {}
  const Bsdf* bsdf(const SurfaceInteraction&, const MaterialContext& context, ScratchBuffer& scratch) const override {
    return scratch.make<ConductorBsdf>(index_.at(context));
  }
  std::string describe() const override { return concat("Conductor(", index_.describe(), ")"); }
  const ConductorIndex& index() const { return index_; }

 private:
  ConductorIndex index_;
};

// A rough metal: GGX microfacets (alpha, or alpha_u along the tangent and alpha_v along the
// bitangent; >= 0, raised to 1e-4), height-correlated Smith masking, exact complex Fresnel of eta +
// i k (unset: F = 1), visible-normal sampling.
class RoughConductor final : public Material {
 public:
  RoughConductor(double alpha_u, double alpha_v, const std::optional<Vec3d>& eta = std::nullopt,
                 const std::optional<Vec3d>& k = std::nullopt)
      : alpha_u_(TrowbridgeReitz::checked_alpha(alpha_u, "alpha_u")), alpha_v_(TrowbridgeReitz::checked_alpha(alpha_v, "alpha_v")),
        index_(eta, k) {}
  const Bsdf* bsdf(const SurfaceInteraction&, const MaterialContext& context, ScratchBuffer& scratch) const override {
    return scratch.make<RoughConductorBsdf>(TrowbridgeReitz(alpha_u_, alpha_v_), index_.at(context));
  }
  std::string describe() const override {
    return concat("RoughConductor(alpha_u=", alpha_u_, ", alpha_v=", alpha_v_, ", ", index_.describe(), ")");
  }
  double alpha_u() const { return alpha_u_; }
  double alpha_v() const { return alpha_v_; }
  const ConductorIndex& index() const { return index_; }

 private:
  double alpha_u_, alpha_v_;
  ConductorIndex index_;
};

}  // namespace refracta
