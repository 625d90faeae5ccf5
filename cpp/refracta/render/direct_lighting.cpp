// Direct lighting with MIS (direct_lighting.h).
#include "refracta/render/direct_lighting.h"

#include "refracta/core/parallel.h"
#include "refracta/shading/sun_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace refracta {

namespace {

constexpr double kMinBendSine = 1e-3;     // below this exit elevation the map's Jacobian is singular: no pre-bend
constexpr double kShadowEpsilon = 1e-4;  // shadow rays to finite lights end this fraction short (pbrt's ShadowEpsilon)
// Light below the horizon over a spherical Earth (DirectLighting::launch_below_horizon): the
// launch elevations searched [rad] (refraction at the horizon is ~0.6 deg, the sun's disc 0.53),
// the exit elevation's tolerance [rad] (1/500 of the sun's disc) and the step of the Jacobian's
// difference quotient [rad].
constexpr double kHighestLaunch = 0.03;
constexpr double kRefractionGuess = 0.01;  // [rad] the first launch: this far above the exit sought
constexpr double kExitTolerance = 1e-5;
// The lowest launch [rad]: half the exit's tolerance above level (a level ray would start on the
// surface's far side, SurfaceInteraction::offset_toward).
constexpr double kLowestLaunch = 0.5 * kExitTolerance;
constexpr double kJacobianStep = 2e-5;
constexpr int kMaxBendIterations = 16;
// LowestLaunches: start-height intervals tabulated, and the scatter of a cast's exit allowed
// beside the interpolation's measured error [rad] (a tenth of the search's tolerance).
constexpr int kLowestLaunchIntervals = 32;
constexpr double kLowestLaunchScatter = 0.1 * kExitTolerance;

}  // namespace

std::shared_ptr<const LowestLaunches> LowestLaunches::build(const Scene& scene,
                                                            const std::vector<const Caster*>& casters,
                                                            const std::vector<double>& scales) {
  if (casters.empty() || casters.size() != scales.size()) return nullptr;
  if (!std::isfinite(scene.lowest()) || !std::isfinite(scene.highest())) return nullptr;
  // offset_toward lifts a point by kSurfaceOffsetAbsolute plus kSurfaceOffsetRelative of |n| . extent
  // (offset_point; |n|_1 <= sqrt 3): the start heights from the lowest surface's least lift (a cast
  // from the surface itself meets it) to the highest's most.
  const double reach = std::max(scene.lower().cwiseAbs().maxCoeff(), scene.upper().cwiseAbs().maxCoeff());
  const double lo = scene.lowest() + kSurfaceOffsetAbsolute;
  const double hi = scene.highest() + kSurfaceOffsetAbsolute + kSurfaceOffsetRelative * std::sqrt(3.0) * reach;
  auto table = std::make_shared<LowestLaunches>();
  table->lo_ = lo;
  table->step_ = (hi - lo) / kLowestLaunchIntervals;
  table->scales_ = scales;
  table->margins_.assign(kLowestLaunchIntervals, 0.0);
  // Each interval's midpoint is cast too: how far the exit strays from the chord between its ends
  // (the interpolation's error, measured) -- 4x the worst over the scales, plus the casts' scatter,
  // is the margin least_exit keeps there. An interval where a path meets the scene (a cast from
  // just above a large surface can meet it within float precision) or strays by more than the
  // search's tolerance is not tabulated (NaN: its casts are made).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Every node and midpoint of every scale (each a pure function of its height and scale: the
  // table is the same whichever thread casts what), then the margins.
  const size_t nodes = 2 * kLowestLaunchIntervals + 1;
  std::vector<std::vector<double>> exits(casters.size(), std::vector<double>(nodes, nan));
  WorkControl control;  // the caller's cancel flags stay in force (parallel_for_each)
  parallel_for_each(int64_t(casters.size() * nodes), 1, control, [&](int64_t index) {
    const size_t i = size_t(index);
    const double h = lo + 0.5 * double(i % nodes) * table->step_;
    exits[i / nodes][i % nodes] = start_frame_exit(*casters[i / nodes], h, kLowestLaunch);
  });
  for (const std::vector<double>& at : exits) {
    for (size_t j = 0; j < size_t(kLowestLaunchIntervals); ++j) {
      const double a = at[2 * j], middle = at[2 * j + 1], b = at[2 * j + 2];
      double& margin = table->margins_[j];
      margin = std::isnan(a) || std::isnan(middle) || std::isnan(b) || std::isnan(margin)
                   ? nan
                   : std::max(margin, std::abs(middle - 0.5 * (a + b)));
    }
    std::vector<double> ends;
    for (size_t j = 0; j < nodes; j += 2) ends.push_back(at[j]);
    table->exits_.push_back(std::move(ends));
  }
  size_t kept = 0;
  for (double& margin : table->margins_) {
    margin = margin <= kExitTolerance ? 4.0 * margin + kLowestLaunchScatter : nan;
    kept += std::isfinite(margin) ? 1 : 0;
  }
  return kept > 0 ? table : nullptr;
}

