// Lambertian reflection (shared/SHADING.md section 3): f = R / pi, sampled by a cosine-weighted
// hemisphere (pdf = cos theta / pi, Malley's method), so every sample weighs R. Two-sided.
//   Diffuse(reflectance = (0.5, 0.5, 0.5), texture = none): an optional texture (a file path or a
//   scene texture id, material_util.h's TexturedReflectance) multiplies R.
#pragma once

#include "refracta/shading/material_util.h"

namespace refracta {

class DiffuseBsdf final : public TwoSidedReflection<DiffuseBsdf> {
 public:
  explicit DiffuseBsdf(const Spectrum& reflectance) : r_(reflectance) {}
  Spectrum f_up(const Vec3d&, const Vec3d&, TransportMode) const { return r_ / kPi; }
  double pdf_up(const Vec3d&, const Vec3d& wi, TransportMode) const { return cosine_hemisphere_pdf(wi.z()); }
  std::optional<BsdfSample> sample_up(const Vec3d&, double, const Vec2d& u, TransportMode) const {
    BsdfSample s;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi.z());
    s.f = r_ / kPi;
    s.weight = r_;
    s.flags = kBsdfReflection | kBsdfDiffuse;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfDiffuse; }

 private:
  Spectrum r_;
};

// Lambertian reflection f = R / pi (two-sided). reflectance: a number or (r, g, b) in [0, 1] (> 1
// is refused: it would create energy).
class Diffuse final : public Material {
 public:
  explicit Diffuse(const TexturedReflectance& reflectance) : reflectance_(reflectance) {}
  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    return scratch.make<DiffuseBsdf>(reflectance_.at(si, context));
  }
  MaterialPtr with_textures(Textures& textures) const override { return with_bound_texture(*this, &Diffuse::reflectance_, textures); }
  bool textured() const override { return reflectance_.textured(); }
  const TexturedReflectance& reflectance() const { return reflectance_; }
  std::string describe() const override {
    return concat("Diffuse(reflectance=", describe_rgb(reflectance_.rgb()), reflectance_.describe_texture(), ")");
  }

 private:
  TexturedReflectance reflectance_;
};

}  // namespace refracta
