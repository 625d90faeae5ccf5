// render_raster: the real-time pipeline on the CPU, for comparing moment methods (issue 5): the
// camera view rasterized into a visibility buffer, every pixel shaded once, the sun's shadow
// from a shadow map (hard, PCF, VSM, Hamburger / Hausdorff 4MSM) or from Embree shadow rays (the
// reference), transparent surfaces (alpha < 1) composited from per-pixel fragment lists (exact,
// peeling, WBOIT, MBOIT). Shadows treat every surface as opaque. No atmosphere: the straight view.
// The lights are evaluated by the ray renderers' DirectLighting, the shadow maps standing in for
// their shadow rays through the LightVisibility seam (raster_visibility.h).
#include "refracta/render/raster_renderer.h"

#include "refracta/core/error.h"
#include "refracta/core/scratch.h"
#include "refracta/render/caster.h"
#include "refracta/render/direct_lighting.h"
#include "refracta/render/raised_sky.h"
#include "refracta/render/raster_visibility.h"
#include "refracta/render/surface_scattering.h"
#include "refracta/render/tile_loop.h"
#include "refracta/shading/aerial_perspective.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace refracta {

ShadowSource parse_shadow_source(const std::string& name) {
  if (name == "map") return ShadowSource::kMap;
  if (name == "embree") return ShadowSource::kEmbree;
  if (name == "none") return ShadowSource::kNone;
  throw_invalid("shadows must be 'map', 'embree' or 'none' (got '", name, "')");
}

const char* shadow_source_name(ShadowSource source) {
  switch (source) {
    case ShadowSource::kMap: return "map";
    case ShadowSource::kEmbree: return "embree";
    case ShadowSource::kNone: return "none";
  }
  return "?";
}

RasterOutput parse_raster_output(const std::string& name) {
  if (name == "radiance") return RasterOutput::kRadiance;
  if (name == "shadow") return RasterOutput::kShadow;
  throw_invalid("output must be 'radiance' or 'shadow' (got '", name, "')");
}

const char* raster_output_name(RasterOutput output) { return output == RasterOutput::kShadow ? "shadow" : "radiance"; }

void RasterRenderOptions::check(Problems& problems) const {
  if (shadows == ShadowSource::kMap) problems.check_nested("shadow_map", shadow_map);
  if (shadow_half_size) {
    // A map wider than the scene's reach has texels wider than anything in it: no shadow survives.
    problems.check(*shadow_half_size > 0.0 && *shadow_half_size <= kSceneReach, "shadow_half_size must be in (0, ",
                   kSceneReach, "] m (got ", *shadow_half_size, ")");
  }
  if (shadow_centre) problems.check(is_finite(*shadow_centre), "shadow_centre must be finite");
  problems.check(shadow_distance > 0.0, "shadow_distance must be > 0 (got ", shadow_distance, ")");
  problems.check(tile >= 1 && tile <= kMaxTile, "tile must be in [1, ", kMaxTile, "] pixels (got ", tile, ")");
  if (transparency) problems.check_nested("transparency", *transparency);
  problems.check(shadow_light >= -1, "shadow_light must be -1 (the sun) or a spot light index (got ", shadow_light,
                 ")");
  problems.check(light_strata >= 1 && light_strata <= 64, "light_strata must be in [1, 64] (got ", light_strata, ")");
}

void RasterRenderOptions::validate() const {
  Problems problems("RasterRenderOptions");
  check(problems);
  problems.throw_if_any();
}

namespace {

// A light's or a BSDF's n^2 sample points, the same at every pixel: the first n^2 points of the R3
// sequence (Roberts 2018, "The unreasonable effectiveness of quasirandom sequences": frac(0.5 +
// k (1/g, 1/g^2, 1/g^3)), g = 1.2207... the root of x^4 = x + 1), (u, v) the direction's and w
// the BSDF lobe's. Every coordinate takes n^2 distinct values spread over [0, 1): a grid's rows
// gave an environment map's marginal n values only (a map with a small bright sun was off by
// 73 % at n = 8), and a lobe of probability F gets about F n^2 points spread over the directions
// (tied to the grid's rows, a dielectric's reflection, F ~ 0.03, took the first row of directions
// only, and rough water under a sky came out 7-10x too dark).
std::vector<Vec3d> sample_points(int n) {
  constexpr double g = 1.22074408460575947536;
  const Vec3d alpha(1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g));
  std::vector<Vec3d> points(size_t(n) * size_t(n));
  for (size_t k = 0; k < points.size(); ++k) {
    for (int d = 0; d < 3; ++d) points[k][d] = std::fmod(0.5 + double(k) * alpha[d], 1.0);
  }
  return points;
}