double LowestLaunches::least_exit(double h, double scale) const {
  const double u = (h - lo_) / step_;
  if (!(u >= 0.0 && u <= kLowestLaunchIntervals) || !(scale >= scales_.front() && scale <= scales_.back())) {
    return -std::numeric_limits<double>::infinity();
  }
  const size_t j = std::min(size_t(u), size_t(kLowestLaunchIntervals - 1));
  if (!std::isfinite(margins_[j])) return -std::numeric_limits<double>::infinity();
  const size_t last = scales_.size() - 1;  // one scale: the render's own air
  const size_t k =
      last == 0 ? 0 : std::min(size_t(std::upper_bound(scales_.begin(), scales_.end(), scale) - scales_.begin()), last) - 1;
  const double w = u - double(j);
  auto at = [&](size_t scale_index) {
    const std::vector<double>& exits = exits_[scale_index];
    return (1.0 - w) * exits[j] + w * exits[j + 1];
  };
  // Between two close scales the exit moves monotonically with the air's n - 1 (hero_casters.h):
  // it lies between theirs.
  return std::min(at(k), at(std::min(k + 1, last))) - margins_[j];
}

DirectLighting::DirectLighting(const RenderScene& scene, const Caster& caster, const RenderOptions& options,
                               const LightVisibility* visibility)
    : scene_(scene),
      caster_(caster),
      options_(options),
      visibility_(visibility ? *visibility : *this),
      select_(scene.lights(), LightSampler::Strategy::kKind) {
  // Pre-bent through the height-only air (fields with local regions: outside them; a path through
  // a spot leaves a little off the sampled direction, and is evaluated where it does leave).
  // Not over a spherical Earth (CurvedEarth): its paths leave the air turned by their central angle
  // as well, which the invariant alone does not give; they launch along the sample (unbiased: the
  // light is evaluated along the exit, in the world frame).
  pre_bend_ = caster.curved() && caster.layered() != nullptr && !std::isfinite(caster.layered()->earth_radius());
  spherical_ = caster.curved() && caster.field() != nullptr && std::isfinite(caster.field()->earth_radius());
  all_lights_ = options.transport == Transport::kDirect;
  // The sun's disc, small beside the refraction at the horizon: its samples below a point's horizon
  // are launched along the rising path that leaves toward them (launch_below_horizon). Samples of
  // the sky there meet the sea (its light from below the horizon arrives by BSDF sampling alone).
  if (spherical_ && scene.sun() != nullptr) bent_sun_ = scene.sun();
}

double DirectLighting::distant_ior(const Vec3d& p, const Vec3d& exit) const {
  const double n_p = caster_.ior(p);
  if (!pre_bend_) return n_p;
  double n_top = n_p, dn;
  try {
    caster_.layered()->evaluate_height(p.y() + options_.max_length * std::max(exit.y(), 0.0), &n_top, &dn);
  } catch (const std::exception&) {  // beyond the field's modelled heights: its top is the last n known
    for (double h = p.y() + options_.max_length * std::max(exit.y(), 0.0); h > p.y(); h = p.y() + 0.5 * (h - p.y())) {
      try {
        caster_.layered()->evaluate_height(h, &n_top, &dn);
        break;
      } catch (const std::exception&) {
      }
    }
  }
  return n_top;
}

