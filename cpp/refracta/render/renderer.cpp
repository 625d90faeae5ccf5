// The straight and curved renderers: one ElevationTable per image for height-only fields, the
// caster, the integrator, the film loop.
//
// Spectral rendering through a field ('curved'): the air disperses (media/dispersed_field.h), so
// each sample's rays bend through the field at its exact hero wavelength, cast and shaded by a
// caster and integrator of a pool retuned to it (hero_casters.h). Its camera ray comes from the
// eye's tables at the dispersion scales either side of its hero's (SpectralEyeTables) where they
// agree to the pixel's tolerance and the samples pay for 16 tables, else it is traced.
#include "refracta/render/renderer.h"

#include "refracta/core/error.h"
#include "refracta/core/wavelength_distribution.h"
#include "refracta/media/dispersed_field.h"
#include "refracta/media/tabulated_height_field.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/render/adaptive_sampling.h"
#include "refracta/render/caster.h"
#include "refracta/render/film.h"
#include "refracta/render/hero_casters.h"
#include "refracta/render/picking.h"
#include "refracta/render/integrator.h"
#include "refracta/render/raised_sky.h"
#include "refracta/render/shimmer_cast.h"
#include "refracta/render/readouts.h"
#include "refracta/shading/spectral.h"
#include "refracta/shading/sun_light.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace refracta {

RenderMethod parse_render_method(const std::string& name) {
  if (name == "straight") return RenderMethod::kStraight;
  if (name == "curved") return RenderMethod::kCurved;
  if (name == "raster_march") return RenderMethod::kRasterMarch;
  throw_invalid("method must be 'straight', 'curved' or 'raster_march' (got '", name, "')");
}

TraceMethod parse_march_method(const std::string& name) {
  if (name == "rk4") return TraceMethod::kRk4;
  if (name == "rk45") return TraceMethod::kRk45;
  throw_invalid("march must be 'rk4' or 'rk45' (got '", name, "')");
}

const char* render_method_name(RenderMethod method) {
  return method == RenderMethod::kStraight ? "straight" : method == RenderMethod::kCurved ? "curved" : "raster_march";
}

const char* transport_name(Transport transport) { return transport == Transport::kDirect ? "direct" : "path"; }

PixelBounds pixel_bounds_from(const std::vector<int>& corners) {
  if (corners.size() != 4) throw_invalid("pixel_bounds must be (x0, y0, x1, y1) (got ", corners.size(), " values)");
  return PixelBounds{corners[0], corners[1], corners[2], corners[3]};
}

RenderStats operator+(const RenderStats& a, const RenderStats& b) {
  return RenderStats{a.samples + b.samples, a.chords + b.chords, a.invalid_samples + b.invalid_samples};
}

Transport parse_transport(const std::string& name) {
  if (name == "direct") return Transport::kDirect;
  if (name == "path") return Transport::kPath;
  throw_invalid("transport must be 'direct' or 'path' (got '", name, "')");
}

