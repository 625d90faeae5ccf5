// Direct lighting with MIS (direct_lighting.h).
#include "refracta/render/direct_lighting.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

constexpr double kMinBendSine = 1e-3;  // below this exit elevation the map's Jacobian is singular: no pre-bend

double sqr(double x) { return x * x; }

}  // namespace

DirectLighting::DirectLighting(const RenderScene& scene, const Caster& caster, const RenderOptions& options)
    : scene_(scene), caster_(caster), options_(options) {
  std::vector<double> power;
  for (const auto& light : scene.lights()) power.push_back(std::max(light->power(), 0.0));
  if (!power.empty()) select_ = PiecewiseConstant1D(power);
  pre_bend_ = caster.curved() && caster.field()->height_only();
}

Vec3d DirectLighting::launch_toward(const Vec3d& p, const Vec3d& exit, double* jacobian) const {
  *jacobian = 1.0;
  if (!pre_bend_ || exit.y() < kMinBendSine) return exit;
  double n_p, n_top, dn;
  const IndexField& field = *caster_.field();
  field.evaluate_height(p.y(), &n_p, &dn);
  field.evaluate_height(p.y() + options_.max_length * exit.y(), &n_top, &dn);
  // n(p) cos e_launch = n_top cos e_exit, same azimuth.
  const double cos_exit = std::sqrt(std::max(0.0, 1.0 - sqr(exit.y())));
  const double cos_launch = std::min(1.0, n_top * cos_exit / n_p);
  const double sin_launch = std::sqrt(std::max(0.0, 1.0 - sqr(cos_launch)));
  if (sin_launch < kMinBendSine) return exit;
  const double scale = cos_exit > 0.0 ? cos_launch / cos_exit : 0.0;
  const Vec3d launch(exit.x() * scale, sin_launch, exit.z() * scale);
  // d omega_exit / d omega_launch = d sin e_exit / d sin e_launch = k^2 sin e_l / sin e_x, k = n_p / n_top.
  *jacobian = sqr(n_p / n_top) * sin_launch / exit.y();
  return launch.normalized();
}

double DirectLighting::exit_jacobian(const Vec3d& p, const Vec3d& launch) const {
  if (!pre_bend_ || launch.y() < kMinBendSine) return 1.0;
  double n_p, n_top, dn;
  const IndexField& field = *caster_.field();
  field.evaluate_height(p.y(), &n_p, &dn);
  const double cos_launch = std::sqrt(std::max(0.0, 1.0 - sqr(launch.y())));
  // The exit elevation from the invariant (n_top from the straight estimate of the end height).
  field.evaluate_height(p.y() + options_.max_length * launch.y(), &n_top, &dn);
  const double cos_exit = std::min(1.0, n_p * cos_launch / n_top);
  const double sin_exit = std::sqrt(std::max(0.0, 1.0 - sqr(cos_exit)));
  if (sin_exit < kMinBendSine) return 1.0;
  return sqr(n_p / n_top) * launch.y() / sin_exit;
}

