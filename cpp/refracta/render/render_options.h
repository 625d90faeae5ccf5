// Options of the renderers.
#pragma once

#include "refracta/rays/trace_options.h"
#include "refracta/render/pixel_bounds.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

enum class RenderMethod { kStraight, kCurved, kRasterMarch };
RenderMethod parse_render_method(const std::string& name);  // "straight", "curved", "raster_march"
TraceMethod parse_march_method(const std::string& name);    // raster_march's integrator: "rk4", "rk45"
const char* render_method_name(RenderMethod method);

// Light transport (render/integrator.h): 'direct' -- emitters seen directly and direct lighting
// at the first non-specular surface (next-event estimation with MIS), following mirror and glass
// chains up to max_depth; 'path' -- unidirectional path tracing with NEE and MIS, max_depth
// scattering events. Both play Russian roulette from rr_depth events on (direct's chains too).
enum class Transport { kDirect, kPath };
Transport parse_transport(const std::string& name);  // "direct", "path"
const char* transport_name(Transport transport);

// Camera rays through a turbulent layer (render/shimmer_cast.h): 'strict' -- the full field's
// path under rk45's error control; 'perturbed' -- the turbulent ray followed as its deviation from
// the calm ray of the eye's table, in fixed steps of the turbulence's cells, the strict path where
// the deviation is not small (issue 21: shimmer at video rates).
enum class TurbulenceTrace { kStrict, kPerturbed, kAuto };
TurbulenceTrace parse_turbulence_trace(const std::string& name);  // "strict", "perturbed", "auto"
const char* turbulence_trace_name(TurbulenceTrace method);

// PixelBounds from (x0, y0, x1, y1) (any other count: std::invalid_argument); pixel_bounds' setter.
PixelBounds pixel_bounds_from(const std::vector<int>& corners);

// Over a spherical Earth without the table's escape (turbulence's perturbed camera rays follow the
// table's whole paths), camera rays longer than this are traced per pixel: each of the table's
// few thousand paths is traced to its end, while a pixel's path, curving up in flat coordinates,
// soon leaves the air by the escape shortcut (Caster::escape_direction). Measured on 2 cores,
// 80 x 60 pixels: the table costs as much as per-pixel tracing at 150 km, 2.3x at 400 km, 32x at
// 1200 km (a setting sun). Over a flat Earth level rays never leave the air: the table stays.
constexpr double kTableLongestPath = 150e3;  // [m]

// Options of refracta.render, with their defaults (defined once, here). Set any field by name;
// validate() reports every bad value at once.
struct RenderOptions {
  RenderMethod method = RenderMethod::kCurved;
  int spp = 1;                // samples per pixel (1: the pixel centre; more: correlated multi-jittered, film.h)
  // Adaptive sampling at the same budget (render/adaptive_sampling.h): a pilot of
  // AdaptiveSampling::first_pass(spp) samples per pixel (2 at 16 spp) chooses how the rest of its
  // 32 x 32 block's budget is shared: every pixel at least half of spp, the others where the
  // pilot's samples vary most (edges, noise); each pixel is one pattern of its count, the pilot
  // is not averaged in (unbiased); the image's total is still width x height x spp.
  // 'straight' and 'curved' only; spp >= 6 (AdaptiveSampling::min_spp; below, a ValueError: the
  // pilot would leave no samples to move).
  bool adaptive = false;
  // Edge refinement (render/film.h EdgeRefinement): when above spp, every pixel at an edge between
  // surfaces -- its first hits' mean albedo or normal differs from a neighbour's -- is rendered
  // again as one pattern of edge_spp samples, so its coverage is weighed as a sensor's pixel
  // integrates it; the other pixels keep spp. The edges' pixels are few (7-13 % on the demo
  // scenes): the cost is that share x edge_spp. 0 (or at most spp): off. Not with adaptive.
  int edge_spp = 0;
  uint64_t seed = 0;  // seed of the per-pixel random streams
  // Curved rays end here and show the sky in their last direction [m]; so do straight rays over a
  // field with an Earth radius (the sphere's straight lines, render/picking.h straight_air). Over
  // such a field a camera ray that ends in the air above every object goes on to where it leaves
  // the air and shows the sky there (Caster::continue_to_sky): the scene is met within max_length,
  // the sky's refraction wherever it happens.
  double max_length = 5000.0;
  double chord = 1000.0;      // longest straight chord tested against the geometry [m]
  double sagitta = 1e-3;      // largest distance between a chord and the curved path [m]
  // Embree intersects in single precision (hits uncertain by ~1e-7 of their distance, 0.1 mm at
  // 1 km): a chord tolerance under a micrometre cannot be honoured, only paid for.
  static constexpr double kSmallestSagitta = 1e-6;  // [m]
  // Camera rays may stray this fraction of a pixel's footprint (pixel angle x path length) from
  // their path when that is more than `sagitta`: what a pixel cannot resolve need not be traced.
  double sagitta_pixels = 0.25;
  // Curved-ray integration tolerance [m] (the integrator, `trace`: 'stratified' for height-only
  // fields, 'rk45' for others).
  double tol = 1e-4;
  std::optional<TraceMethod> trace;  // force 'rk45' or 'stratified' (default: by the field)
  // Camera rays through turbulence: 'auto' follows them as deviations from their calm paths
  // ('perturbed', render/shimmer_cast.h: 20-25x faster than 'strict' on the hot road, within 4 % of
  // the turbulence's own effect of the strict image) wherever that applies, and traces them
  // strictly elsewhere, silently; 'perturbed' says where it does not apply (a SceneWarning).
  TurbulenceTrace turbulence_trace = TurbulenceTrace::kAuto;
  // 'perturbed': the step through the layer, in the turbulence's cells. The cubic B-spline's
  // gradient varies on the cell's scale, and a step h samples the path integral's spectrum
  // aliased from wavenumbers 2 pi / h along the path: at 1 cell that is where the spline's
  // response has its zeros (along the lattice axes), at 2 cells the grid's Nyquist, where it
  // carries full power. In [0.01, 16]: below a hundredth of a cell nothing changes but the cost
  // (1e-300 overflowed the step count and meant one step through the layer).
  double turbulence_step = 1.0;

