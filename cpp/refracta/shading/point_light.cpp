// The point light (point_light.h).
#include "refracta/shading/point_light.h"

#include "refracta/shading/light_common.h"

namespace refracta {

PointLight::PointLight(const Vec3d& position, const Color& intensity)
    : position_(position), intensity_(intensity) {
  detail::check_point(position, "PointLight: position");
  detail::check_emission(intensity, "PointLight: intensity");
}

std::optional<LightLiSample> PointLight::sample_li(const LightSampleContext& ctx, const Vec2d& /*u*/,
                                                   const SampledWavelengths& lambda) const {
  const Vec3d d = position_ - ctx.p;
  const double r2 = d.squaredNorm();
  if (!(r2 > 0.0) || !std::isfinite(r2)) return std::nullopt;
  LightLiSample s;
  s.distance = std::sqrt(r2);
  s.wi = d / s.distance;
  s.L = intensity_.sample(lambda) / r2;
  s.pdf = 1.0;
  s.p_light = position_;
  return s;
}

double PointLight::power() const { return 4.0 * kPi * detail::luminance(intensity_.rgb()); }

std::string PointLight::describe() const {
  return concat("PointLight(position=(", position_.x(), ", ", position_.y(), ", ", position_.z(), "), intensity=(",
                intensity_.rgb().x(), ", ", intensity_.rgb().y(), ", ", intensity_.rgb().z(), "))");
}

}  // namespace refracta
