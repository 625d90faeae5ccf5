// The spot light (spot_light.h).
#include "refracta/shading/spot_light.h"

#include "refracta/shading/light_common.h"

namespace refracta {

SpotLight::SpotLight(const Vec3d& position, const Vec3d& direction, double angle, const Color& intensity,
                     double inner_angle)
    : position_(position), angle_(angle), inner_angle_(inner_angle < 0.0 ? angle : inner_angle), intensity_(intensity) {
  detail::check_point(position, "SpotLight: position");
  direction_ = detail::check_direction(direction, "SpotLight: direction");
  given_direction_ = direction;
  if (!std::isfinite(angle) || !(angle > 0.0) || angle > 360.0) throw_invalid("SpotLight: angle must be in (0, 360] degrees (got ", angle, ")");
  if (std::isnan(inner_angle) || !(inner_angle_ > 0.0) || inner_angle_ > angle) {
    throw_invalid("SpotLight: inner_angle must be in (0, angle = ", angle, "] degrees, or < 0 for a hard edge (got ", inner_angle, ")");
  }
  detail::check_emission(intensity, "SpotLight: intensity");
  cos_outer_ = std::cos(degrees_to_radians(0.5 * angle_));
  cos_inner_ = std::cos(degrees_to_radians(0.5 * inner_angle_));
}

double SpotLight::falloff(const Vec3d& w) const {
  const double c = direction_.dot(w);
  if (c >= cos_inner_) return 1.0;
  if (c < cos_outer_) return 0.0;
  const double t = (c - cos_outer_) / (cos_inner_ - cos_outer_);  // cos_inner_ > c >= cos_outer_ here
  return t * t * (3.0 - 2.0 * t);
}

std::optional<LightLiSample> SpotLight::sample_li(const LightSampleContext& ctx, const Vec2d& /*u*/,
                                                  const SampledWavelengths& lambda) const {
  const Vec3d d = position_ - ctx.p;
  const double r2 = d.squaredNorm();
  if (!(r2 > 0.0) || !std::isfinite(r2)) return std::nullopt;
  LightLiSample s;
  s.distance = std::sqrt(r2);
  s.wi = d / s.distance;
  const double f = falloff(-s.wi);
  if (f <= 0.0) return std::nullopt;
  s.L = intensity_.sample(lambda) * (f / r2);
  s.pdf = 1.0;
  s.p_light = position_;
  return s;
}

double SpotLight::power() const {
  return 2.0 * kPi * detail::luminance(intensity_.rgb()) * ((1.0 - cos_inner_) + 0.5 * (cos_inner_ - cos_outer_));
}

std::string SpotLight::describe() const {
  return concat("SpotLight(position=(", position_.x(), ", ", position_.y(), ", ", position_.z(), "), direction=(",
                direction_.x(), ", ", direction_.y(), ", ", direction_.z(), "), angle=", angle_,
                ", inner_angle=", inner_angle_, ", intensity=(", intensity_.rgb().x(), ", ", intensity_.rgb().y(), ", ",
                intensity_.rgb().z(), "))");
}

}  // namespace refracta
