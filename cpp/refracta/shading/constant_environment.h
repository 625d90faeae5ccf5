// ConstantEnvironment (shared/SHADING.md section 5), the white furnace when L_e = 1. Cosine
// sampling gives pdf 0 below the surface: the integrator's BSDF sampling, MIS-weighted, must
// cover transmission.
//
// Integrator: an infinite light, as EnvironmentLight (environment_light.h): escaping rays add
// Le(dir); NEE with sample_li / pdf_li(ctx, wi, ., .); preprocess(centre, R) before power().
#pragma once

#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

#include <atomic>

namespace refracta {

// Uniform radiance L_e [W/(m^2 sr)] (a colour) from every direction; sampling 'cosine' (about the
// point's normal, when given) or 'uniform' (the sphere, pdf 1/(4 pi)). Irradiance pi L_e.
class ConstantEnvironment final : public Light {
 public:
  enum class Sampling { kCosine, kUniform };
  // 'cosine' or 'uniform' (ValueError otherwise).
  static Sampling sampling_from(const std::string& name);
  explicit ConstantEnvironment(const Color& radiance, Sampling sampling = Sampling::kCosine);

  LightType type() const override { return LightType::kInfinite; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  Spectrum Le(const Vec3d& dir, const SampledWavelengths& lambda) const override;
  double power() const override;  // 4 pi^2 R^2 Y(L_e)
  void preprocess(const Vec3d& centre, double radius) override;
  std::string describe() const override;

  const Color& radiance() const { return radiance_; }
  Sampling sampling() const { return sampling_; }

 private:
  bool cosine(const LightSampleContext& ctx) const { return sampling_ == Sampling::kCosine && ctx.n.squaredNorm() > 0.0; }
  Color radiance_;
  Sampling sampling_;
  std::atomic<double> scene_radius_{1.0};  // preprocess writes it while other renders may read it
};

}  // namespace refracta
