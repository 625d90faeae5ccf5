// Direct lighting shared by the integrators: one light chosen in proportion to its power and
// sampled (next-event estimation), emitters met by BSDF-sampled rays, both weighted by the power
// heuristic (Veach 1997, ch. 9) so that neither strategy is counted twice.
//
// Connections: finite lights (point, spot, area, sphere) by a straight shadow segment. The air
// bends such a connection by at most L^2 |grad n| / 8 (a 10 m connection through a 10 K / 10 cm
// hot road layer, |grad n| <= 9e-5 /m: 1.04 mm measured 1 cm above the road); the irradiance the
// straight connection misses is the layer's focusing of the lamp's light: +0.9 to 1.3 % at 10 m
// and +9 % at 30 m for lamps a few cm above a hot road, under 0.2 % for lamps 1.5 m up
// (tests/render/test_shading_09_curved_connections.py solves the curved connections);
// distant lights (sun, environment, sky) by a curved shadow ray through the caster, the light
// evaluated along the path's exit direction. In height-only fields the launch direction that
// leaves toward a sampled direction follows from the invariant n(h) cos e = const ("pre-bent",
// shared/SHADING.md section 6), with the Jacobian of that map in the density; other fields
// (and a spherical Earth, whose paths also turn by their central angle) launch along the sampled
// direction (unbiased: the light is evaluated where the path does leave; a sun near the horizon
// is then met by fewer samples) -- over a spherical Earth the sampled direction turned into the
// point's own frame first, so that a path without air leaves exactly along it (else a sun 0.53 deg
// wide is missed beyond ~30 km, where the central angle exceeds its radius), and the sun's samples
// through its exit map (SunExitMap) above the point's horizon and by a search below it.
#pragma once

#include "refracta/core/rng.h"
#include "refracta/core/sampling.h"
#include "refracta/core/spectrum.h"
#include "refracta/render/caster.h"
#include "refracta/render/light_visibility.h"
#include "refracta/render/raised_sky.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"
#include "refracta/render/sun_exit_map.h"
#include "refracta/shading/bsdf.h"
#include "refracta/shading/light_sampler.h"

#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace refracta {

// Over a spherical Earth, where the lowest launch of DirectLighting::launch_below_horizon leaves
// the air: its exit elevation [rad] in the start point's own frame, tabulated over start heights
// and the air's dispersion scales (a spectral render retunes the air per sample). In a height-only
// air over a sphere a path depends on its start height and launch elevation alone (the frame turns
// with the point), so one cast per node stands for every point's. A sun sample that the table puts
// below that exit by more than the search's tolerance has set for the point -- the answer the
// lowest launch's own cast gives -- without the cast (issue 21: it was ~60 % of a spectral green
// flash frame, one 8 km grazing path per sea sample).
class LowestLaunches {
 public:
  // casters[k]: the render's air at dispersion scale scales[k] (ascending; at least one, each
  // curved through a height-only air over a spherical Earth); start heights from scene.lowest() to scene.highest() plus the largest offset of a
  // surface point (SurfaceInteraction::offset_toward). Null where no interval of heights can stand
  // for the casts (build).
  static std::shared_ptr<const LowestLaunches> build(const Scene& scene, const std::vector<const Caster*>& casters,
                                                     const std::vector<double>& scales);
  // A lower bound [rad] of the lowest launch's exit elevation from start height h [m] at
  // dispersion scale `scale`: -inf outside the tabulated heights, intervals and scales.
  double least_exit(double h, double scale) const;

 private:
  double lo_ = 0.0, step_ = 0.0;            // heights lo_ + j step_, j = 0 .. count - 1 [m]
  std::vector<double> scales_;               // ascending
  std::vector<std::vector<double>> exits_;   // exits_[k][j] at scales_[k], height j [rad]
  std::vector<double> margins_;              // [rad] per height interval (build); NaN: not tabulated
};

