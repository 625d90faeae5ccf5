// PointLight (shared/SHADING.md section 5). Integrator: a delta light (type kDeltaPosition). It cannot be hit by rays; only next-event
// estimation reaches it. sample_li returns pdf = 1 and L = I / r^2 (the inverse square already
// applied): the contribution is f * L * |cos theta_i| / pdf, shadowed by a ray to p_light.
// pdf_li is 0 (never MIS-weighted against BSDF sampling).
//
//   auto light = std::make_shared<PointLight>(Vec3d(0, 10, 0), Color::illuminant({100, 100, 100}));
#pragma once

#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

namespace refracta {

// A point light: intensity I [W/sr] (a colour: one number or RGB) in every direction from
// position [m]; irradiance at distance r on a surface tilted by theta E = I cos(theta) / r^2;
// power 4 pi I.
class PointLight final : public Light {
 public:
  // position [m] finite; intensity an illuminant Color [W/sr] (throws std::invalid_argument).
  PointLight(const Vec3d& position, const Color& intensity);

  LightType type() const override { return LightType::kDeltaPosition; }
  // nullopt when ctx.p is the light's position (no direction is defined there).
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext&, const Vec3d&, const Vec3d&, const Vec3d&) const override { return 0.0; }
  double power() const override;  // 4 pi Y(I)
  std::string describe() const override;

  const Vec3d& position() const { return position_; }
  const Color& intensity() const { return intensity_; }

 private:
  Vec3d position_;
  Color intensity_;
};

}  // namespace refracta
