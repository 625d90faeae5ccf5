// The constant environment (constant_environment.h).
#include "refracta/shading/constant_environment.h"

#include "refracta/core/error.h"
#include "refracta/core/frame.h"
#include "refracta/shading/light_common.h"

namespace refracta {

ConstantEnvironment::Sampling ConstantEnvironment::sampling_from(const std::string& name) {
  if (name != "cosine" && name != "uniform") {
    throw_invalid("ConstantEnvironment: sampling must be 'cosine' or 'uniform' (got '", name, "')");
  }
  return name == "cosine" ? Sampling::kCosine : Sampling::kUniform;
}

ConstantEnvironment::ConstantEnvironment(const Color& radiance, Sampling sampling)
    : radiance_(radiance), sampling_(sampling) {
  detail::check_emission(radiance, "ConstantEnvironment: radiance");
}

std::optional<LightLiSample> ConstantEnvironment::sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                                            const SampledWavelengths& lambda) const {
  LightLiSample s;
  if (cosine(ctx)) {
    const Vec3d n = ctx.n.normalized();
    const Vec3d local = sample_cosine_hemisphere(u);
    if (!(local.z() > 0.0)) return std::nullopt;
    s.wi = Frame::from_z(n).from_local(local).normalized();
    s.pdf = cosine_hemisphere_pdf(n.dot(s.wi));
    if (!(s.pdf > 0.0)) return std::nullopt;
  } else {
    s.wi = sample_uniform_sphere(u);
    s.pdf = uniform_sphere_pdf();
  }
  s.L = radiance_.sample(lambda);
  return s;
}

double ConstantEnvironment::pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d&, const Vec3d&) const {
  if (cosine(ctx)) return cosine_hemisphere_pdf(ctx.n.normalized().dot(wi));
  return uniform_sphere_pdf();
}

Spectrum ConstantEnvironment::Le(const Vec3d& /*dir*/, const SampledWavelengths& lambda) const { return radiance_.sample(lambda); }

double ConstantEnvironment::power() const {
  const double r = scene_radius_;  // one load: another render's preprocess may write it
  return 4.0 * kPi * kPi * r * r * detail::luminance(radiance_.rgb());
}

void ConstantEnvironment::preprocess(const Vec3d& centre, double radius) {
  detail::check_point(centre, "ConstantEnvironment.preprocess: centre");
  scene_radius_ = detail::check_positive(radius, "ConstantEnvironment.preprocess: radius");
}

std::string ConstantEnvironment::describe() const {
  return concat("ConstantEnvironment(radiance=(", radiance_.rgb().x(), ", ", radiance_.rgb().y(), ", ", radiance_.rgb().z(),
                "), sampling=", sampling_ == Sampling::kCosine ? "'cosine'" : "'uniform'", ")");
}

}  // namespace refracta
