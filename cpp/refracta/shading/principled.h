// The principled BRDF of Burley 2012 ("Physically-Based Shading at Disney", SIGGRAPH course
// notes; the reference shader disney.brdf of Disney's BRDF Explorer, wdas/brdf), without the
// subsurface approximation. With theta_d the angle between wi and h, F_S(x) = (1 - x)^5:
//   diffuse  base/pi (1 + (F_D90 - 1) F_S(cos_i)) (1 + (F_D90 - 1) F_S(cos_o)),
//            F_D90 = 0.5 + 2 roughness cos^2 theta_d (the retro-reflective rim),
//   sheen    sheen lerp(1, tint, sheen_tint) F_S(cos theta_d); both times (1 - metallic),
//   specular D_GGX(h; ax, ay) G1(wo) G1(wi) F / (4 cos_o cos_i), alpha = roughness^2,
//            aspect = sqrt(1 - 0.9 anisotropic), ax = max(0.001, alpha / aspect),
//            ay = max(0.001, alpha aspect), F = lerp(C0, 1, F_S(cos theta_d)),
//            C0 = lerp(0.08 specular lerp(1, tint, specular_tint), base, metallic),
//   clearcoat 0.25 clearcoat D_GTR1(h; lerp(0.1, 0.001, clearcoat_gloss)) lerp(0.04, 1, F_S)
//            G1_0.25(wo) G1_0.25(wi) / (4 cos_o cos_i).
// tint = base / luminance(base) (disney.brdf's 0.3, 0.6, 0.1 weights). The masking terms are
// SEPARABLE Smith G1 products, as disney.brdf writes them (the rest of refracta's microfacet
// BSDFs use the height-correlated form). Sampling: a lobe by probability (diffuse 1 - metallic,
// specular 1, clearcoat 0.25 clearcoat, normalised): cosine hemisphere, GGX visible normals,
// GTR1 half vectors (cos^2 theta_h = (1 - a^(2(1-u))) / (1 - a^2)); the pdf is the mixture. Two-sided.
#pragma once

#include "refracta/shading/material_util.h"
#include "refracta/shading/microfacet.h"

namespace refracta {

struct PrincipledParameters {
  double metallic = 0.0, roughness = 0.5, anisotropic = 0.0, specular = 0.5, specular_tint = 0.0;
  double sheen = 0.0, sheen_tint = 0.5, clearcoat = 0.0, clearcoat_gloss = 1.0;
};

class PrincipledBsdf final : public TwoSidedReflection<PrincipledBsdf> {
 public:
  PrincipledBsdf(const Spectrum& base, const Spectrum& tint, const PrincipledParameters& p, const SampledWavelengths& lambda)
      : base_(base), p_(p) {
    const double alpha = p.roughness * p.roughness, aspect = std::sqrt(1.0 - 0.9 * p.anisotropic);
    specular_ = TrowbridgeReitz(std::max(0.001, alpha / aspect), std::max(0.001, alpha * aspect));
    const Spectrum one = Spectrum::Ones();
    c0_ = (1.0 - p.metallic) * (0.08 * p.specular * (one + p.specular_tint * (tint - one))) + p.metallic * base;
    sheen_color_ = p.sheen * (one + p.sheen_tint * (tint - one));
    clearcoat_alpha_ = 0.1 + (0.001 - 0.1) * p.clearcoat_gloss;
    const double wd = 1.0 - p.metallic, ws = 1.0, wc = 0.25 * p.clearcoat, sum = wd + ws + wc;
    p_diffuse_ = wd / sum, p_clearcoat_ = wc / sum;
    (void)lambda;
  }

  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    if (!(wi.z() > 0.0)) return Spectrum::Zero();
    const Vec3d h = (wo + wi).normalized();
    const double cos_d = wi.dot(h), fh = schlick(cos_d);
    const double fd90 = 0.5 + 2.0 * p_.roughness * cos_d * cos_d;
    const double fd = (1.0 + (fd90 - 1.0) * schlick(wi.z())) * (1.0 + (fd90 - 1.0) * schlick(wo.z()));
    Spectrum f = (1.0 - p_.metallic) * (base_ * (fd / kPi) + sheen_color_ * fh);
    const double cos4 = 4.0 * wo.z() * wi.z();
    f += (c0_ + (1.0 - c0_) * fh) * (specular_.D(h) * specular_.G_separable(wo, wi) / cos4);
    if (p_.clearcoat > 0.0) {
      const TrowbridgeReitz coat_g(0.25, 0.25);
      f += 0.25 * p_.clearcoat * gtr1(h.z()) * (0.04 + 0.96 * fh) * coat_g.G_separable(wo, wi) / cos4;
    }
    return f;
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    if (!(wi.z() > 0.0)) return 0.0;
    const Vec3d h = (wo + wi).normalized();
    const double jacobian = 1.0 / (4.0 * std::abs(wo.dot(h)));
    return p_diffuse_ * cosine_hemisphere_pdf(wi.z()) +
           (1.0 - p_diffuse_ - p_clearcoat_) * specular_.D_visible(wo, h) * jacobian +
           p_clearcoat_ * gtr1(h.z()) * h.z() * jacobian;
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const {
    BsdfSample s;
    if (uc < p_diffuse_) {
      s.wi = sample_cosine_hemisphere(u);
      s.flags = kBsdfReflection | kBsdfDiffuse;
    } else if (uc < p_diffuse_ + p_clearcoat_) {
      const double a2 = clearcoat_alpha_ * clearcoat_alpha_;
      const double cos2 = (1.0 - std::pow(a2, 1.0 - u.x())) / (1.0 - a2);
      const double cos_h = std::sqrt(std::max(0.0, cos2)), sin_h = std::sqrt(std::max(0.0, 1.0 - cos2));
      const double phi = 2.0 * kPi * u.y();
      s.wi = reflect(wo, Vec3d(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h));
      s.flags = kBsdfReflection | kBsdfGlossy;
    } else {
      s.wi = reflect(wo, specular_.sample_wm(wo, u));
      s.flags = kBsdfReflection | kBsdfGlossy;
    }
    if (!(s.wi.z() > 0.0)) return std::nullopt;
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfDiffuse | kBsdfGlossy; }