void RenderOptions::validate() const {
  Problems problems("RenderOptions");
  if (spp < 1) problems.add("spp must be >= 1 (got ", spp, ")");
  if (!(max_length > 0.0) || !std::isfinite(max_length)) problems.add("max_length must be > 0 and finite (got ", max_length, ")");
  if (!(chord > 0.0) || !std::isfinite(chord)) {
    problems.add("chord must be > 0 (got ", chord, ")");
  } else if (const int64_t most = TraceOptions().max_steps;
             std::isfinite(max_length) && max_length > 0.0 && max_length / chord > double(most)) {
    // chord is also the curved traces' largest node spacing (curved_trace_options)
    problems.add("max_length ", max_length, " m with chord ", chord, " m needs more than ", most,
                 " steps of the curved traces (chord is their largest node spacing): raise chord to at least ",
                 max_length / double(most), " m or lower max_length");
  }
  if (!(sagitta >= kSmallestSagitta) || !std::isfinite(sagitta)) {
    problems.add("sagitta must be >= ", kSmallestSagitta, " m and finite (got ", sagitta, ")");
  }
  if (!(sagitta_pixels >= 0.0) || !std::isfinite(sagitta_pixels)) {
    problems.add("sagitta_pixels must be >= 0 and finite (got ", sagitta_pixels, ")");
  }
  if (!(tol > 0.0) || !std::isfinite(tol)) {
    problems.add("tol must be > 0 (got ", tol, ")");
  } else if (method != RenderMethod::kStraight && tol < kMinRelativeTol * max_length) {
    problems.add("tol must be at least ", kMinRelativeTol, " x max_length = ", kMinRelativeTol * max_length,
                 " m, the round-off of positions (got ", tol, "): raise tol or lower max_length");
  }
  if (tile < 1 || tile > kMaxTile) problems.add("tile must be in [1, ", kMaxTile, "] pixels (got ", tile, ")");
  if (trace && *trace == TraceMethod::kRk4) problems.add("trace must be 'rk45' or 'stratified' for rendering");
  if (march == TraceMethod::kStratified) problems.add("march must be 'rk4' or 'rk45'");
  if (!(step > 0.0) || !std::isfinite(step)) problems.add("step must be > 0 (got ", step, ")");
  if (max_steps < 1) problems.add("max_steps must be >= 1 (got ", max_steps, ")");
  if (surface_aovs && method == RenderMethod::kRasterMarch) problems.add("surface_aovs needs method 'straight' or 'curved'");
  if (guide_spp < 0) problems.add("guide_spp must be >= 0 (got ", guide_spp, ")");
  if (readouts && method == RenderMethod::kRasterMarch) problems.add("readouts need method 'straight' or 'curved'");
  if (sample_counts && method == RenderMethod::kRasterMarch) problems.add("sample_counts needs method 'straight' or 'curved'");
  if (adaptive && method == RenderMethod::kRasterMarch) problems.add("adaptive needs method 'straight' or 'curved'");
  if (adaptive && spp < AdaptiveSampling::min_spp()) {
    const int first = AdaptiveSampling::first_pass(spp);
    if (spp <= first) {
      problems.add("adaptive needs spp >= ", AdaptiveSampling::min_spp(), " (got ", spp, "): its pilot takes ", first,
                   " samples a pixel");
    } else {
      problems.add("adaptive needs spp >= ", AdaptiveSampling::min_spp(), " (got ", spp, "): below, its pilot of ",
                   first, " samples a pixel leaves none to move, and every pixel would get ", spp - first,
                   " instead of ", spp);
    }
  }
  if (edge_spp < 0) problems.add("edge_spp must be >= 0 (got ", edge_spp, ")");
  if (edge_spp > spp && adaptive) problems.add("edge_spp (", edge_spp, ") and adaptive cannot be combined");
  if (edge_spp > spp && method == RenderMethod::kRasterMarch) problems.add("edge_spp needs method 'straight' or 'curved'");
  if (!(guard_band >= 0.0 && guard_band <= 2.0)) problems.add("guard_band must be in [0, 2] (got ", guard_band, ")");
  if (!(turbulence_step >= 0.01 && turbulence_step <= 16.0)) {
    problems.add("turbulence_step must be in [0.01, 16] cells (got ", turbulence_step, ")");
  }
  if (max_depth < 0) problems.add("max_depth must be >= 0 (got ", max_depth, ")");
  if (rr_depth < 1) problems.add("rr_depth must be >= 1 (got ", rr_depth, ")");
  if (pixel_bounds && !(pixel_bounds->x0 >= 0 && pixel_bounds->y0 >= 0 && pixel_bounds->x1 > pixel_bounds->x0 &&
                        pixel_bounds->y1 > pixel_bounds->y0)) {
    problems.add("pixel_bounds (x0, y0, x1, y1) must have 0 <= x0 < x1 and 0 <= y0 < y1 (got (", pixel_bounds->x0, ", ",
                   pixel_bounds->y0, ", ", pixel_bounds->x1, ", ", pixel_bounds->y1, "))");
  }
  problems.throw_if_any();
}

