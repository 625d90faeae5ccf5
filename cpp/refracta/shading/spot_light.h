// SpotLight (shared/SHADING.md section 5). Its power, 2 pi I ((1 - cos(inner/2)) + (cos(inner/2)
// - cos(angle/2)) / 2), is exact because the smoothstep integrates to one half over its interval.
//
// Integrator: a delta light (kDeltaPosition), as PointLight: sample_li gives pdf = 1,
// L = I(w) / r^2 (nullopt outside the cone), pdf_li = 0; shadow ray to p_light.
#pragma once

#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

namespace refracta {

// A spot light at position [m] shining along direction into a cone of full angle [deg] with
// intensity I [W/sr] (a colour). A hard edge by default (full intensity inside the cone, nothing
// outside); with inner_angle [deg] < angle a smoothstep falloff (pbrt-v4 SpotLight::I):
// I(w) = I smoothstep(cos(angle/2), cos(inner_angle/2), cos theta), theta from the axis.
class SpotLight final : public Light {
 public:
  // direction: the cone's axis (non-zero, normalised here); angle: full cone angle [deg] in
  // (0, 360]; inner_angle [deg] in (0, angle], or < 0 for "= angle" (a hard edge).
  SpotLight(const Vec3d& position, const Vec3d& direction, double angle, const Color& intensity,
            double inner_angle = -1.0);

  LightType type() const override { return LightType::kDeltaPosition; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext&, const Vec3d&, const Vec3d&, const Vec3d&) const override { return 0.0; }
  double power() const override;
  std::string describe() const override;

  // The fraction of I emitted along unit w (from the light outward): 1 inside inner_angle, the
  // smoothstep between, 0 outside angle.
  double falloff(const Vec3d& w) const;

  const Vec3d& position() const { return position_; }
  const Vec3d& direction() const { return direction_; }
  const Vec3d& given_direction() const { return given_direction_; }  // as passed to the constructor
  const Color& intensity() const { return intensity_; }
  double angle() const { return angle_; }
  double inner_angle() const { return inner_angle_; }

 private:
  Vec3d position_, direction_, given_direction_;
  double angle_, inner_angle_;
  Color intensity_;
  double cos_outer_, cos_inner_;  // cosines of the half angles
};

}  // namespace refracta