Spectrum DirectLighting::sample_light(const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                                      const SampledWavelengths& lambda, const Vec2d& u_light, double u_pick,
                                      const LightVisibility* visibility) const {
  if (scene_.lights().empty()) return Spectrum::Zero();
  size_t index;
  select_.sample(u_pick, nullptr, &index);
  const double pick = pick_probability(index);
  if (!(pick > 0.0)) return Spectrum::Zero();
  const Light& light = *scene_.lights()[index];
  LightSampleContext ctx;
  ctx.p = si.p;
  ctx.n = si.n_toward_wo();
  const auto ls = light.sample_li(ctx, u_light, lambda);
  if (!ls || !(ls->pdf > 0.0) || !(ls->L.maxCoeff() > 0.0)) return Spectrum::Zero();
  double light_pdf = ls->pdf;
  Spectrum L = ls->L;
  Vec3d wi = ls->wi;
  double visible = 1.0;
  const std::optional<double> given = visibility && *visibility ? (*visibility)(index, si, wi) : std::nullopt;
  if (light.is_infinite()) {
    // Launch the curved shadow ray so that it leaves toward the sampled direction.
    double jacobian = 1.0;
    wi = launch_toward(si.p, ls->wi, &jacobian);
    light_pdf *= jacobian;
    if (given) {
      visible = *given;
    } else if (caster_.curved()) {
      const PathEnd end = caster_.cast(si.offset_toward(wi), wi);
      if (end.hit) return Spectrum::Zero();
      L = light.Le(end.direction, lambda);  // along the exit direction
      double n_p = caster_.ior(si.p), n_top = n_p, dn;
      if (pre_bend_) caster_.field()->evaluate_height(si.p.y() + options_.max_length * std::max(end.direction.y(), 0.0), &n_top, &dn);
      L *= sqr(n_p / n_top);  // basic radiance L / n^2 is conserved (Ament et al. 2014)
    } else {
      visible = caster_.scene().occluded(si.offset_toward(wi), wi, 1e7) ? 0.0 : 1.0;
    }
  } else if (given) {
    visible = *given;
  } else {
    const Vec3d from = si.offset_toward(wi);
    const double distance = (ls->p_light - from).norm() * (1.0 - 1e-6) - 1e-6;
    visible = caster_.occluded_straight(from, wi, distance) ? 0.0 : 1.0;
  }
  if (!(visible > 0.0) || !(L.maxCoeff() > 0.0)) return Spectrum::Zero();
  const Spectrum f = bsdf.f(si.wo, wi) * std::abs(wi.dot(bsdf.frame.n));
  if (!(f.maxCoeff() > 0.0)) return Spectrum::Zero();
  const double pdf = pick * light_pdf;
  if (light.is_delta()) return f * L * (visible / pdf);
  const double weight = power_heuristic(1, pdf, 1, bsdf.pdf(si.wo, wi));
  return f * L * (visible * weight / pdf);
}

Spectrum DirectLighting::escaped(const PathEnd& end, const Vec3d& launch_dir, const SurfaceInteraction* from,
                                 double bsdf_pdf, bool specular, const SampledWavelengths& lambda) const {
  Spectrum L = Spectrum::Zero();
  const auto& lights = scene_.lights();
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!lights[i]->is_infinite()) continue;
    const Spectrum Le = lights[i]->Le(end.direction, lambda);
    if (!(Le.maxCoeff() > 0.0)) continue;
    if (!from || specular) {
      L += Le;
      continue;
    }
    LightSampleContext ctx;
    ctx.p = from->p;
    ctx.n = from->n_toward_wo();
    const double light_pdf = pick_probability(i) * lights[i]->pdf_li(ctx, end.direction, Vec3d::Zero(), Vec3d::Zero()) *
                             exit_jacobian(from->p, launch_dir);
    L += Le * power_heuristic(1, bsdf_pdf, 1, light_pdf);
  }
  return L;
}

Spectrum DirectLighting::emitted(const SurfaceInteraction& si, const SurfaceInteraction* from, double bsdf_pdf,
                                 bool specular, const SampledWavelengths& lambda) const {
  const int index = scene_.light_of(si.geometry);
  if (index < 0) return Spectrum::Zero();
  const Light& light = *scene_.lights()[size_t(index)];
  const Spectrum Le = light.L(si.p, si.n, si.wo, lambda);
  if (!(Le.maxCoeff() > 0.0) || !from || specular) return Le;
  LightSampleContext ctx;
  ctx.p = from->p;
  ctx.n = from->n_toward_wo();
  const Vec3d wi = (si.p - from->p).normalized();
  const double light_pdf = pick_probability(size_t(index)) * light.pdf_li(ctx, wi, si.p, si.n);
  return Le * power_heuristic(1, bsdf_pdf, 1, light_pdf);
}

}  // namespace refracta
