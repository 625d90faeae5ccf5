// An infinite light times a constant factor (Scene.set_physical_sky's `scale` on its sky).
#pragma once

#include "refracta/core/error.h"
#include "refracta/shading/light.h"
#include "refracta/shading/sun_light.h"

#include <cmath>
#include <utility>

namespace refracta {

// An infinite light (a sky or an environment, not the sun) times a constant factor `scale`:
// Scene.set_physical_sky's `scale` on its sky. Pickles through its light and scale.
class ScaledInfiniteLight final : public Light {
 public:
  // `light` must be infinite and not the sun, and `scale` finite and >= 0.
  ScaledInfiniteLight(LightPtr light, double scale) : light_(std::move(light)), scale_(scale) {
    if (!light_ || !light_->is_infinite()) throw_invalid("ScaledLight: the light must be infinite (a sky or an environment)");
    // The scene finds its sun by type (the bent sun, hero wavelengths, set_sun): a scaled one it would not.
    if (dynamic_cast<const SunLight*>(light_.get())) {
      throw_invalid("ScaledLight: scale the sun by its radiance instead (SunLight(direction, radiance * scale))");
    }
    if (!(scale_ >= 0.0 && std::isfinite(scale_))) throw_invalid("ScaledLight: scale must be finite and >= 0 (got ", scale_, ")");
  }
  LightType type() const override { return light_->type(); }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override {
    auto sample = light_->sample_li(ctx, u, lambda);
    if (sample) sample->L *= scale_;
    return sample;
  }
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light, const Vec3d& n_light) const override {
    return light_->pdf_li(ctx, wi, p_light, n_light);
  }
  Spectrum Le(const Vec3d& dir, const SampledWavelengths& lambda) const override { return scale_ * light_->Le(dir, lambda); }
  double power() const override { return scale_ * light_->power(); }
  void preprocess(const Vec3d& centre, double radius) override { light_->preprocess(centre, radius); }
  std::string describe() const override { return concat(light_->describe(), " x ", scale_); }

  const LightPtr& light() const { return light_; }
  double scale() const { return scale_; }

 private:
  LightPtr light_;
  double scale_;
};

}  // namespace refracta