  // Light transport and its bounds.
  Transport transport = Transport::kDirect;
  // Scattering events along a path (0: emitters only, 1: direct lighting; Mitsuba's max_depth
  // is this + 1). 'direct' uses it for specular chains only.
  int max_depth = 5;
  // Russian roulette from this many scattering events on (survival min(0.95, max throughput)).
  int rr_depth = 3;
  // Spectral rendering: 4 hero wavelengths per sample (Wilkie et al. 2014) instead of RGB.
  bool spectral = false;
  // Height-only fields: serve every pixel from one ElevationTable for the camera's eye height
  // (interpolated to `tol`) instead of tracing each pixel (over a CurvedEarth, paths over 150 km end in
  // the table where they leave the air; spectral renders of 8 spp or more: one table per dispersion scale; renderer.cpp).
  bool use_table = true;
  int tile = 16;  // tile size [pixels] of the parallel loop
  // Render only these pixels of the camera's image, (x0, y0, x1, y1): pixels [x0, x1) x [y0, y1)
  // (the result has the bounds' size); each pixel exactly as in the whole image (its seed and the
  // eye's ElevationTable are the whole image's: distributed tiles). Unset (None): the whole image.
  // Checked against the camera's image by bounds_in(width, height).
  std::optional<PixelBounds> pixel_bounds;
  // Filter textures over each sample's footprint (OIIO MIP-mapping, anisotropic; bilinear between
  // texels); false reads the finest level at the sample's point, bilinearly (aliases: only for
  // references and tests). Magnified, both are that bilinear lookup.
  bool texture_filter = true;
  // A camera ray's footprint on a textured surface from ray differentials through the air
  // (Caster::footprint: the paths of its neighbours, as squeezed or stretched by a mirage); false:
  // the ray cone (pixel angle x path length), as for every later bounce.
  bool differentials = true;
  // Also render the albedo and normal of each sample's first non-specular hit (averaged over the
  // pixel's samples): the image then has 9 channels, radiance, albedo, normal (Intel Open Image
  // Denoise's auxiliary features; renderer.h; Python's render returns them as
  // aovs=["albedo", "normal"] and the image's 3). 'straight' and 'curved' only.
  bool surface_aovs = false;
  // With surface_aovs: when above spp, the albedo and normal come from a pass of their own with
  // this many samples per pixel that stops at each path's first non-specular surface (no lighting:
  // a camera ray, its mirror and glass chain and the surface's albedo), so they carry the pixel's
  // edge coverage to guide_spp samples' accuracy (render(denoise=True)'s guided filter rebuilds the
  // image's edges from them, python/refracta/_denoise.py). Non-adaptive, RGB (a spectral render's
  // guides follow the air at its reference wavelength); 0 or at most spp: the image's own samples.
  // Off by default: 64 guide samples cost 0.7-1.7x the CPU of 16 'direct' RGB ones on the demo
  // scenes (about what 32 spp cost, and 32 spp denoised gain as much or more; 0.2x of the spectral
  // green flash's, where they find no surface: benchmarks/bench_denoise.py).
  int guide_spp = 0;
  // Also render the per-pixel readouts (readouts.h: distance, position, object id, apparent and
  // true elevation, apparent azimuth, hidden heights) after those 9 channels: 19 in all.
  // Implies surface_aovs. 'straight' and 'curved' only.
  bool readouts = false;
  // Also write each pixel's number of camera samples (the ones its value averages: spp, edge_spp
  // at a refined edge, the adaptive count; a pilot's samples only choose that count) as one more,
  // last channel (renderer.h). 'straight' and 'curved' only.
  bool sample_counts = false;

  // raster_march (the original editor's method): the integrator marching each pixel's ray
  // against the depth buffer: 'rk4' with `step` [m] for at most `max_steps` steps (the
  // original: 0.3 m, 1000 steps), or 'rk45' to `tol` over max_length.
  TraceMethod march = TraceMethod::kRk45;
  double step = kRk4DefaultStep;  // raster_march 'rk4': the step [m]
  int max_steps = 1000;           // raster_march 'rk4': steps at most
  // Extra raster view on each side, as a fraction of the image size: rays that bend out of the
  // camera's view can still find geometry there. What is in no raster pixel cannot appear.
  double guard_band = 0.1;

  void validate() const;
  // The pixels to render of a width x height image, (x0, y0, x1, y1): pixel_bounds (checked to lie
  // inside, non-empty; std::invalid_argument otherwise) or the whole image.
  PixelBounds bounds_in(int width, int height) const;
};

}  // namespace refracta
