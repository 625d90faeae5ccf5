// The energy-normalised Blinn-Phong BRDF of the MTL materials (Blinn 1977; normalisation
// (ns + 8) / (8 pi), Akenine-Moller et al., Real-Time Rendering 4th ed., eq. 9.71):
//   f = kd / pi + ks (ns + 8) / (8 pi) (n.h)^ns,  h = normalize(wo + wi).
// Sampled by a mixture: the cosine hemisphere with probability p_d = mean(kd) / (mean(kd) +
// mean(ks)), else the lobe around the half vector, pdf_h(h) = (ns + 1) / (2 pi) (n.h)^ns (so
// cos theta_h = u^(1/(ns+1))) reflected about h, pdf(wi) = pdf_h / (4 |wo.h|). The pdf is the exact
// mixture; half vectors whose reflection falls below the surface are lost samples. Two-sided.
// (The raster pipeline's shading/blinn_phong.h evaluates the same f from scene/material.h.)
#pragma once

#include "refracta/shading/fresnel.h"
#include "refracta/shading/material_util.h"

namespace refracta {

class BlinnPhongBsdf final : public TwoSidedReflection<BlinnPhongBsdf> {
 public:
  BlinnPhongBsdf(const Spectrum& kd, const Spectrum& ks, double ns, double p_diffuse)
      : kd_(kd), ks_(ks), ns_(ns), p_diffuse_(p_diffuse) {}

  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    Spectrum f = kd_ / kPi;
    const Vec3d h = wo + wi;
    if (p_diffuse_ < 1.0 && h.squaredNorm() > 0.0) {
      f += ks_ * ((ns_ + 8.0) / (8.0 * kPi) * std::pow(std::max(0.0, h.normalized().z()), ns_));
    }
    return f;
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    double pdf = p_diffuse_ * cosine_hemisphere_pdf(wi.z());
    const Vec3d hv = wo + wi;
    if (p_diffuse_ < 1.0 && hv.squaredNorm() > 0.0) {
      const Vec3d h = hv.normalized();
      const double cos_h = std::max(0.0, h.z());
      pdf += (1.0 - p_diffuse_) * (ns_ + 1.0) / (2.0 * kPi) * std::pow(cos_h, ns_) / (4.0 * std::abs(wo.dot(h)));
    }
    return pdf;
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const {
    BsdfSample s;
    if (uc < p_diffuse_) {
      s.wi = sample_cosine_hemisphere(u);
    } else {
      const double cos_h = std::pow(u.x(), 1.0 / (ns_ + 1.0));
      const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h)), phi = 2.0 * kPi * u.y();
      const Vec3d h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      s.wi = reflect(wo, h);
      if (!(s.wi.z() > 0.0)) return std::nullopt;
    }
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    s.flags = kBsdfReflection | (uc < p_diffuse_ ? kBsdfDiffuse : kBsdfGlossy);
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfDiffuse | (p_diffuse_ < 1.0 ? kBsdfGlossy : 0u); }

 private:
  Spectrum kd_, ks_;
  double ns_, p_diffuse_;
};

// Normalised Blinn-Phong: f = kd / pi + ks (ns + 8) / (8 pi) (n.h)^ns (the MTL model). kd, ks in
// [0, 1] (numbers or (r, g, b)), ns >= 0; alpha in [0, 1] is the raster opacity (MTL d). Sampled by
// a mixture of the cosine hemisphere and the (n.h)^ns lobe; pdf exact. A texture multiplies kd.
class BlinnPhong final : public Material {
 public:
  // The defaults of BlinnPhong(...) in Python and of the Scene.add_* calls' kd/ks/ns shorthand.
  static constexpr double kDefaultKd = 0.5, kDefaultNs = 1.0;

  // kd + ks <= 1 per channel (kd: its colour, which scales a texture): more would reflect far more
  // light than arrives (a trial: kd = ks = 1 gave 2.09 in a white furnace). Within it the lobe's
  // normalisation is approximate: ks = 1 alone reflects 1.02-1.075 at normal incidence for ns from 1
  // to 100 (1.024 at ns = 1, 1.075 at 8-10, 1.018 at 100: sampled, 4e5 draws), kd = ks = 0.5 at
  // ns = 20 reflects 1.03.
  BlinnPhong(const TexturedReflectance& kd, const Vec3d& ks, double ns, double alpha = 1.0)
      : kd_(kd), ks_rgb_(ks), ks_(checked_reflectance(ks, "ks")), ns_(checked_scalar(ns, "ns", 0.0, 1e7)),
        alpha_(checked_scalar(alpha, "alpha", 0.0, 1.0)) {
    if (!((kd_.rgb() + ks_rgb_).maxCoeff() <= 1.0 + 1e-6)) {  // float inputs (MTL) may sum to 1 + 1e-8
      throw_invalid("BlinnPhong: kd + ks must be <= 1 in every channel (got kd ", describe_rgb(kd_.rgb()), ", ks ",
                    describe_rgb(ks_rgb_), "): more would reflect far more light than arrives");
    }
  }

  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    const Spectrum kd = kd_.at(si, context), ks = ks_.sample(*context.lambda);
    const double md = channel_mean(kd, *context.lambda), ms = channel_mean(ks, *context.lambda);
    const double p_diffuse = md + ms > 0.0 ? md / (md + ms) : 1.0;
    return scratch.make<BlinnPhongBsdf>(kd, ks, ns_, p_diffuse);
  }
  MaterialPtr with_textures(Textures& textures) const override { return with_bound_texture(*this, &BlinnPhong::kd_, textures); }
  bool textured() const override { return kd_.textured(); }
  double alpha() const override { return alpha_; }
  const TexturedReflectance& kd() const { return kd_; }
  const Vec3d& ks() const { return ks_rgb_; }
  double ns() const { return ns_; }
  std::string describe() const override {
    return concat("BlinnPhong(kd=", describe_rgb(kd_.rgb()), ", ks=", describe_rgb(ks_rgb_), ", ns=", ns_, kd_.describe_texture(),
                  alpha_ < 1.0 ? concat(", alpha=", alpha_) : "", ")");
  }

 private:
  TexturedReflectance kd_;
  Vec3d ks_rgb_;
  Color ks_;
  double ns_;
  double alpha_;
};

}  // namespace refracta
