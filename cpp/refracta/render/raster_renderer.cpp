// render_raster: the real-time pipeline on the CPU, for comparing moment methods (issue 5): the
// camera view rasterized into a visibility buffer, every pixel shaded once, the sun's shadow
// from a shadow map (hard, PCF, VSM, Hamburger / Hausdorff 4MSM) or from Embree shadow rays (the
// reference), transparent surfaces (alpha < 1) composited from per-pixel fragment lists (exact,
// peeling, WBOIT, MBOIT). Shadows treat every surface as opaque. No atmosphere: the straight view.
#include "refracta/render/raster_renderer.h"

#include "refracta/core/error.h"
#include "refracta/core/frame.h"
#include "refracta/core/rng.h"
#include "refracta/core/scratch.h"
#include "refracta/render/surface_scattering.h"
#include "refracta/render/tile_loop.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"

#include <tbb/enumerable_thread_specific.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

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
  if (shadows == ShadowSource::kMap) shadow_map.check(problems);
  if (shadow_half_size) {
    problems.check(*shadow_half_size > 0.0 && std::isfinite(*shadow_half_size), "shadow_half_size must be > 0 (got ",
                   *shadow_half_size, ")");
  }
  if (shadow_centre) problems.check(is_finite(*shadow_centre), "shadow_centre must be finite");
  problems.check(shadow_distance > 0.0, "shadow_distance must be > 0 (got ", shadow_distance, ")");
  problems.check(tile >= 1, "tile must be >= 1 (got ", tile, ")");
  if (transparency) transparency->check(problems);
  problems.check(shadow_light >= -1, "shadow_light must be -1 (the sun) or a spot light index (got ", shadow_light, ")");
  problems.check(light_strata >= 1 && light_strata <= 64, "light_strata must be in [1, 64] (got ", light_strata, ")");
}

void RasterRenderOptions::validate() const {
  Problems problems("RasterRenderOptions");
  check(problems);
  problems.throw_if_any();
}

namespace {

constexpr double kFar = 1e7;  // [m] shadow rays toward distant lights end here

Vec3d offset_point(const Hit& hit) { return hit.point + hit.normal * (1e-5 + 2e-6 * hit.point.cwiseAbs().maxCoeff()); }

double sun_occlusion(const Scene& scene, const Hit& hit, const Vec3d& wi) {
  return scene.occluded(offset_point(hit), wi, kFar) ? 1.0 : 0.0;
}

// The reference for spot light shadows: a shadow ray to the point light, or for an area spot
// (radius > 0) 8 x 8 stratified shadow rays to its disc (soft shadows).
double spot_occlusion(const Scene& scene, const Hit& hit, const SpotLight& light, double radius) {
  const Vec3d p = offset_point(hit);
  auto blocked = [&](const Vec3d& target) {
    const Vec3d to = target - p;
    const double d = to.norm();
    return d > 0.0 && scene.occluded(p, to / d, d * (1.0 - 1e-7)) ? 1.0 : 0.0;
  };
  if (radius <= 0.0) return blocked(light.position());
  const Frame disc = Frame::from_z(light.direction());
  constexpr int kStrata = 8;
  double sum = 0.0;
  for (int i = 0; i < kStrata; ++i) {
    for (int j = 0; j < kStrata; ++j) {
      const Vec2d q = sample_uniform_disk_concentric(Vec2d((i + 0.5) / kStrata, (j + 0.5) / kStrata)) * radius;
      sum += blocked(light.position() + disc.from_local(Vec3d(q.x(), q.y(), 0.0)));
    }
  }
  return sum / (kStrata * kStrata);
}

bool spot_covers(const SpotLight& spot, const Vec3d& point) {
  const Vec3d to = point - spot.position();
  return to.norm() > 0.0 && spot.falloff(to.normalized()) > 0.0;
}

}  // namespace