PixelBounds RenderOptions::bounds_in(int width, int height) const {
  if (!pixel_bounds) return PixelBounds{0, 0, width, height};
  const PixelBounds& b = *pixel_bounds;
  if (!(b.x0 >= 0 && b.y0 >= 0 && b.x1 > b.x0 && b.y1 > b.y0 && b.x1 <= width && b.y1 <= height)) {
    throw_invalid("pixel_bounds (", b.x0, ", ", b.y0, ", ", b.x1, ", ", b.y1, ") must be a non-empty rectangle inside the ",
                  width, " x ", height, " image");
  }
  return b;
}

namespace {

// The elevations [rad] the camera's pixels look along, with a margin of two pixels.
std::pair<double, double> elevation_range(const Camera& camera) {
  double lo = kPi, hi = -kPi;
  const int steps = 64;
  for (int i = 0; i <= steps; ++i) {
    for (int j = 0; j <= steps; ++j) {
      const Vec3d d = camera.direction(camera.width() * double(i) / steps, camera.height() * double(j) / steps);
      const double e = std::asin(std::clamp(d.y(), -1.0, 1.0));
      lo = std::min(lo, e), hi = std::max(hi, e);
    }
  }
  // Two pixels, and the largest turn of a jittered camera's rays (sampled above only at the grid).
  double jitter = 0.0;
  for (float a : camera.jitter()) jitter = std::max(jitter, double(std::abs(a)));
  const double margin = 2.0 * camera.pixel_angle() * std::max(1.0, double(camera.width()) / camera.height()) + 2.0 * jitter;
  return {std::max(lo - margin, -0.5 * kPi), std::min(hi + margin, 0.5 * kPi)};
}

// `field`: the height-only air camera rays see outside every local region (null for 3-D fields).
// escape: over a spherical Earth, the caster's (Caster::plane_escape): each entry ends where it
// leaves the air, so an entry to the horizon costs what a pixel's traced path costs; ceiling: the
// caster's (ElevationTableOptions::ceiling).
// A spectral render's air depends on each sample's wavelength: its tables are SpectralEyeTables'
// (hero_casters.h), one per dispersion scale, each built here (`spectral_slice`).
std::unique_ptr<ElevationTable> eye_table(const RenderScene& scene, const Camera& camera, const FieldPtr& field,
                                          const RenderOptions& options, const PlaneEscape& escape, double ceiling,
                                          WorkControl& control, bool spectral_slice = false) {
  if (!field || !field->height_only() || options.method != RenderMethod::kCurved || !options.use_table ||
      (options.max_length > kTableLongestPath && std::isfinite(field->earth_radius()) && !escape) ||
      (options.spectral && !spectral_slice) || (options.trace && *options.trace != TraceMethod::kStratified) ||
      camera.aperture_diameter() > 0.0) {  // a thin lens's rays leave the eye almost never
    return nullptr;
  }
  ElevationTableOptions table_options;
  table_options.eye_height = camera.position().y();
  std::tie(table_options.min_elevation, table_options.max_elevation) = elevation_range(camera);
  table_options.tol = options.tol;
  // A quarter of a pixel's angle per metre of path: errors well below what a pixel resolves.
  table_options.angular_tol = 0.25 * camera.pixel_angle();
  // More exact traces than a quarter of the pixels would not pay: trace the rest per pixel. A
  // spectral render's kScales slices together at most one per pixel (a quarter each cost the
  // green flash frame 3.6x straight, 1 / kScales each 2.5x, its image the same to 7e-9 of its
  // mean; a quarter of that budget changed its sun's rim).
  const int64_t pixels = int64_t(camera.width()) * camera.height();
  table_options.max_rays = std::max<int64_t>(spectral_slice ? pixels / SpectralEyeTables::kScales : pixels / 4,
                                             2 * table_options.initial_rays);
  table_options.trace = curved_trace_options(scene.geometry, *field, camera.position(), options, options.max_length);
  table_options.escape = escape;
  if (escape) table_options.ceiling = ceiling;
  auto table = std::make_unique<ElevationTable>(field, table_options, control);
  control.done = 0;
  return table;
}

// The density a spectral render draws its hero wavelengths from (core/wavelength_distribution.h).
// With a sun: a quarter pbrt-v4's visible density (SampleVisibleWavelengths: 1 / cosh^2(0.0072
// (lambda - 538 nm)), over every colour) and three quarters the sun's radiance times x-bar + y-bar
// + z-bar, on 1 nm bins; without one, uniform (unchanged). Through the ~38 air masses of a setting
// sun its radiance at 450 nm is 0.2 % of 700 nm's: drawn uniformly, one wavelength's estimate of
// the sky's luminance beside it has a relative standard deviation of 1.51, drawn by this density
// 0.45 (its X 0.52, Z 2.9). All three matching functions, not y-bar alone: drawn by the sun times
// y-bar (luminance 0.34, but X 0.72, Z 3.0; under a white sun Z 3.5 against 1.3 now), a wavelength
// where x-bar or z-bar is large and y-bar small carried a large weight in X or Z, and a grey floor
// under a white sun was 3.3x noisier than with uniform wavelengths (16 spp, relative RMSE 0.066
// against 0.020; a blue one 0.152 against 0.033: a trial). Now 0.009 and 0.014. The green flash's
// sky (64 x 64, 16 spp, 6 seeds) pays a little of its luminance: per-pixel relative noise 0.052
// against y-bar's 0.042, its blue channel 0.63 against 0.70. The visible share keeps every colour
// sampled.
WavelengthDistribution hero_wavelengths(const RenderScene& scene) {
  const SunLight* sun = scene.sun();
  if (!sun) return WavelengthDistribution();
  constexpr double kVisibleShare = 0.25;
  const int bins = int(kLambdaMax - kLambdaMin);  // 1 nm
  std::vector<double> visible(size_t(bins), 0.0), lit(size_t(bins), 0.0);
  double visible_sum = 0.0, lit_sum = 0.0;
  for (int k = 0; k < bins; ++k) {
    const double lambda = kLambdaMin + k + 0.5;
    visible[size_t(k)] = 1.0 / std::pow(std::cosh(0.0072 * (lambda - 538.0)), 2);
    lit[size_t(k)] = std::max(0.0, sun->radiance().evaluate(lambda)) * spectral::cie_xyz(lambda).sum();
    visible_sum += visible[size_t(k)];
    lit_sum += lit[size_t(k)];
  }
  if (!(lit_sum > 0.0)) return WavelengthDistribution();
  std::vector<double> weights(visible.size());
  for (size_t k = 0; k < weights.size(); ++k) {
    weights[k] = kVisibleShare * visible[k] / visible_sum + (1.0 - kVisibleShare) * lit[k] / lit_sum;
  }
  return WavelengthDistribution(weights);
}

}  // namespace