// The light evaluation, and (as a LightVisibility) the ray renderers' shadow rays through the
// caster; another visibility (render_raster's shadow maps) may stand in for them.
class DirectLighting : public LightVisibility {
 public:
  // visibility: how light samples are tested (kept by reference, must outlive this); null: this
  // object's own shadow rays (arriving below).
  DirectLighting(const RenderScene& scene, const Caster& caster, const RenderOptions& options,
                 const LightVisibility* visibility = nullptr);
  DirectLighting(const DirectLighting&) = delete;  // it may be its own visibility: not copied
  DirectLighting& operator=(const DirectLighting&) = delete;

  // NEE at si with `bsdf`: f L |cos| / pdf of light samples, MIS-weighted against BSDF sampling
  // for non-delta lights. 'path' samples one light chosen in proportion to power; 'direct' one
  // sample of every light (less noise where a few lights matter, as a sun and its sky).
  Spectrum sample_lights(const SurfaceInteraction& si, const SurfaceBsdf& bsdf, const SampledWavelengths& lambda,
                         Sampler& sampler) const;
  // One sample (u) of light `index` at si: f L |cos| / pdf, every light taken with certainty, for a
  // renderer that evaluates each light by its own samples (render_raster); mis: weighted against
  // as many BSDF samples (emitted, escaped), else the light's samples alone.
  Spectrum sample_light(size_t index, const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                        const SampledWavelengths& lambda, const Vec2d& u, bool mis) const;

  // Over a spherical Earth with a sun: the render's lowest launches (LowestLaunches; without them
  // every lowest launch is cast), its sun's exit map (SunExitMap; without it sun samples above a
  // point's horizon launch along the sample), and where the sample's dispersion scale is read (a
  // spectral render's hero's air's; 1 for an RGB render's one air). Either table may be null.
  void use_sun_tables(std::shared_ptr<const LowestLaunches> lowest, std::shared_ptr<const SunExitMap> exits,
                      std::shared_ptr<const double> scale) {
    lowest_launches_ = std::move(lowest);
    sun_exits_ = std::move(exits);
    scale_ = std::move(scale);
  }

  // A raised camera's sky (raised_sky.h; null: the ground's sky everywhere).
  void use_raised_sky(std::shared_ptr<const RaisedSky> sky) { raised_sky_ = std::move(sky); }
  // A distant light's radiance along dir as seen from scene height y (the raised camera's sky).
  Spectrum distant_Le(const Light& light, double y, const Vec3d& dir, const SampledWavelengths& lambda) const {
    return raised_sky_ ? raised_sky_->Le(light, y, dir, lambda) : light.Le(dir, lambda);
  }

  // The shadow rays: toward a distant light a curved (or straight) ray through the caster, the
  // light seen along its exit direction; to a finite light a straight segment, dimmed by the
  // aerial perspective.
  Spectrum arriving(size_t light, const SurfaceInteraction& si, const Vec3d& wi, const LightLiSample& ls,
                    const SampledWavelengths& lambda) const override;

  // Radiance of the infinite lights seen at the end of an escaped path that left scene height
  // `from_y` (its last segment's start: the eye or `from`), MIS-weighted against light sampling
  // from `from` (bsdf_pdf: density of the launch direction; specular: no MIS).
  Spectrum escaped(const PathEnd& end, const Vec3d& launch_dir, const SurfaceInteraction* from, double from_y,
                   double bsdf_pdf, bool specular, const SampledWavelengths& lambda) const;
  // Radiance an area light emits at si toward si.wo, MIS-weighted likewise.
  Spectrum emitted(const SurfaceInteraction& si, const SurfaceInteraction* from, double bsdf_pdf, bool specular,
                   const SampledWavelengths& lambda) const;

  // n of the air where a distant path from p toward `exit` leaves the modelled range (the straight
  // estimate of its end height, within the field's range), n(p) without a height-only field.
  double distant_ior(const Vec3d& p, const Vec3d& exit) const;