 private:
  static double schlick(double c) {
    const double m = std::clamp(1.0 - c, 0.0, 1.0), m2 = m * m;
    return m2 * m2 * m;
  }
  // Berry's distribution, GTR with gamma = 1, normalised so that int D cos = 1.
  double gtr1(double cos_h) const {
    const double a2 = clearcoat_alpha_ * clearcoat_alpha_;
    return (a2 - 1.0) / (kPi * std::log(a2) * (1.0 + (a2 - 1.0) * cos_h * cos_h));
  }
  Spectrum base_, c0_, sheen_color_;
  PrincipledParameters p_;
  TrowbridgeReitz specular_;
  double clearcoat_alpha_, p_diffuse_, p_clearcoat_;
};

// Burley 2012's principled BRDF (disney.brdf without subsurface): base_color (r, g, b) in [0, 1],
// and metallic, roughness (alpha = roughness^2), anisotropic, specular, specular_tint, sheen,
// sheen_tint, clearcoat, clearcoat_gloss, all in [0, 1]. A texture multiplies base_color.
// Not energy conserving, as Burley's model is not: its lobes are summed (the diffuse is not
// reduced by the specular's reflectance) and the diffuse's retro-reflective rim exceeds 1 at
// grazing angles. A white base_color, the other parameters at their defaults, reflects 1.04 of
// the light at normal incidence and 1.19 at 89 deg (1.05 and 1.21 with clearcoat 1; the mean of
// sample() weights): a white furnace renders it about 4 % bright.
class Principled final : public Material {
 public:
  Principled(const TexturedReflectance& base_color, const PrincipledParameters& p) : base_(base_color), p_(p) {
    checked_scalar(p.metallic, "metallic", 0.0, 1.0);
    checked_scalar(p.roughness, "roughness", 0.0, 1.0);
    checked_scalar(p.anisotropic, "anisotropic", 0.0, 1.0);
    checked_scalar(p.specular, "specular", 0.0, 1.0);
    checked_scalar(p.specular_tint, "specular_tint", 0.0, 1.0);
    checked_scalar(p.sheen, "sheen", 0.0, 1.0);
    checked_scalar(p.sheen_tint, "sheen_tint", 0.0, 1.0);
    checked_scalar(p.clearcoat, "clearcoat", 0.0, 1.0);
    checked_scalar(p.clearcoat_gloss, "clearcoat_gloss", 0.0, 1.0);
  }
  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    const Vec3d rgb = base_.rgb_at(si, context);
    const Spectrum base = reflectance_spectrum(rgb, *context.lambda);
    const double luminance = 0.3 * rgb.x() + 0.6 * rgb.y() + 0.1 * rgb.z();
    const Spectrum tint = luminance > 0.0 ? Spectrum(base / luminance) : Spectrum(Spectrum::Ones());
    return scratch.make<PrincipledBsdf>(base, tint, p_, *context.lambda);
  }
  MaterialPtr with_textures(Textures& textures) const override { return with_bound_texture(*this, &Principled::base_, textures); }
  bool textured() const override { return base_.textured(); }
  std::string describe() const override {
    return concat("Principled(base_color=", describe_rgb(base_.rgb()), ", metallic=", p_.metallic, ", roughness=", p_.roughness,
                  ", anisotropic=", p_.anisotropic, ", specular=", p_.specular, ", specular_tint=", p_.specular_tint,
                  ", sheen=", p_.sheen, ", sheen_tint=", p_.sheen_tint, ", clearcoat=", p_.clearcoat,
                  ", clearcoat_gloss=", p_.clearcoat_gloss, base_.describe_texture(), ")");
  }
  const TexturedReflectance& base_color() const { return base_; }
  const PrincipledParameters& parameters() const { return p_; }

 private:
  TexturedReflectance base_;
  PrincipledParameters p_;
};

}  // namespace refracta