Vec3d DirectLighting::launch_toward(const Vec3d& p, const Vec3d& exit, double* jacobian) const {
  *jacobian = 1.0;
  if (!pre_bend_ || exit.y() < kMinBendSine) return exit;
  const double n_p = caster_.ior(p), n_top = distant_ior(p, exit);
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
  const double n_p = caster_.ior(p), n_top = distant_ior(p, launch);
  const double cos_launch = std::sqrt(std::max(0.0, 1.0 - sqr(launch.y())));
  // The exit elevation from the invariant (n_top from the straight estimate of the end height).
  const double cos_exit = std::min(1.0, n_p * cos_launch / n_top);
  const double sin_exit = std::sqrt(std::max(0.0, 1.0 - sqr(cos_exit)));
  if (sin_exit < kMinBendSine) return 1.0;
  return sqr(n_p / n_top) * launch.y() / sin_exit;
}

std::optional<Vec3d> DirectLighting::launch_bent_sun(const SurfaceInteraction& si, const Vec3d& exit,
                                                     const Eigen::Matrix3d& to_world, double* jacobian) const {
  // Below p's horizon: the setting sun, seen by the refraction of its light alone (and its glitter
  // on the sea). The rising path that leaves along the sample, found by its casts.
  if (exit.y() < 0.0) return launch_below_horizon(si, exit, to_world, jacobian);
  // Above it: the launch the sun's exit map sends toward the sample, where it covers it.
  if (sun_exits_ && sun_exits_->covers(si.p, *scale_, exit)) {
    const auto launch = sun_exits_->launch(si.p, to_world, *scale_, exit);
    if (!launch) return std::nullopt;  // rare: no launch found for a covered exit (none has this density)
    *jacobian = launch->jacobian;
    return launch->direction;
  }
  *jacobian = 1.0;
  return exit;
}

double DirectLighting::bent_sun_pdf(const SurfaceInteraction& from, const Vec3d& launch_dir, const Vec3d& exit_here,
                                    const LightSampleContext& ctx, const Eigen::Matrix3d& to_world) const {
  // The light samples that can launch along launch_dir, by where their exit lay (launch_bent_sun).
  const Light& sun = *bent_sun_;
  const Vec3d horizontal(launch_dir.x(), 0.0, launch_dir.z());
  const double launch = std::asin(std::clamp(launch_dir.y(), -1.0, 1.0));
  double pdf = 0.0;
  // Above p's horizon through the exit map: the density at the exit it maps this launch to.
  Vec3d exit;
  if (sun_exits_) {
    const auto jacobian = sun_exits_->density(from.p, to_world, *scale_, launch_dir, &exit);
    if (jacobian && exit.y() >= 0.0) pdf += sun.pdf_li(ctx, to_world * exit, Vec3d::Zero(), Vec3d::Zero()) * *jacobian;
  }
  // Above it where the map does not cover the sample: launched along the sample itself.
  if (launch_dir.y() >= 0.0 && !(sun_exits_ && sun_exits_->covers(from.p, *scale_, launch_dir))) {
    pdf += sun.pdf_li(ctx, to_world * launch_dir, Vec3d::Zero(), Vec3d::Zero());
  }
  // Below it (launch_below_horizon): the rising path that leaves along the sample, whose exit this
  // path's own is.
  if (exit_here.y() < 0.0 && launch >= kLowestLaunch && launch <= kHighestLaunch) {
    const double pdf_exit = sun.pdf_li(ctx, to_world * exit_here, Vec3d::Zero(), Vec3d::Zero());
    if (pdf_exit > 0.0) {
      const double below = std::asin(std::clamp(exit_here.y(), -1.0, 1.0));
      pdf += pdf_exit * std::max(bend_jacobian(from, horizontal.normalized(), launch, below, to_world), 0.0);
    }
  }
  return pdf;
}

double DirectLighting::exit_elevation(const SurfaceInteraction& si, const Vec3d& across, double elevation,
                                      const Eigen::Matrix3d& to_world) const {
  const Vec3d launch = std::cos(elevation) * across + Vec3d(0.0, std::sin(elevation), 0.0);
  const PathEnd end = caster_.cast(si.offset_toward(launch), launch);
  if (end.hit) return -std::numeric_limits<double>::infinity();
  return std::asin(std::clamp(Vec3d(to_world.transpose() * end.direction).y(), -1.0, 1.0));
}

