// The sun disc (sun_light.h).
#include "refracta/shading/sun_light.h"

#include "refracta/shading/light_common.h"

namespace refracta {

namespace {
// A direction sampled at the disc's rim is re-measured with rounding of ~1e-16 / (1 - cos alpha)
// relative (1e-11 for the sun): accept it as inside the disc.
constexpr double kSunRimSlack = 1e-9;
}  // namespace

SunLight::SunLight(const Vec3d& direction, const Color& radiance, double angular_diameter, double limb_darkening)
    : radiance_(radiance), angular_diameter_(angular_diameter), limb_(limb_darkening) {
  frame_ = Frame::from_z(detail::check_direction(direction, "SunLight: direction"));
  given_direction_ = direction;
  detail::check_emission(radiance, "SunLight: radiance");
  if (!(angular_diameter >= kMinAngularDiameter && angular_diameter < 180.0)) {
    throw_invalid("SunLight: angular_diameter must be in [", kMinAngularDiameter, ", 180) degrees (got ",
                  angular_diameter, ")");
  }
  if (!(limb_darkening >= 0.0 && limb_darkening <= 1.0)) {
    throw_invalid("SunLight: limb_darkening must be in [0, 1] (got ", limb_darkening, ")");
  }
  const double half = degrees_to_radians(0.5 * angular_diameter);
  const double s = std::sin(0.5 * half);
  one_minus_cos_max_ = 2.0 * s * s;  // accurate for tiny discs
  sin2_max_ = std::sin(half) * std::sin(half);
}

double SunLight::profile(double t) const {
  return (1.0 - limb_ * (1.0 - std::sqrt(std::max(0.0, 1.0 - t)))) / (1.0 - limb_ / 3.0);
}

double SunLight::disc_fraction(const Vec3d& dir) const {
  const double t = detail::one_minus_cos(dir, frame_.n) / one_minus_cos_max_;
  if (!(t <= 1.0 + kSunRimSlack)) return -1.0;
  return std::min(t, 1.0);
}

std::optional<LightLiSample> SunLight::sample_li(const LightSampleContext& /*ctx*/, const Vec2d& u,
                                                 const SampledWavelengths& lambda) const {
  // The mixture p(t) = w_uniform * 1 + (1 - w_uniform) * (3/2) sqrt(1 - t), chosen by u.x.
  const double w_uniform = (1.0 - limb_) / (1.0 - limb_ / 3.0);
  double t;
  if (u.x() < w_uniform) {
    t = u.x() / w_uniform;
  } else {
    const double v = std::min((u.x() - w_uniform) / (1.0 - w_uniform), 1.0);
    t = 1.0 - std::cbrt((1.0 - v) * (1.0 - v));  // inverse of F(t) = 1 - (1 - t)^(3/2)
  }
  t = std::clamp(t, 0.0, 1.0);
  const double omc = t * one_minus_cos_max_;  // 1 - cos(theta)
  const double cos_theta = 1.0 - omc, sin_theta = std::sqrt(std::max(0.0, omc * (2.0 - omc)));
  const double phi = 2.0 * kPi * u.y();
  LightLiSample s;
  s.wi = frame_.from_local(Vec3d(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta)).normalized();
  const double p = profile(t);
  s.pdf = p / (2.0 * kPi * one_minus_cos_max_);
  s.L = radiance_.sample(lambda) * p;
  return s;
}

double SunLight::pdf_li(const LightSampleContext& /*ctx*/, const Vec3d& wi, const Vec3d&, const Vec3d&) const {
  const double t = disc_fraction(wi);
  return t < 0.0 ? 0.0 : profile(t) / (2.0 * kPi * one_minus_cos_max_);
}

Spectrum SunLight::Le(const Vec3d& dir, const SampledWavelengths& lambda) const {
  const double t = disc_fraction(dir);
  return t < 0.0 ? Spectrum(Spectrum::Zero()) : Spectrum(radiance_.sample(lambda) * profile(t));
}

Vec3d SunLight::irradiance_rgb() const { return radiance_.rgb() * (kPi * sin2_max_); }

double SunLight::power() const {
  const double r = scene_radius_;  // one load: another render's preprocess may write it
  return kPi * r * r * detail::luminance(irradiance_rgb());
}

void SunLight::preprocess(const Vec3d& centre, double radius) {
  detail::check_point(centre, "SunLight.preprocess: centre");
  scene_radius_ = detail::check_positive(radius, "SunLight.preprocess: radius");
}

std::string SunLight::describe() const {
  const Vec3d& d = frame_.n;
  return concat("SunLight(direction=(", d.x(), ", ", d.y(), ", ", d.z(), "), radiance=(", radiance_.rgb().x(), ", ",
                radiance_.rgb().y(), ", ", radiance_.rgb().z(), "), angular_diameter=", angular_diameter_,
                ", limb_darkening=", limb_, ")");
}

}  // namespace refracta