// The fragments' depth range [m], to which MBOIT's log-depth warp is fitted when not given.
void fit_mboit_range(const FragmentLists& fragments, OitSettings& oit) {
  if (oit.method != OitMethod::kMboit) return;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const auto& list : fragments.lists) {
    for (const auto& f : list) lo = std::min(lo, double(f.depth)), hi = std::max(hi, double(f.depth));
  }
  if (oit.mboit.z_far > oit.mboit.z_near) {
    // MBOIT warps depths in the range to [-1, 1]: those beyond it leave the moments' domain (a
    // trial's range of 100-200 m over fragments 6-14 m away was taken, and the image changed).
    if (hi >= lo && !(oit.mboit.z_near <= lo && hi <= oit.mboit.z_far)) {
      throw_invalid("transparency.mboit: z_near, z_far = ", oit.mboit.z_near, ", ", oit.mboit.z_far,
                    " m must hold every transparent fragment's depth (they lie from ", lo, " to ", hi,
                    " m); leave both 0 to fit them");
    }
    return;
  }
  if (hi > lo) oit.mboit.z_near = lo, oit.mboit.z_far = hi * (1.0 + 1e-6);
}

}  // namespace

Image render_raster(const RenderScene& render_scene, const Camera& camera, const RasterRenderOptions& options,
                    WorkControl& control, RasterRenderStats* stats) {
  options.validate();
  if (camera.aperture_diameter() > 0.0) {
    throw_invalid("render_raster draws through a pinhole: depth of field (a camera with an f_number) needs "
                  "refracta.render with method 'straight' or 'curved'");
  }
  // The visibility buffer, float32 RGB here and in the numpy copy handed to Python, and with
  // transparency a fragment list's header (a std::vector) per pixel.
  check_image_memory(camera.width(), camera.height(),
                     kVisibilityBytesPerPixel + 24.0 + (options.transparency ? double(sizeof(std::vector<int>)) : 0.0),
                     "render_raster");
  render_scene.prepare();
  const Scene& scene = render_scene.geometry;
  const RasterLights lights = raster_lights(render_scene, options);
  const auto start = std::chrono::steady_clock::now();

  // The camera's visibility buffer, and the transparent surfaces' fragments in front of it.
  const RasterView view = RasterView::from_camera(camera);
  std::vector<bool> transparent(scene.geometry_count(), false);
  bool any_transparent = false;
  auto alpha_of = [&](unsigned g) { return render_scene.material(scene.material(g)).alpha(); };
  if (options.transparency) {
    for (size_t g = 0; g < transparent.size(); ++g) any_transparent |= transparent[g] = alpha_of(unsigned(g)) < 1.0;
  }
  FragmentLists fragments;
  const VisibilityBuffer buffer = rasterize(scene, view, control, kRasterTile, nullptr,
                                            any_transparent ? &transparent : nullptr,
                                            any_transparent ? &fragments : nullptr);
  const Vec3d eye = camera.position();
  OitSettings oit = options.transparency.value_or(OitSettings{});
  if (any_transparent) fit_mboit_range(fragments, oit);

  if (options.shadow_light >= int(lights.spots.size())) {
    throw_invalid("shadow_light ", options.shadow_light, " must index the spot lights shaded (", lights.spots.size(),
                  ", as lights= or spots= select them)");
  }
  const bool output_shadow = options.output == RasterOutput::kShadow;
  if (output_shadow && options.shadow_light < 0 && !lights.sun) throw_invalid("output 'shadow': the scene has no sun");

  // The light evaluation the ray renderers use (DirectLighting), its visibility from the shadow
  // maps (or the Embree reference) for the sun and the spot lights, from straight shadow rays for
  // the other lights.
  RenderOptions ray_options;
  ray_options.method = RenderMethod::kStraight;
  const Caster caster(scene, nullptr, ray_options);
  const DirectLighting shadow_rays(render_scene, caster, ray_options);
  const RasterVisibility visibility(render_scene, lights, options, buffer, eye, shadow_rays, control);
  DirectLighting lighting(render_scene, caster, ray_options, &visibility);
  lighting.use_raised_sky(RaisedSky::for_camera(render_scene, eye.y()));  // a raised camera's sky (raised_sky.h)

  // Shading of a rasterized surface, every shining light deterministically: the sun along its disc's
  // centre (irradiance = disc radiance x solid angle; sunlight below), spots and point lights exactly,
  // lights with extent (area lights, environments, the sky) by light_strata^2 quasi-random light samples
  // and as many BSDF samples, combined by the power heuristic (Veach 1997, ch. 9) as the ray renderers'
  // direct lighting does. Light samples alone left a quadrature bias of +39 % under a panel 0.2 m above a
  // floor at n = 8 (its samples a grid on the panel, as far apart as the floor is from it); BSDF samples
  // alone (the earlier environment rule) missed or hit a small bright patch of a map: -73 % or +346 % (a
  // trial). A light that no BSDF sample can meet (no emitting geometry), and with shadows 'none' an area
  // light (a BSDF sample finds it through what stands in front), keeps its light samples alone.
  tbb::enumerable_thread_specific<ScratchBuffer> scratch_per_thread;
  const SampledWavelengths lambda_rgb = SampledWavelengths::rgb();
  const int n = options.light_strata;
  const double weight = 1.0 / (n * n);
  const std::vector<Vec3d> points = sample_points(n);
  const bool traced = options.shadows != ShadowSource::kNone;
  std::vector<size_t> environments;  // the infinite lights with extent among lights.others
  std::vector<bool> met_by_bsdf(render_scene.lights().size(), false);
  for (size_t i : lights.others) {
    const Light& light = *render_scene.lights()[i];
    if (light.is_delta()) continue;
    if (light.is_infinite()) environments.push_back(i);
    met_by_bsdf[i] = light.is_infinite() || (traced && render_scene.emitter_of(i) >= 0);
  }
  const bool bsdf_samples = std::find(met_by_bsdf.begin(), met_by_bsdf.end(), true) != met_by_bsdf.end();
  // The air between the eye and a surface (aerial perspective), as the ray renderers' integrators
  // add it: its in-scatter arrives, and it dims the surface's light (a trial: the raster image was
  // the same with and without the haze).
  const AerialPerspective* air = render_scene.aerial_perspective();
  auto through_air = [&](const Vec3d& p, const Spectrum& L) -> Vec3d {
    if (!air) return Vec3d(L.head<3>().matrix());
    const AerialPerspective::Segment segment = air->along(eye, p, caster.air_frame(), lambda_rgb);
    return Vec3d((segment.transmittance * L + segment.inscatter).head<3>().matrix());
  };
  // The environments seen along a BSDF sample that leaves the scene, each MIS-weighted against its
  // light samples (no weight for a specular sample, which light samples cannot take).
  auto environments_along = [&](const SurfaceInteraction& si, const BsdfSample& bs, const SampledWavelengths& lambda) {
    Spectrum L = Spectrum::Zero();
    LightSampleContext ctx;
    ctx.p = si.p;
    ctx.n = si.n_toward_wo();
    for (size_t i : environments) {
      const Light& light = *render_scene.lights()[i];
      const double mis =
          bs.is_specular() ? 1.0 : power_heuristic(1, bs.pdf, 1, light.pdf_li(ctx, bs.wi, Vec3d::Zero(), Vec3d::Zero()));
      L += lighting.distant_Le(light, si.p.y(), bs.wi, lambda) * mis;
    }
    return L;
  };
  // What a BSDF sample from si meets of the lights met by BSDF samples: an area light's surface
  // or, leaving the scene, the environments.
  auto met_along = [&](const SurfaceInteraction& si, const BsdfSample& bs, const SampledWavelengths& lambda) {
    if (!traced) return environments_along(si, bs, lambda);
    const PathEnd end = caster.cast(si.offset_toward(bs.wi), bs.wi);
    if (!end.hit) return environments_along(si, bs, lambda);
    const int light = render_scene.light_of(end.hit->geometry);
    if (light < 0 || !met_by_bsdf[size_t(light)]) return Spectrum::Zero().eval();
    const SurfaceInteraction at = scene.interaction(*end.hit, bs.wi, 0.0);
    Spectrum L = lighting.emitted(at, &si, bs.pdf, bs.is_specular(), lambda);
    if (air) L *= air->transmittance(si.p, at.p, caster.air_frame(), lambda);
    return L;
  };
  // The sun along its disc's centre (irradiance = disc radiance x solid angle): on a diffuse surface
  // within alpha^2 / 4 of the disc's integral (1.9e-5 for a disc of radius alpha = 0.5 deg) while the
  // whole disc stands above (or below) the surface's horizon. A wider disc, or one the horizon cuts,
  // by light_strata^2 samples of it (as its shadow map, their visibility is the centre's): a 170 deg
  // sun at the zenith was +84 %, the physical sun 0.1 deg up -15 % (a trial).
  const SunLight* sun = lights.sun_shines ? render_scene.sun() : nullptr;
  constexpr double kCentredSunRadius = kPi / 360.0;  // 0.5 deg [rad]
  const double sun_radius = sun ? degrees_to_radians(0.5 * sun->angular_diameter()) : 0.0;
  const bool small_sun = sun_radius <= kCentredSunRadius;
  const double sin_sun_radius = std::sin(sun_radius);
  auto sunlight = [&](const SurfaceInteraction& si, const SurfaceBsdf& bsdf, const SampledWavelengths& lambda) {
    if (small_sun && std::abs(si.n_toward_wo().dot(sun->direction())) >= sin_sun_radius) {
      return lighting.sample_light(*lights.sun, si, bsdf, lambda, Vec2d(0.0, 0.0), false);
    }
    Spectrum L = Spectrum::Zero();
    for (const Vec3d& u : points) L += lighting.sample_light(*lights.sun, si, bsdf, lambda, Vec2d(u.x(), u.y()), false);
    return Spectrum(L * weight);
  };
  auto shade = [&](const Hit& hit, const Vec3d& dir, double footprint) -> Vec3d {
    ScratchBuffer& scratch = scratch_per_thread.local();
    scratch.reset();
    const SurfaceInteraction si = scene.interaction(hit, dir, footprint);
    SampledWavelengths lambda = lambda_rgb;
    const Scattering s = scattering_at(render_scene, si, MediumStack(), 1.0, lambda, scratch);
    Spectrum L = lighting.emitted(si, nullptr, 0.0, true, lambda);
    if (!s.bsdf) return through_air(si.p, L);
    if (lights.sun_shines) L += sunlight(si, s.bsdf, lambda);
    for (size_t spot : lights.spots) L += lighting.sample_light(spot, si, s.bsdf, lambda, Vec2d(0.5, 0.5), false);
    for (size_t i : lights.others) {
      if (render_scene.lights()[i]->is_delta()) {
        L += lighting.sample_light(i, si, s.bsdf, lambda, Vec2d(0.5, 0.5), false);
        continue;
      }
      for (const Vec3d& u : points) {
        L += lighting.sample_light(i, si, s.bsdf, lambda, Vec2d(u.x(), u.y()), met_by_bsdf[i]) * weight;
      }
    }
    if (!bsdf_samples) return through_air(si.p, L);
    for (const Vec3d& u : points) {
      const auto bs = s.bsdf.sample(si.wo, u.z(), Vec2d(u.x(), u.y()));
      if (!bs || !(bs->weight.maxCoeff() > 0.0)) continue;
      if (si.leaks(bs->wi, bs->is_transmission())) continue;
      L += bs->weight * met_along(si, *bs, lambda) * weight;
    }
    return through_air(si.p, L);
  };
  auto sky = [&](const Vec3d& dir) {
    Spectrum L = Spectrum::Zero();
    for (size_t i = 0; i < render_scene.lights().size(); ++i) {
      const Light& light = *render_scene.lights()[i];
      if (light.is_infinite() && (i != lights.sun || lights.sun_shines)) {
        L += lighting.distant_Le(light, eye.y(), dir, lambda_rgb);
      }
    }
    return Vec3d(L.head<3>().matrix());
  };
  // output 'shadow': (shadow intensity, 1, 0) where the light reaches the surface, else zeros.
  const size_t shadow_light =
      options.shadow_light < 0 ? lights.sun.value_or(0) : lights.spots[size_t(options.shadow_light)];
  auto shadow_pixel = [&](const std::optional<Hit>& hit) {
    if (!hit || !visibility.reaches(shadow_light, hit->point, hit->normal)) return Vec3d::Zero().eval();
    return Vec3d(visibility.shadow(shadow_light, hit->point, hit->normal, hit->extent), 1.0, 0.0);
  };

  // Every pixel: its opaque surface (or the sky), under the transparent fragments in front of it.
  control.done = 0;
  Image image = render_tiles(camera.width(), camera.height(), options.tile, control, [&](int x, int y) {
    const auto hit = surface_at(scene, buffer, x, y, eye);
    if (output_shadow) return shadow_pixel(hit);
    const Vec3d dir = camera.direction(x + 0.5, y + 0.5);
    const Vec3d behind = hit ? shade(*hit, dir, camera.pixel_angle() * hit->t) : sky(dir);
    if (!any_transparent) return behind;
    const auto& list = fragments.lists[fragments.index(x, y)];
    if (list.empty()) return behind;
    std::vector<Fragment> layers;
    layers.reserve(list.size());
    for (const RasterFragment& f : list) {
      const Hit surface = surface_of(scene, f.geometry, f.primitive, f.b1, f.b2, eye);
      layers.push_back({double(f.depth), alpha_of(f.geometry), shade(surface, dir, camera.pixel_angle() * surface.t)});
    }
    return composite(layers, behind, oit);
  });
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->shadow_build_seconds = visibility.build_seconds();
    stats->bytes_per_texel = visibility.bytes_per_texel();
    stats->transparent_fragments = fragments.total();
    const double per_pixel = double(fragments.total()) / (double(camera.width()) * camera.height());
    stats->oit_bytes_per_pixel = any_transparent ? oit.bytes_per_pixel(per_pixel) : 0.0;
  }
  return image;
}

}  // namespace refracta
