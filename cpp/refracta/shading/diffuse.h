// Lambertian reflection (shared/SHADING.md section 3): f = R / pi, sampled by a cosine-weighted
// hemisphere (pdf = cos theta / pi, Malley's method), so every sample weighs R. Two-sided.
//   Diffuse(reflectance = (0.5, 0.5, 0.5), texture = -1): an optional texture multiplies R.
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

class Diffuse final : public Material {
 public:
  explicit Diffuse(const Vec3d& reflectance = Vec3d::Constant(0.5), int texture = -1)
      : rgb_(reflectance), reflectance_(checked_reflectance(reflectance, "reflectance")), texture_(texture) {}
  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    return scratch.make<DiffuseBsdf>(resolve_reflectance(reflectance_, texture_, si, context));
  }
  const Vec3d& reflectance() const { return rgb_; }
  int texture() const { return texture_; }
  std::string describe() const override {
    return concat("Diffuse(reflectance=", describe_rgb(rgb_), texture_ >= 0 ? concat(", texture=", texture_) : "", ")");
  }

 private:
  Vec3d rgb_;
  Color reflectance_;
  int texture_;
};

}  // namespace refracta
