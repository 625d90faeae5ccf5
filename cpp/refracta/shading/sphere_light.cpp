// The emissive sphere (sphere_light.h).
#include "refracta/shading/sphere_light.h"

#include "refracta/core/frame.h"
#include "refracta/shading/light_common.h"

namespace refracta {

namespace {
// Directions sampled at the cone's rim are re-measured with rounding of order 1e-16 / (1 -
// cos theta_max) relative: accepted as inside.
constexpr double kSphereRimSlack = 1e-9;
}  // namespace

SphereLight::SphereLight(const Vec3d& centre, double radius, const Color& emission)
    : centre_(centre), radius_(radius), emission_(emission) {
  detail::check_point(centre, "SphereLight: centre");
  detail::check_positive(radius, "SphereLight: radius");
  if (radius > kSceneReach) throw_invalid("SphereLight: radius must be <= ", kSceneReach, " m (got ", radius, ")");
  detail::check_emission(emission, "SphereLight: emission");
}

bool SphereLight::from_inside(const Vec3d& p) const {
  return (centre_ - p).squaredNorm() <= radius_ * radius_ * (1.0 + 2e-9);
}

std::optional<LightLiSample> SphereLight::sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                                    const SampledWavelengths& lambda) const {
  const Vec3d to_centre = centre_ - ctx.p;
  const double d2 = to_centre.squaredNorm();
  const double r2 = radius_ * radius_;
  LightLiSample s;
  if (from_inside(ctx.p)) {
    // Inside: uniform area; the outward emission cannot reach the point.
    const Vec3d n = sample_uniform_sphere(u);
    s.p_light = centre_ + radius_ * n;
    const Vec3d d = s.p_light - ctx.p;
    const double dist2 = d.squaredNorm();
    if (!(dist2 > 0.0)) return std::nullopt;
    s.distance = std::sqrt(dist2);
    s.wi = d / s.distance;
    // L(p_light, n, -wi) is 0 here: from inside, -wi leaves the surface inward.
    if (!(n.dot(-s.wi) > 0.0)) return std::nullopt;
    s.pdf = dist2 / (std::abs(n.dot(s.wi)) * 4.0 * kPi * r2);
    s.L = L(s.p_light, n, -s.wi, lambda);
    return s;
  }
  // Outside: the subtended cone, sin^2(theta_max) = r^2/d^2.
  const double d = std::sqrt(d2);
  const double sin2_max = r2 / d2;
  const double cos_max = std::sqrt(std::max(0.0, 1.0 - sin2_max));
  const double one_minus_cos_max = sin2_max / (1.0 + cos_max);
  const double omc = u.x() * one_minus_cos_max;  // 1 - cos(theta), theta from the centre direction
  const double cos_theta = 1.0 - omc;
  const double sin2_theta = omc * (2.0 - omc);
  // The angle alpha at the centre between -to_centre and the point hit by that direction:
  // cos alpha = sin^2(theta) / sin(theta_max) + cos(theta) sqrt(1 - sin^2(theta) / sin^2(theta_max)).
  const double sin_max = std::sqrt(sin2_max);
  const double cos_alpha = sin2_theta / sin_max + cos_theta * std::sqrt(std::max(0.0, 1.0 - sin2_theta / sin2_max));
  const double sin_alpha = std::sqrt(std::max(0.0, 1.0 - cos_alpha * cos_alpha));
  const double phi = 2.0 * kPi * u.y();
  const Frame frame = Frame::from_z(-to_centre / d);  // z: from the centre toward the point
  const Vec3d n = frame.from_local(Vec3d(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), cos_alpha));
  s.p_light = centre_ + radius_ * n;
  const Vec3d w = s.p_light - ctx.p;
  s.distance = w.norm();
  if (!(s.distance > 0.0)) return std::nullopt;
  s.wi = w / s.distance;
  s.pdf = 1.0 / (2.0 * kPi * one_minus_cos_max);
  if (!std::isfinite(s.pdf)) return std::nullopt;
  s.L = emission_.sample(lambda);
  return s;
}

double SphereLight::pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                           const Vec3d& n_light) const {
  const Vec3d to_centre = centre_ - ctx.p;
  const double d2 = to_centre.squaredNorm();
  const double r2 = radius_ * radius_;
  if (from_inside(ctx.p)) {
    const double dist2 = (p_light - ctx.p).squaredNorm();
    const double len = n_light.norm();
    const double cos_l = len > 0.0 ? std::abs(n_light.dot(wi)) / len : 0.0;
    if (!(cos_l > 0.0) || !(dist2 > 0.0)) return 0.0;
    const double pdf = dist2 / (cos_l * 4.0 * kPi * r2);
    return std::isfinite(pdf) ? pdf : 0.0;
  }
  const double d = std::sqrt(d2);
  const double sin2_max = r2 / d2;
  const double one_minus_cos_max = sin2_max / (1.0 + std::sqrt(std::max(0.0, 1.0 - sin2_max)));
  if (!(detail::one_minus_cos(wi, to_centre / d) <= one_minus_cos_max * (1.0 + kSphereRimSlack))) return 0.0;
  const double pdf = 1.0 / (2.0 * kPi * one_minus_cos_max);
  return std::isfinite(pdf) ? pdf : 0.0;
}

Spectrum SphereLight::L(const Vec3d& p_light, const Vec3d& /*n_light*/, const Vec3d& w, const SampledWavelengths& lambda) const {
  if (!((p_light - centre_).dot(w) > 0.0)) return Spectrum::Zero();
  return emission_.sample(lambda);
}

double SphereLight::power() const { return 4.0 * kPi * kPi * radius_ * radius_ * detail::luminance(emission_.rgb()); }

std::string SphereLight::describe() const {
  return concat("SphereLight(centre=(", centre_.x(), ", ", centre_.y(), ", ", centre_.z(), "), radius=", radius_,
                ", emission=(", emission_.rgb().x(), ", ", emission_.rgb().y(), ", ", emission_.rgb().z(), "))");
}

}  // namespace refracta
