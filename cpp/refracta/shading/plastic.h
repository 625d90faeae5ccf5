// Coated diffuse ("plastic"): a dielectric coat of relative index eta over a Lambertian base of
// reflectance R (Weidlich & Wilkie 2007, "Arbitrarily Layered Micro-Facet Surfaces"; Mitsuba 3's
// plastic / roughplastic). Light refracts into the coat, bounces diffusely between base and coat
// (the internal diffuse reflectance Fbar_int of the coat's underside sums the series), refracts out:
//   f = F(wo) delta_mirror [smooth] or F(wo.h) D G / (4 cos_o cos_i) [rough, GGX]
//     + (1 - F(wi)) (1 - F(wo)) R / (pi eta^2 (1 - R Fbar_int)).
// F is the smooth interface's Fresnel in the diffuse term for both (Mitsuba's roughplastic uses a
// tabulated rough transmittance there instead; the difference is measured in the tests).
// Fbar_int = fresnel_diffuse_reflectance(1 / eta) (SHADING.md section 1: 0.596346 for 1.5).
// Sampling: the specular lobe with probability P = F(wo) w / (F(wo) w + (1 - F(wo))(1 - w)),
// w = 1 / (1 + mean(R)) (Mitsuba's specular sampling weight with specular reflectance 1), else
// the cosine hemisphere. Two-sided.
#pragma once

#include "refracta/shading/fresnel.h"
#include "refracta/shading/ior.h"
#include "refracta/shading/material_util.h"
#include "refracta/shading/microfacet.h"

namespace refracta {

class PlasticBsdf final : public TwoSidedReflection<PlasticBsdf> {
 public:
  // alpha_x == 0: a smooth coat.
  PlasticBsdf(const Spectrum& reflectance, double eta, double fdr_internal, double specular_weight, double alpha_x, double alpha_y)
      : r_(reflectance), eta_(eta), fdr_internal_(fdr_internal), specular_weight_(specular_weight), smooth_(alpha_x == 0.0),
        distribution_(smooth_ ? 1.0 : alpha_x, smooth_ ? 1.0 : alpha_y) {}

  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    Spectrum f = diffuse(wo, wi);
    if (!smooth_) {
      const Vec3d h = (wo + wi).normalized();
      f += fresnel_dielectric(wo.dot(h), eta_) * distribution_.D(h) * distribution_.G(wo, wi) / (4.0 * wo.z() * wi.z());
    }
    return f;
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    const double p = specular_probability(wo);
    double pdf = (1.0 - p) * cosine_hemisphere_pdf(wi.z());
    if (!smooth_) {
      const Vec3d h = (wo + wi).normalized();
      pdf += p * distribution_.D_visible(wo, h) / (4.0 * std::abs(wo.dot(h)));
    }
    return pdf;
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const {
    const double p = specular_probability(wo);
    BsdfSample s;
    if (smooth_ && uc < p) {
      s.wi = Vec3d(-wo.x(), -wo.y(), wo.z());
      s.pdf = p;
      s.weight = Spectrum::Constant(fresnel_dielectric(wo.z(), eta_) / p);
      s.f = s.weight * p / wo.z();
      s.flags = kBsdfReflection | kBsdfSpecular;
      return s;
    }
    s.wi = uc < p ? reflect(wo, distribution_.sample_wm(wo, u)) : sample_cosine_hemisphere(u);
    if (!(s.wi.z() > 0.0)) return std::nullopt;
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    s.flags = kBsdfReflection | (uc < p ? kBsdfGlossy : kBsdfDiffuse);
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfDiffuse | (smooth_ ? kBsdfSpecular : kBsdfGlossy); }