std::optional<Vec3d> DirectLighting::launch_below_horizon(const SurfaceInteraction& si, const Vec3d& exit,
                                                          const Eigen::Matrix3d& to_world, double* jacobian) const {
  const Vec3d across = Vec3d(exit.x(), 0.0, exit.z()).normalized();
  const double target = std::asin(std::clamp(exit.y(), -1.0, 1.0));
  // The exit elevation rises with the launch elevation from the lowest launch that clears the
  // scene up (the ray's vertical plane holds the Earth's centre: the azimuth is kept). Secant
  // steps from a guess, kept inside the bracket [lo, hi] the evaluations have narrowed (false
  // position, or bisection while the lower end met the sea); the light has set for si when the
  // bracket closes at the lowest launch that clears the scene with the exit still too high.
  double lo = kLowestLaunch, hi = kHighestLaunch;
  double f_lo = -std::numeric_limits<double>::infinity(), f_hi = std::numeric_limits<double>::quiet_NaN();
  double e = std::clamp(target + kRefractionGuess, 0.05 * kHighestLaunch, 0.95 * kHighestLaunch);
  double previous_e = 0.0, previous_f = std::numeric_limits<double>::quiet_NaN();
  // The lowest launch first: where it already leaves above the sample, every rising launch does
  // (the exit rises with the launch) and the light has set for si -- one cast, where bisecting
  // the bracket down to kExitTolerance took ~10 (a sun 0.74 deg below the true horizon seen from
  // the sea: every sample). Otherwise it is the bracket's lower end. A spectral render's table of
  // the lowest launches (LowestLaunches) answers the first case without the cast where its bound
  // already leaves above the sample.
  if (lowest_launches_) {
    const Vec3d lowest = std::cos(lo) * across + Vec3d(0.0, std::sin(lo), 0.0);
    if (lowest_launches_->least_exit(si.offset_toward(lowest).y(), *scale_) - target > kExitTolerance) {
      return std::nullopt;
    }
  }
  if (const double f = exit_elevation(si, across, lo, to_world) - target; std::isfinite(f)) {
    if (f > kExitTolerance) return std::nullopt;
    if (f >= -kExitTolerance) {
      *jacobian = bend_jacobian(si, across, lo, f + target, to_world);
      if (!(*jacobian > 0.0)) return std::nullopt;
      return Vec3d(std::cos(lo) * across + Vec3d(0.0, std::sin(lo), 0.0));
    }
    f_lo = previous_f = f;
    previous_e = lo;
  }
  for (int i = 0; i < kMaxBendIterations; ++i) {
    const double f = exit_elevation(si, across, e, to_world) - target;
    if (std::abs(f) <= kExitTolerance) {
      *jacobian = bend_jacobian(si, across, e, f + target, to_world);
      if (!(*jacobian > 0.0)) return std::nullopt;
      return Vec3d(std::cos(e) * across + Vec3d(0.0, std::sin(e), 0.0));
    }
    if (f > 0.0) {
      hi = e, f_hi = f;
    } else {
      lo = e, f_lo = f;
    }
    if (hi - lo < kExitTolerance) return std::nullopt;
    double next = std::numeric_limits<double>::quiet_NaN();
    if (std::isfinite(f) && std::isfinite(previous_f) && f != previous_f) {
      next = e - f * (e - previous_e) / (f - previous_f);
    }
    if (!(next > lo && next < hi)) {
      next = std::isfinite(f_lo) && std::isfinite(f_hi) ? (lo * f_hi - hi * f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
    }
    previous_e = e, previous_f = f;
    e = next;
  }
  return std::nullopt;
}

double DirectLighting::bend_jacobian(const SurfaceInteraction& si, const Vec3d& across, double launch, double exit,
                                     const Eigen::Matrix3d& to_world) const {
  // d omega_exit / d omega_launch = cos e_exit d e_exit / (cos e_launch d e_launch), azimuth kept.
  const double next = exit_elevation(si, across, launch + kJacobianStep, to_world);
  if (!std::isfinite(next)) return 0.0;
  return std::cos(exit) * (next - exit) / (std::cos(launch) * kJacobianStep);
}

Eigen::Matrix3d DirectLighting::to_world_frame(const Vec3d& p) const {
  return spherical_ ? caster_.field()->sky_frame(p) : Eigen::Matrix3d::Identity();
}

Spectrum DirectLighting::sample_lights(const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                                       const SampledWavelengths& lambda, Sampler& sampler) const {
  const size_t count = scene_.lights().size();
  if (count == 0) return Spectrum::Zero();
  if (all_lights_) {
    Spectrum sum = Spectrum::Zero();
    std::optional<Eigen::Matrix3d> frame;  // p's frame, turned once for all the distant lights
    for (size_t i = 0; i < count; ++i) {
      sum += sample_one(i, 1.0, si, bsdf, lambda, sampler.uniform2(), true, &frame);
    }
    return sum;
  }
  const size_t index = select_.sample(sampler.uniform())->index;
  const double pick = pick_probability(index);
  if (!(pick > 0.0)) return Spectrum::Zero();
  return sample_one(index, pick, si, bsdf, lambda, sampler.uniform2(), true);
}

Spectrum DirectLighting::sample_light(size_t index, const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                                      const SampledWavelengths& lambda, const Vec2d& u, bool mis) const {
  return sample_one(index, 1.0, si, bsdf, lambda, u, mis);
}

Spectrum DirectLighting::sample_one(size_t index, double pick, const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                                    const SampledWavelengths& lambda, const Vec2d& u_light, bool mis,
                                    std::optional<Eigen::Matrix3d>* frame) const {
  const Light& light = *scene_.lights()[index];
  LightSampleContext ctx;
  ctx.p = si.p;
  ctx.n = si.n_toward_wo();
  // A distant light is sampled in the world frame; over a spherical Earth the sample is then turned
  // into p's frame (a rotation: its density is unchanged).
  const bool turned = spherical_ && light.is_infinite();
  std::optional<Eigen::Matrix3d> own_frame;
  if (!frame) frame = &own_frame;
  if (turned && !*frame) *frame = to_world_frame(si.p);
  const Eigen::Matrix3d to_world = turned ? **frame : Eigen::Matrix3d::Identity();
  if (turned) ctx.n = to_world * ctx.n;
  auto ls = light.sample_li(ctx, u_light, lambda);
  if (!ls || !(ls->pdf > 0.0) || !(ls->L.maxCoeff() > 0.0)) return Spectrum::Zero();
  // The sample carries the ground's sky or sun; seen from a raised point, the raised one's (a
  // curved shadow ray's arriving() evaluates it again along its exit).
  if (raised_sky_) ls->L = raised_sky_->seen_from(light, si.p.y(), ls->wi, ls->L, lambda);
  double light_pdf = ls->pdf;
  Vec3d wi = ls->wi;
  double jacobian = 1.0;
  // Launch the curved shadow ray toward a distant light so that it leaves along the sample.
  if (light.is_infinite()) {
    const Vec3d exit = turned ? Vec3d(to_world.transpose() * ls->wi) : ls->wi;
    if (turned && &light == bent_sun_) {
      const auto launch = launch_bent_sun(si, exit, to_world, &jacobian);
      if (!launch) return Spectrum::Zero();
      wi = *launch;
    } else {
      wi = launch_toward(si.p, exit, &jacobian);
    }
  }
  light_pdf *= jacobian;
  // Light leaking through a shading normal is refused here as the integrators refuse their BSDF
  // samples: light samples alone took it, MIS-weighted, so part of it counted (a review: a quad
  // with tilted vertex normals under a map bright below the horizon, 0.78 where refusing it on
  // both sides gives 0.45). The shading frame decides what the BSDF takes as transmitted.
  const Vec3d& ns = bsdf.frame.n;
  if (si.leaks(wi, (wi.dot(ns) > 0.0) != (si.wo.dot(ns) > 0.0))) return Spectrum::Zero();
  // The BSDF first: a shadow test (through curved air, the expensive part) only where it counts.
  const Spectrum f = bsdf.f(si.wo, wi) * std::abs(wi.dot(bsdf.frame.n));
  if (!(f.maxCoeff() > 0.0)) return Spectrum::Zero();
  const Spectrum L = visibility_.arriving(index, si, wi, *ls, lambda);
  if (!(L.maxCoeff() > 0.0)) return Spectrum::Zero();
  const double pdf = pick * light_pdf;
  if (!mis || light.is_delta()) return f * L / pdf;
  const double weight = power_heuristic(1, pdf, 1, bsdf.pdf(si.wo, wi));
  return f * L * (weight / pdf);
}

Spectrum DirectLighting::arriving(size_t light, const SurfaceInteraction& si, const Vec3d& wi, const LightLiSample& ls,
                                  const SampledWavelengths& lambda) const {
  const Light& source = *scene_.lights()[light];
  if (source.is_infinite()) {
    if (caster_.curved()) {
      const PathEnd end = caster_.cast(si.offset_toward(wi), wi, 0.0, 0.0, si.cone_width_along(wi));
      if (end.hit) return Spectrum::Zero();
      // Along the exit direction; basic radiance L / n^2 is conserved (Ament et al. 2014).
      return distant_Le(source, si.p.y(), end.direction, lambda) * sqr(caster_.ior(si.p) / distant_ior(si.p, end.direction));
    }
    return caster_.scene().occluded(si.offset_toward(wi), wi, kSceneReach) ? Spectrum::Zero() : ls.L;
  }
  // Aim the shadow ray from the offset point at the light point itself: a ray parallel to wi
  // from the offset origin would meet the light's surface up to offset / cos short of
  // |p_light - from| and count the light as its own blocker (a Diffuse floor 1 m under a quad
  // light lost 21% of its irradiance, most of it at grazing angles). Stop short of the light by
  // kShadowEpsilon of the length (float hit precision at grazing incidence).
  const Vec3d from = si.offset_toward(wi);
  const Vec3d to_light = ls.p_light - from;
  const double length = to_light.norm();
  if (length > 0.0 && caster_.occluded_straight(from, to_light / length, length * (1.0 - kShadowEpsilon))) {
    return Spectrum::Zero();
  }
  if (const AerialPerspective* air = scene_.aerial_perspective()) {
    return ls.L * air->transmittance(si.p, ls.p_light, caster_.air_frame(), lambda);
  }
  return ls.L;
}

Spectrum DirectLighting::escaped(const PathEnd& end, const Vec3d& launch_dir, const SurfaceInteraction* from,
                                 double from_y, double bsdf_pdf, bool specular, const SampledWavelengths& lambda) const {
  Spectrum L = Spectrum::Zero();
  const auto& lights = scene_.lights();
  std::optional<Eigen::Matrix3d> frame;  // from's frame, turned once for all the distant lights
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!lights[i]->is_infinite()) continue;
    const Spectrum Le = distant_Le(*lights[i], from_y, end.direction, lambda);
    if (!(Le.maxCoeff() > 0.0)) continue;
    if (!from || specular) {
      L += Le;
      continue;
    }
    LightSampleContext ctx;
    ctx.p = from->p;
    if (!frame) frame = to_world_frame(from->p);
    const Eigen::Matrix3d& to_world = *frame;
    ctx.n = to_world * from->n_toward_wo();
    // The density with which light sampling would have launched this same ray: pre-bent, that of
    // the exit direction it was aimed at (times the map's Jacobian); the sun over a spherical
    // Earth, by where its sample's exit lay (bent_sun_pdf); otherwise light samples launch along
    // the sampled direction itself, so its density at launch_dir (in the world frame). Over a
    // spherical Earth the two differ by the whole refraction: weighting the BSDF ray that reflects
    // a setting sun off the water by the density at its exit direction gave it ~0.3 % of its
    // radiance, and the sea lost its glitter path.
    double light_pdf =
        pre_bend_ ? lights[i]->pdf_li(ctx, end.direction, Vec3d::Zero(), Vec3d::Zero()) *
                        exit_jacobian(from->p, launch_dir)
        : lights[i].get() == bent_sun_
            ? bent_sun_pdf(*from, launch_dir, Vec3d(to_world.transpose() * end.direction), ctx, to_world)
            : lights[i]->pdf_li(ctx, to_world * launch_dir, Vec3d::Zero(), Vec3d::Zero());
    light_pdf *= pick_probability(i);
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