Image render_raster(const RenderScene& render_scene, const Camera& camera, const RasterRenderOptions& options,
                    WorkControl& control, RasterRenderStats* stats) {
  options.validate();
  if (camera.aperture_diameter() > 0.0) {
    throw_invalid("render_raster draws through a pinhole: depth of field (a camera with an f_number) needs "
                  "refracta.render with method 'straight' or 'curved'");
  }
  // float32 RGB here and in the numpy copy handed to Python: 24 bytes per pixel at least.
  check_image_memory(camera.width(), camera.height(), 24.0, "render_raster");
  render_scene.prepare();
  const Scene& scene = render_scene.geometry;
  // The lights: the sun (the first), the spot lights (selected by options.spots), and the rest.
  const SunLight* sun = nullptr;
  std::vector<const SpotLight*> all_spots;
  std::vector<size_t> spot_index;  // in the scene's light list
  std::vector<size_t> others;
  for (size_t i = 0; i < render_scene.lights().size(); ++i) {
    const Light* light = render_scene.lights()[i].get();
    if (auto s = dynamic_cast<const SunLight*>(light); s && !sun) {
      sun = s;
    } else if (auto spot = dynamic_cast<const SpotLight*>(light)) {
      all_spots.push_back(spot), spot_index.push_back(i);
    } else {
      others.push_back(i);
    }
  }
  std::vector<const SpotLight*> spots;
  std::vector<double> spot_radius;
  std::vector<size_t> chosen_spots;
  for (size_t k = 0; k < all_spots.size(); ++k) chosen_spots.push_back(k);
  if (options.spots) {
    chosen_spots.clear();
    for (int k : *options.spots) {
      if (k < 0 || size_t(k) >= all_spots.size()) {
        throw_invalid("lights: spot light ", k, " is not in the scene (it has ", all_spots.size(), ")");
      }
      chosen_spots.push_back(size_t(k));
    }
  }
  for (size_t k : chosen_spots) spots.push_back(all_spots[k]), spot_radius.push_back(render_scene.shadow_radius(spot_index[k]));
  const bool sun_on = sun && options.use_sun;
  const Vec3d sun_direction = sun ? sun->direction() : Vec3d::UnitY();
  const auto start = std::chrono::steady_clock::now();
  const RasterView view = RasterView::from_camera(camera);
  std::vector<bool> transparent(scene.geometry_count(), false);
  bool any_transparent = false;
  auto alpha_of = [&](unsigned g) { return render_scene.material(scene.material(g)).alpha(); };
  if (options.transparency) {
    for (size_t g = 0; g < transparent.size(); ++g) any_transparent |= transparent[g] = alpha_of(unsigned(g)) < 1.0;
  }
  FragmentLists fragments;
  const VisibilityBuffer buffer =
      rasterize(scene, view, control, kRasterTile, nullptr, any_transparent ? &transparent : nullptr, any_transparent ? &fragments : nullptr);
  const Vec3d eye = camera.position();
  OitSettings oit = options.transparency.value_or(OitSettings{});
  if (any_transparent && oit.method == OitMethod::kMboit && !(oit.mboit.z_far > oit.mboit.z_near)) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const auto& list : fragments.lists) {
      for (const auto& f : list) lo = std::min(lo, double(f.depth)), hi = std::max(hi, double(f.depth));
    }
    if (hi > lo) oit.mboit.z_near = lo, oit.mboit.z_far = hi * (1.0 + 1e-6);
  }

  if (options.shadow_light >= int(spots.size())) {
    throw_invalid("shadow_light ", options.shadow_light, " is not a spot light of the scene (it has ", spots.size(), ")");
  }
  const bool output_shadow = options.output == RasterOutput::kShadow;
  if (output_shadow && options.shadow_light < 0 && !sun) throw_invalid("output 'shadow': the scene has no sun");
  const bool mapped = options.shadows == ShadowSource::kMap;
  const bool shadows_on = options.shadows != ShadowSource::kNone;
  const ShadowMapOptions& map_options = options.shadow_map;
  // The sun's map (when the sun shines or its shadow is asked for) covers, seen from the sun, the
  // visible points within shadow_distance.
  std::unique_ptr<ShadowMap> map;
  const bool sun_needed = sun_on || (output_shadow && options.shadow_light < 0);
  if (mapped && sun_needed) {
    const Vec3d along = -sun_direction;
    const Frame sun_frame = Frame::from_z(along);
    const Vec3d side = sun_frame.s, up = sun_frame.t;
    Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int y = 0; y < buffer.height; ++y) {
      poll_cancel();  // a serial pass over every pixel
      for (int x = 0; x < buffer.width; ++x) {
        const auto hit = surface_at(scene, buffer, x, y, eye);
        if (!hit || (hit->point - eye).norm() > options.shadow_distance) continue;
        const Vec3d q(hit->point.dot(side), hit->point.dot(up), hit->point.dot(along));
        lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      }
    }
    Vec3d centre = options.shadow_centre.value_or(Vec3d::Zero());
    double half = options.shadow_half_size.value_or(1.0);
    if (!options.shadow_centre || !options.shadow_half_size) {
      if (!(hi.x() >= lo.x())) lo = hi = Vec3d::Zero();
      const Vec3d mid = 0.5 * (lo + hi);
      if (!options.shadow_centre) centre = mid.x() * side + mid.y() * up + mid.z() * along;
      if (!options.shadow_half_size) half = std::max(0.5 * (hi - lo).head<2>().maxCoeff() * 1.02, 1e-3);
    }
    map = std::make_unique<ShadowMap>(scene, sun_direction, centre, half, map_options, control);
  }
  // One perspective map per spot light, covering its cone.
  std::vector<std::unique_ptr<ShadowMap>> spot_maps;
  if (mapped) {
    for (const SpotLight* spot : spots) {
      const Vec3d up = std::abs(spot->direction().y()) < 0.99 ? Vec3d::UnitY() : Vec3d::UnitX();
      const RasterView spot_view = RasterView::perspective(spot->position(), spot->direction(), up,
                                                           std::tan(0.5 * degrees_to_radians(std::min(spot->angle(), 170.0))),
                                                           map_options.resolution, 0.01);
      spot_maps.push_back(std::make_unique<ShadowMap>(scene, spot_view, map_options, control));
    }
  }
  auto sun_shadow = [&](const Hit& hit) {
    return !shadows_on ? 0.0 : map ? map->shadow(hit.point, hit.normal) : sun_occlusion(scene, hit, sun_direction);
  };
  auto spot_shadow = [&](const Hit& hit, size_t k) {
    return !shadows_on ? 0.0 : mapped ? spot_maps[k]->shadow(hit.point, hit.normal) : spot_occlusion(scene, hit, *spots[k], spot_radius[k]);
  };

  // Shading of a rasterized surface: every chosen light evaluated deterministically -- the sun
  // along its centre (irradiance = disc radiance x solid angle) and spots exactly, with the
  // shadow method's visibility; other lights by light_strata^2 stratified samples with Embree
  // shadow rays.
  tbb::enumerable_thread_specific<ScratchBuffer> scratch_per_thread;
  const SampledWavelengths lambda_rgb = SampledWavelengths::rgb();
  auto shade = [&](const Hit& hit, const Vec3d& dir, double footprint) -> Vec3d {
    ScratchBuffer& scratch = scratch_per_thread.local();
    scratch.reset();
    const SurfaceInteraction si = scene.interaction(hit, dir, footprint);
    SampledWavelengths lambda = lambda_rgb;
    const Scattering s = scattering_at(render_scene, si, MediumStack(), 1.0, lambda, scratch);
    Spectrum L = Spectrum::Zero();
    if (const int e = render_scene.light_of(si.geometry); e >= 0) {
      L += render_scene.lights()[size_t(e)]->L(si.p, si.n, si.wo, lambda);
    }
    if (!s.bsdf) return Vec3d(L.head<3>().matrix());
    LightSampleContext ctx;
    ctx.p = si.p;
    ctx.n = si.n_toward_wo();
    // f L |cos| / pdf of a light sample arriving along ls.wi, scaled by the visible fraction.
    auto add = [&](const LightLiSample& ls, double visible, double weight) {
      if (!(ls.pdf > 0.0) || ls.wi.dot(ctx.n) <= 0.0) return;
      L += s.bsdf.f(si.wo, ls.wi) * ls.L * (std::abs(ls.wi.dot(s.bsdf.frame.n)) * visible * weight / ls.pdf);
    };
    if (sun_on && hit.normal.dot(sun_direction) > 0.0) {
      if (const auto ls = sun->sample_li(ctx, Vec2d(0.0, 0.0), lambda)) add(*ls, 1.0 - sun_shadow(hit), 1.0);  // the disc's centre
    }
    for (size_t k = 0; k < spots.size(); ++k) {
      if (!spot_covers(*spots[k], si.p) || hit.normal.dot(spots[k]->position() - si.p) <= 0.0) continue;
      if (const auto ls = spots[k]->sample_li(ctx, Vec2d(0.5, 0.5), lambda)) add(*ls, 1.0 - spot_shadow(hit, k), 1.0);
    }
    const int n = options.light_strata;
    const double weight = 1.0 / (n * n);
    for (size_t i : others) {
      const Light& light = *render_scene.lights()[i];
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          const Vec2d u((a + 0.5) / n, (b + 0.5) / n);
          if (light.is_infinite()) {
            // Environments by BSDF sampling: its weight f |cos| / pdf is smooth (for a diffuse
            // surface, the albedo), so a few strata converge where the light's own density
            // (luminance x sin theta) would leave a cot-shaped integrand.
            const auto bs = s.bsdf.sample(si.wo, (a * n + b + 0.5) * weight, u);
            if (!bs || bs->wi.dot(ctx.n) <= 0.0) continue;
            if (shadows_on && scene.occluded(si.offset_toward(bs->wi), bs->wi, kFar)) continue;
            L += bs->weight * light.Le(bs->wi, lambda) * weight;
            continue;
          }
          const auto ls = light.sample_li(ctx, u, lambda);
          if (!ls || !(ls->pdf > 0.0) || ls->wi.dot(ctx.n) <= 0.0) continue;
          const Vec3d from = si.offset_toward(ls->wi);
          if (shadows_on && scene.occluded(from, ls->wi, (ls->p_light - from).norm() * (1.0 - 1e-6))) continue;
          add(*ls, 1.0, weight);
        }
      }
    }
    return Vec3d(L.head<3>().matrix());
  };
  auto sky = [&](const Vec3d& dir) {
    Spectrum L = Spectrum::Zero();
    for (const auto& light : render_scene.lights()) {
      if (light->is_infinite() && (light.get() != sun || sun_on)) L += light->Le(dir, lambda_rgb);
    }
    return Vec3d(L.head<3>().matrix());
  };

  control.done = 0;
  Image image = render_tiles(camera.width(), camera.height(), options.tile, control, [&](int x, int y) {
    const auto hit = surface_at(scene, buffer, x, y, eye);
    const Vec3d dir = camera.direction(x + 0.5, y + 0.5);
    if (output_shadow) {  // (shadow intensity, 1) where the light reaches the surface, else (0, 0)
      if (!hit) return Vec3d::Zero().eval();
      if (options.shadow_light < 0) {
        if (hit->normal.dot(sun_direction) <= 0.0) return Vec3d::Zero().eval();
        return Vec3d(sun_shadow(*hit), 1.0, 0.0);
      }
      const SpotLight& spot = *spots[size_t(options.shadow_light)];
      if (!spot_covers(spot, hit->point) || hit->normal.dot(spot.position() - hit->point) <= 0.0) return Vec3d::Zero().eval();
      return Vec3d(spot_shadow(*hit, size_t(options.shadow_light)), 1.0, 0.0);
    }
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
    stats->shadow_build_seconds = 0.0;
    stats->bytes_per_texel = 0;
    if (map) spot_maps.push_back(std::move(map));
    for (const auto& m : spot_maps) {
      stats->shadow_build_seconds += m->build_seconds();
      stats->bytes_per_texel = m->bytes_per_texel();
    }
    stats->transparent_fragments = fragments.total();
    const double per_pixel = double(fragments.total()) / (double(camera.width()) * camera.height());
    stats->oit_bytes_per_pixel = any_transparent ? oit.bytes_per_pixel(per_pixel) : 0.0;
  }
  return image;
}

}  // namespace refracta
