// SunLight (shared/SHADING.md section 5): with angular diameter 2 alpha, the irradiance on a
// surface facing it is radiance * pi sin^2(alpha) whatever the limb darkening.
//
// Limb darkening (linear law): I(mu) = 1 - u (1 - mu), u in [0, 1], mu the cosine on the solar
// surface. With t = (1 - cos theta) / (1 - cos alpha) the fraction of the disc's solid angle
// within the angle theta from its centre, mu = sqrt(1 - t) (the small-angle form of
// sqrt(1 - sin^2 theta / sin^2 alpha), equal to it within 1e-5 for the sun). The mean of I over
// the disc is 1 - u/3, so Le = radiance * I(mu) / (1 - u/3) inside the disc, 0 outside.
//
// Sampling: the cone of half angle alpha, by the limb-darkened density: p(t) = I(mu(t)) /
// (1 - u/3), a mixture of the uniform density (weight (1 - u)/(1 - u/3)) and (3/2) sqrt(1 - t)
// (inverted exactly); pdf_w = p(t) / (2 pi (1 - cos alpha)). Then Le / pdf = radiance * Omega:
// a sun alone is sampled without variance. u = 0 is the uniform cone.
//
// Integrator: an infinite light (kInfinite). Rays that escape the scene along dir see Le(dir)
// (the sun disc, add it to any sky/environment); next-event estimation uses sample_li (distance
// = inf) and MIS with pdf_li(ctx, wi, ., .) (p_light, n_light unused). In curved air, evaluate
// Le and pdf_li along the shadow ray's exit direction. power() needs preprocess() (scene radius;
// 1 m until then, as Mitsuba's unit bounding sphere).
#pragma once

#include "refracta/core/frame.h"
#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

#include <atomic>

namespace refracta {

// The sun: a disc at infinity toward direction, mean radiance [W/(m^2 sr)] (a colour) over the
// disc, angular_diameter [deg], linear limb darkening u in [0, 1] (I(mu) = 1 - u (1 - mu)).
class SunLight final : public Light {
 public:
  // [deg] The smallest disc: its solid angle (4e-12 sr) keeps the sampling density 1 / solid
  // angle finite with room to spare (a 1e-300 deg disc's underflows to 0: pdf inf). The sun seen
  // from Neptune is 0.018 deg; a smaller source is a point and wants no disc.
  static constexpr double kMinAngularDiameter = 1e-4;

  // direction toward the sun (non-zero; normalised); angular_diameter [deg] in
  // [kMinAngularDiameter, 180); limb_darkening u in [0, 1].
  SunLight(const Vec3d& direction, const Color& radiance, double angular_diameter = 0.53,
           double limb_darkening = 0.0);

  LightType type() const override { return LightType::kInfinite; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  Spectrum Le(const Vec3d& dir, const SampledWavelengths& lambda) const override;
  // pi R^2 * Y(radiance) * pi sin^2(alpha): the power through the scene's disc (exact for u = 0).
  double power() const override;
  void preprocess(const Vec3d& centre, double radius) override;
  std::string describe() const override;

  const Vec3d& direction() const { return frame_.n; }
  const Vec3d& given_direction() const { return given_direction_; }  // as passed to the constructor
  const Color& radiance() const { return radiance_; }
  double angular_diameter() const { return angular_diameter_; }
  double limb_darkening() const { return limb_; }
  double solid_angle() const { return 2.0 * kPi * one_minus_cos_max_; }
  // The irradiance [W/m^2] (as RGB) on a surface facing the sun.
  Vec3d irradiance_rgb() const;

 private:
  // p(t) / mean: the relative radiance at the disc fraction t in [0, 1].
  double profile(double t) const;
  // t of a direction, or < 0 outside the disc.
  double disc_fraction(const Vec3d& dir) const;

  Frame frame_;
  Vec3d given_direction_;
  Color radiance_;
  double angular_diameter_, limb_;
  double one_minus_cos_max_, sin2_max_;
  std::atomic<double> scene_radius_{1.0};  // preprocess writes it while other renders may read it
};

}  // namespace refracta