 private:
  Spectrum diffuse(const Vec3d& wo, const Vec3d& wi) const {
    const double t = (1.0 - fresnel_dielectric(wi.z(), eta_)) * (1.0 - fresnel_dielectric(wo.z(), eta_));
    return r_ / (1.0 - fdr_internal_ * r_) * (t / (kPi * eta_ * eta_));
  }
  double specular_probability(const Vec3d& wo) const {
    const double F = fresnel_dielectric(wo.z(), eta_);
    const double s = F * specular_weight_, d = (1.0 - F) * (1.0 - specular_weight_);
    return s + d > 0.0 ? s / (s + d) : 0.0;
  }
  Spectrum r_;
  double eta_, fdr_internal_, specular_weight_;
  bool smooth_;
  TrowbridgeReitz distribution_;
};

// Coated diffuse (Weidlich & Wilkie 2007): a dielectric coat of index ior over a Lambertian base of
// reflectance in [0, 1]; alpha = 0: smooth coat (a delta lobe), > 0: GGX (or alpha_u, alpha_v). A
// texture multiplies the reflectance. The base's light enters and leaves through the smooth coat's
// Fresnel terms at any alpha, (1 - F(wi)) (1 - F(wo)) R / (pi eta^2 (1 - R Fdr_internal))
// (internal reflections at the coat summed). Smooth: Mitsuba 3's plastic with nonlinear=True (its default, False,
// divides by 1 - Fdr_internal instead: brighter by (1 - R Fdr_internal) / (1 - Fdr_internal),
// 35 % at R 0.77 and 2.5x as R -> 0 for ior 1.5). Rough: roughplastic's specular lobe; its diffuse part differs from
// roughplastic's, which takes the rough interface's tabulated transmittance and internal
// reflectance (a trial's directional albedos, alpha 0.3, white base, ior 1.5: 11.8 % above
// roughplastic's at normal incidence, 4.4 % below at 80 deg, 0.54 against 0.62 at 85 deg and
// 0.28 against 0.60 at 89 deg). The rough lobe's Fresnel at grazing can outgrow the smooth
// coat's F that the diffuse part leaves room for: a white base under a coat of ior 10 reflects
// 1.05 of what arrives at 85 deg (1.29 at ior 50); at a polymer's 1.5 it never exceeds 1.
// ior in (0, 100]: beyond, Fdr_internal rounds to 1 and a white base's 1 / (1 - R Fdr_internal)
// to infinity.
class Plastic final : public Material {
 public:
  static constexpr double kDefaultIor = 1.5;  // a varnish's or a polymer's coat
  static constexpr double kMaxIor = 100.0;     // far above any coat's (diamond 2.42)
  // alpha = 0: smooth coat; otherwise GGX roughness alpha_u, alpha_v (>= TrowbridgeReitz::kMinAlpha).
  Plastic(const TexturedReflectance& reflectance, double ior = kDefaultIor, double alpha_u = 0.0, double alpha_v = 0.0)
      : reflectance_(reflectance), ior_(ior) {
    if (!(ior_.rgb_value() <= kMaxIor)) {
      throw_invalid("Plastic: ior must be at most ", kMaxIor, " (got ", ior_.rgb_value(), ")");
    }
    const double au = checked_alpha_or_zero(alpha_u, "alpha_u"), av = checked_alpha_or_zero(alpha_v, "alpha_v");
    if ((au == 0.0) != (av == 0.0)) throw_invalid("alpha_u and alpha_v must both be 0 (smooth) or both > 0 (got ", alpha_u, ", ", alpha_v, ")");
    alpha_u_ = au, alpha_v_ = av;
  }
  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    const Spectrum r = reflectance_.at(si, context);
    const double eta = ior_.rgb_value() / context.eta_outside;
    const double specular_weight = 1.0 / (1.0 + channel_mean(r, *context.lambda));
    return scratch.make<PlasticBsdf>(r, eta, fresnel_diffuse_reflectance(1.0 / eta), specular_weight, alpha_u_, alpha_v_);
  }
  std::string describe() const override {
    return concat("Plastic(reflectance=", describe_rgb(reflectance_.rgb()), ", ior=", ior_.describe(),
                  alpha_u_ > 0.0 ? concat(", alpha_u=", alpha_u_, ", alpha_v=", alpha_v_) : "", reflectance_.describe_texture(), ")");
  }
  MaterialPtr with_textures(Textures& textures) const override { return with_bound_texture(*this, &Plastic::reflectance_, textures); }
  bool textured() const override { return reflectance_.textured(); }
  const TexturedReflectance& reflectance() const { return reflectance_; }
  double ior() const { return ior_.rgb_value(); }
  double alpha_u() const { return alpha_u_; }
  double alpha_v() const { return alpha_v_; }

 private:
  static double checked_alpha_or_zero(double alpha, const char* name) {
    return alpha == 0.0 ? 0.0 : TrowbridgeReitz::checked_alpha(alpha, name);
  }
  TexturedReflectance reflectance_;
  Ior ior_;
  double alpha_u_ = 0.0, alpha_v_ = 0.0;
};

}  // namespace refracta