 private:
  double pick_probability(size_t light) const { return all_lights_ ? 1.0 : select_.pmf(light); }
  // mis: weighted against BSDF sampling (power heuristic) unless the light is delta. frame: where
  // si.p's turned frame (to_world_frame) is kept between the lights of one point (null: not kept).
  Spectrum sample_one(size_t index, double pick, const SurfaceInteraction& si, const SurfaceBsdf& bsdf,
                      const SampledWavelengths& lambda, const Vec2d& u, bool mis,
                      std::optional<Eigen::Matrix3d>* frame = nullptr) const;
  // Pre-bending in height-only fields: the launch direction at p whose curved path leaves along
  // `exit`, and the density factor |d omega_exit / d omega_launch|.
  Vec3d launch_toward(const Vec3d& p, const Vec3d& exit, double* jacobian) const;
  // Over a spherical Earth in flat coordinates (CurvedEarth) the frame at p is the origin's turned
  // by the central angle (IndexField::sky_direction): the rotation taking p's frame to the world
  // frame distant lights are given in (identity elsewhere).
  Eigen::Matrix3d to_world_frame(const Vec3d& p) const;
  double exit_jacobian(const Vec3d& p, const Vec3d& launch) const;
  // Over a spherical Earth, a distant light's sample `exit` (in p's frame) below p's horizon: the
  // rising launch direction from si whose curved path leaves the air along it (found by false
  // position on the launch elevation, the azimuth kept), and the density factor
  // |d omega_exit / d omega_launch| in `jacobian`; nullopt when no path rising from si leaves
  // that low (the light has set for si).
  // The scene's sun over a spherical Earth, its sample `exit` in p's frame: launched below p's
  // horizon by launch_below_horizon, above it through the sun's exit map where that covers the
  // exit, else along the sample; the density factor in `jacobian`, nullopt where the sun has set.
  std::optional<Vec3d> launch_bent_sun(const SurfaceInteraction& si, const Vec3d& exit, const Eigen::Matrix3d& to_world,
                                       double* jacobian) const;
  // The density of light samples of that sun launching along `launch_dir` (p's frame) from `from`,
  // whose path left along `exit_here` (p's frame): the sum over the three ways above.
  double bent_sun_pdf(const SurfaceInteraction& from, const Vec3d& launch_dir, const Vec3d& exit_here,
                      const LightSampleContext& ctx, const Eigen::Matrix3d& to_world) const;
  std::optional<Vec3d> launch_below_horizon(const SurfaceInteraction& si, const Vec3d& exit,
                                            const Eigen::Matrix3d& to_world, double* jacobian) const;
  // The elevation in p's frame [rad] at which the path launched from si at `elevation` in the
  // vertical plane of the horizontal unit vector `across` leaves the air (-inf if it meets the scene).
  double exit_elevation(const SurfaceInteraction& si, const Vec3d& across, double elevation,
                        const Eigen::Matrix3d& to_world) const;
  // |d omega_exit / d omega_launch| at that launch, whose exit elevation is `exit`, by a difference quotient.
  double bend_jacobian(const SurfaceInteraction& si, const Vec3d& across, double launch, double exit,
                       const Eigen::Matrix3d& to_world) const;

  const RenderScene& scene_;
  const Caster& caster_;
  const RenderOptions& options_;
  const LightVisibility& visibility_;
  LightSampler select_;  // 'path''s choice of one light a vertex (by kind: a lamp under a sky is sampled)
  bool pre_bend_ = false;
  bool spherical_ = false;  // CurvedEarth: distant lights are turned into each point's frame
  bool all_lights_ = false;
  const Light* bent_sun_ = nullptr;  // over a spherical Earth: the scene's sun (launch_below_horizon)
  std::shared_ptr<const LowestLaunches> lowest_launches_;  // use_sun_tables
  std::shared_ptr<const SunExitMap> sun_exits_;
  std::shared_ptr<const double> scale_;
  std::shared_ptr<const RaisedSky> raised_sky_;
};

}  // namespace refracta