Image render(const RenderScene& scene, const Camera& camera, const FieldPtr& exact_field, const RenderOptions& options,
             WorkControl& control, RenderStats* stats) {
  options.validate();
  // Rays must stay where scene coordinates may lie (Embree's points are checked against
  // kSceneReach): one let run farther failed mid-render (a trial's max_length 1e8 m, seconds in).
  const double eye = camera.position().cwiseAbs().maxCoeff() + camera.aperture_diameter();
  if (!(eye < kSceneReach)) {  // no max_length would do: none is 0 or less
    throw_invalid("render: the camera is ", eye, " m from the origin, at the end of scene coordinates (",
                  kSceneReach, " m): rays cannot start there; place the scene's origin nearer the camera");
  }
  if (!(eye + options.max_length <= kSceneReach)) {
    throw_invalid("render: max_length ", options.max_length, " m from a camera ", eye, " m out would take rays beyond ",
                  kSceneReach, " m from the origin, where scene coordinates end: give max_length at most ",
                  std::max(0.0, kSceneReach - eye), " m");
  }
  const PixelBounds bounds = options.bounds_in(camera.width(), camera.height());  // before any work
  // float32 channels, and room for one copy by the caller (the pixels themselves move out).
  check_image_memory(bounds.width(), bounds.height(),
                     (options.readouts ? 152.0 : options.surface_aovs ? 72.0 : 24.0) + (options.sample_counts ? 12.0 : 0.0),
                     "render");
  scene.prepare();
  if (options.method == RenderMethod::kRasterMarch) {
    if (camera.aperture_diameter() > 0.0) {
      throw_invalid("method 'raster_march' renders through a pinhole: depth of field (a camera with an f_number) needs "
                    "method 'straight' or 'curved'");
    }
    return render_raster_march(scene, camera, exact_field, options, control, stats);
  }
  // Straight rays over a spherical Earth are straight in its true geometry (straight_air); like
  // every curved path they end after max_length.
  if (options.method == RenderMethod::kStraight && exact_field && std::isfinite(exact_field->earth_radius())) {
    RenderOptions curved = options;
    curved.method = RenderMethod::kCurved;
    return render(scene, camera, straight_air(exact_field.get()), curved, control, stats);
  }
  // Height-only air -- the field, or outside its local regions its height-only part -- is
  // tabulated once (to 1e-12 in n) over every height a ray can reach. (Not when rk45 is forced:
  // that stands for fields that are not height-only.)
  const bool forced_rk45 = options.trace && *options.trace == TraceMethod::kRk45;
  FieldPtr field = exact_field;
  FieldPtr layered = field && field->height_only() ? field : field ? field->height_only_part() : nullptr;
  if (layered && (options.method != RenderMethod::kCurved || forced_rk45)) layered = nullptr;
  if (layered) {
    const auto [lo, hi] = render_heights(scene.geometry, camera.position(), options);
    layered = tabulate_heights(layered, lo, hi);
    if (field->height_only()) field = layered;
  }
  // Height-only air: the least n any ray meets; rays that cannot turn are cut into chords
  // without tracing (Caster::cast_monotone).
  // Spectral: n at each height is affine in the dispersion scale, so the floor over all
  // wavelengths is the lower of the floors at the ends of the range.
  std::optional<IorFloors> floors;
  if (layered) {
    floors = render_ior_floors(scene.geometry, *layered, camera.position(), options);
    if (options.spectral) {
      const double reference = field_reference_wavelength(*layered);
      for (double wavelength : {kLambdaMin, kLambdaMax}) {
        floors->merge(render_ior_floors(scene.geometry, *dispersed_field(layered, wavelength, reference),
                                        camera.position(), options));
      }
    }
    // Over a spherical Earth: what stands over the ground, built once for every caster of the render.
    if (std::isfinite(layered->earth_radius())) floors->cover = std::make_shared<const HeightCover>(scene.geometry);
  }
  Caster caster(scene.geometry, field.get(), options);
  if (layered && !field->height_only()) caster.use_layered(layered.get());
  if (floors) caster.set_ior_floors(*floors);
  // Over a spherical Earth, paths longer than kTableLongestPath end in the table where they
  // escape, as a pixel's traced path does (not under turbulence's perturbed camera rays: they walk
  // the calm path to its end). Shorter ones are traced whole: the cold sea's 41 km table with
  // escapes was no faster (240 x 80, 1 spp: 4.96 s against 4.84 s; its rays stay under the
  // coast's 165 m hills, where nothing escapes).
  PlaneEscape escape;
  const bool perturbed = perturbed_trace_serves(field.get(), options, camera);
  const bool escapes = layered && std::isfinite(layered->earth_radius()) && options.max_length > kTableLongestPath &&
                       !perturbed;
  if (escapes) {
    escape = [&caster, spread = camera.pixel_angle()](const RayNode<double>& node, double remaining) {
      return caster.plane_escape(node, remaining, spread);
    };
  }
  const std::unique_ptr<ElevationTable> table =
      eye_table(scene, camera, layered, options, escape, caster.ceiling(), control);
  if (table) caster.use_table(table.get(), camera.position(), camera.pixel_angle());
  caster.set_secondary_spread(camera.pixel_angle());  // shadow and bounce rays' tolerance (caster.h)
  // Camera rays through turbulence as deviations from the calm rays (options.turbulence_trace).
  const std::unique_ptr<ShimmerCaster> shimmer =
      perturbed ? ShimmerCaster::make(scene.geometry, *field, layered, table.get(), camera.position(),
                                      camera.pixel_angle(), floors, options)
                : nullptr;
  const std::unique_ptr<Integrator> integrator = make_integrator(scene, caster, options);
  const std::shared_ptr<const RaisedSky> raised_sky = RaisedSky::for_camera(scene, camera.position().y());
  integrator->lighting().use_raised_sky(raised_sky);
  // Over a spherical Earth with a sun, the lowest launches of its samples below a point's horizon
  // and its exit map above it from tables (LowestLaunches, SunExitMap, at the render's one scale);
  // spectral renders' heroes carry theirs (hero_casters.cpp).
  if (!options.spectral && caster.curved() && caster.field()->height_only() &&
      std::isfinite(caster.field()->earth_radius()) && scene.sun() != nullptr) {
    integrator->lighting().use_sun_tables(
        LowestLaunches::build(scene.geometry, {&caster}, {1.0}),
        SunExitMap::build(scene.geometry, {caster.field()}, {1.0}, field, options, camera.pixel_angle(), *scene.sun()),
        std::make_shared<const double>(1.0));
  }
  // 'perturbed': the lighting rays of samples whose camera ray was a small perturbation through
  // the layer go through the calm air (shimmer_cast.h).
  const std::unique_ptr<Integrator> calm_integrator = shimmer ? make_integrator(scene, shimmer->calm(), options) : nullptr;
  if (calm_integrator) calm_integrator->lighting().use_raised_sky(raised_sky);
  std::atomic<int64_t> chords{0}, invalid{0};
  // Dispersive air: a spectral render through a field that bends rays.
  const bool dispersive = options.spectral && caster.curved();
  // A camera ray meeting a textured surface gets its footprint from its neighbours' paths (ray
  // differentials through the air, Caster::footprint): half a sample's spacing either side.
  // Through a thin lens the neighbours' rays leave the same lens point. Only image textures read
  // it (Material::textured): an untextured sea or hull spends no four neighbour paths on it (6 %
  // of the cold sea's curved render).
  auto textured = [&](unsigned geometry) {
    const int material = scene.geometry.material(geometry);
    return material >= 0 && scene.material(material).textured();
  };
  auto with_footprint = [&](const Caster& c, const Vec3d& origin, const Vec2d& pixel, const Vec2d& lens,
                            double spacing, PathEnd* first) {
    if (!options.texture_filter || !options.differentials || !first->hit ||
        !scene.geometry.has_uvs(first->hit->geometry) || !textured(first->hit->geometry)) {
      return;
    }
    const double h = 0.5 * spacing;
    auto dir_at = [&](double u, double v) { return camera.lens_ray(u, v, lens).direction; };
    first->footprint = c.footprint(origin, *first, {{{dir_at(pixel.x() - h, pixel.y()), dir_at(pixel.x() + h, pixel.y())},
                                                     {dir_at(pixel.x(), pixel.y() - h), dir_at(pixel.x(), pixel.y() + h)}}});
  };
  // A thin lens's rays start off the eye (all but the lens centre's): the caster traces them
  // exactly (the eye's table holds paths from the eye alone), see Camera::lens_ray. A horizontal
  // lens offset would be an exact translation of the eye's paths, but a level camera's lens disc
  // is vertical, and serving a lens point delta above the eye from the eye's path moved up by
  // delta is not negligible near a hot road: for delta = 7 cm (400 mm at f/2.8) the two paths
  // part by up to 0.26 px (480 px across 36 mm) at 260 m, for rays grazing the road near the
  // mirage's critical angle (-0.31 deg), where n changes over centimetres. Tracing costs what
  // table=False costs: hot road, 480 x 160, 4 spp: 3.7 s with a lens, 1.3 s pinhole with the table.
  // Readouts (readouts.h): the camera ray's direction at the eye and its first hit.
  const double earth_radius = field ? field->earth_radius() : std::numeric_limits<double>::infinity();
  auto record_camera_ray = [earth_radius](const Vec3d& origin, const Vec3d& dir, const PathEnd& first, SurfaceAovs* aovs) {
    if (!aovs) return;
    aovs->eye_direction = dir;
    aovs->hit = first.hit;
    aovs->distance = first.hit ? true_path_length(first.length, origin.y(), first.hit->point.y(), dir.normalized().y(),
                                                  first.direction.y(), earth_radius)
                               : first.length;
  };
  // Dispersive air: a pool of casters and integrators, one retuned to each sample's hero (hero_casters.h).
  const std::unique_ptr<HeroCasters> heroes =
      dispersive ? std::make_unique<HeroCasters>(scene, field, options, floors, camera.pixel_angle(), raised_sky) : nullptr;
  // Dispersive height-only air: camera rays from the eye tables of the scales either side of the hero's.
  // Each table traces at most 1 / kScales of the pixels' elevations (eye_table's max_rays), and
  // costs ~20 ms at least (16 tables for 24 x 12 pixels: 0.56 s, against 0.11 s for tracing its
  // 2304 camera rays, measured with a quarter each): the kScales tables pay for themselves when
  // every pixel casts at least kScales / 2 camera rays and the image has at least 1024 camera
  // rays per table.
  // The whole image's, so that pixel_bounds renders its pixels as the whole image does.
  const int64_t camera_rays = int64_t(camera.width()) * camera.height() * options.spp;
  std::unique_ptr<SpectralEyeTables> spectral_eye;
  if (heroes && field->height_only() && 2 * options.spp >= SpectralEyeTables::kScales &&
      camera_rays >= 1024 * SpectralEyeTables::kScales) {
    // The slices' tables are built side by side: each counts its own progress (the render's
    // cancel flag stays in force through the parallel loops' chain, core/parallel.h).
    auto make_table = [&](const FieldPtr& air, const PlaneEscape& slice_escape) {
      WorkControl slice_control;
      return eye_table(scene, camera, air, options, slice_escape, caster.ceiling(), slice_control,
                       /*spectral_slice=*/true);
    };
    spectral_eye = std::make_unique<SpectralEyeTables>(scene, field, options, floors, camera.position(),
                                                       camera.pixel_angle(), escapes, make_table);
  }
  const WavelengthDistribution wavelengths = options.spectral ? hero_wavelengths(scene) : WavelengthDistribution();
  auto sample = [&](const Vec2d& pixel, const Vec2d& lens, double spacing, double pixel_angle, SampledWavelengths& lambda,
                    Sampler& sampler, ScratchBuffer& scratch, SurfaceAovs* aovs) {
    const Camera::LensRay ray = camera.lens_ray(pixel.x(), pixel.y(), lens);
    const Vec3d& origin = ray.origin;
    const Vec3d& dir = ray.direction;
    if (heroes) lambda.terminate_secondary();
    const std::optional<HeroCasters::Lease> hero =
        heroes ? std::optional<HeroCasters::Lease>(std::in_place, heroes->for_wavelength(lambda.hero())) : std::nullopt;
    const Caster* cast_by = hero ? &hero->caster() : &caster;
    const Integrator* shade_by = hero ? &hero->integrator() : integrator.get();
    // Turbulence's perturbed camera rays follow the calm air's table: not a dispersed one.
    const ShimmerCaster* shimmering = heroes ? nullptr : shimmer.get();
    bool perturbed = false;
    PathEnd first = shimmering     ? shimmering->cast(caster, origin, dir, camera.pixel_angle(), &perturbed)
                    : spectral_eye ? spectral_eye->cast(*cast_by, hero->scale(), origin, dir, camera.pixel_angle())
                                   : cast_by->cast(origin, dir, 0.0, camera.pixel_angle());
    with_footprint(shimmering ? shimmering->calm() : *cast_by, origin, pixel, lens, spacing, &first);
    record_camera_ray(origin, dir, first, aovs);
    chords.fetch_add(first.chords, std::memory_order_relaxed);
    if (perturbed && calm_integrator) shade_by = calm_integrator.get();
    const Spectrum L = shade_by->li_after(origin, dir, first, pixel_angle, lambda, sampler, scratch, aovs);
    if (!L.isFinite().all()) invalid.fetch_add(1, std::memory_order_relaxed);
    return L;
  };
  Image image, counts;
  Image* const pixel_samples = options.sample_counts ? &counts : nullptr;
  int64_t samples = 0;
  if (options.readouts) {
    const ReadoutGeometry geometry(camera.position(), exact_field.get(), options.max_length, &control.cancel);
    image = render_film<FilmLayout::kReadouts>(camera, options, control, sample, &samples, &geometry, wavelengths,
                                               pixel_samples);
  } else if (options.surface_aovs) {
    image = render_film<FilmLayout::kSurface>(camera, options, control, sample, &samples, nullptr, wavelengths,
                                              pixel_samples);
  } else {
    image = render_film<FilmLayout::kRadiance>(camera, options, control, sample, &samples, nullptr, wavelengths,
                                               pixel_samples);
  }
  // The denoiser's guides from a pass of their own (options.guide_spp): the first non-specular
  // surface of guide_spp samples a pixel, from the same casters (a spectral render's at the air's
  // reference wavelength, its camera rays through an eye table of their own), their albedo and
  // normal replacing the image's own samples' (channels 3-8).
  if (options.surface_aovs && options.guide_spp > options.spp) {
    RenderOptions guide_options = options;
    guide_options.spp = options.guide_spp;
    guide_options.adaptive = false;
    guide_options.spectral = false;
    guide_options.seed = options.seed ^ 0x9e3779b97f4a7c15ull;  // streams apart from the image's
    std::unique_ptr<ElevationTable> guide_table;
    if (!table && options.spectral) {
      guide_table = eye_table(scene, camera, layered, guide_options, escape, caster.ceiling(), control);
      if (guide_table) caster.use_table(guide_table.get(), camera.position(), camera.pixel_angle());
    }
    auto guide = [&](const Vec2d& pixel, const Vec2d& lens, double spacing, double pixel_angle, SampledWavelengths& lambda,
                     Sampler& sampler, ScratchBuffer& scratch, SurfaceAovs* aovs) {
      const Camera::LensRay ray = camera.lens_ray(pixel.x(), pixel.y(), lens);
      PathEnd first = shimmer ? shimmer->cast(caster, ray.origin, ray.direction, camera.pixel_angle())
                              : caster.cast(ray.origin, ray.direction, 0.0, camera.pixel_angle());
      with_footprint(shimmer ? shimmer->calm() : caster, ray.origin, pixel, lens, spacing, &first);
      chords.fetch_add(first.chords, std::memory_order_relaxed);
      integrator->surface_after(ray.origin, ray.direction, first, pixel_angle, lambda, sampler, scratch, *aovs);
      return Spectrum(Spectrum::Zero());
    };
    const Image guides = render_film<FilmLayout::kSurface>(camera, guide_options, control, guide);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) std::copy_n(guides.at(x, y) + 3, 6, image.at(x, y) + 3);
    }
  }
  if (pixel_samples) image = with_channel(image, counts);
  if (stats) {
    stats->samples = samples;
    stats->chords = chords.load();
    stats->invalid_samples = invalid.load();
  }
  return image;
}

}  // namespace refracta
