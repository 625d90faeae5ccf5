// render_raster: the real-time pipeline on the CPU, for comparing moment methods (issue 5): the
// camera view rasterized into a visibility buffer, every pixel shaded once, the sun's shadow
// from a shadow map (hard, PCF, VSM, Hamburger / Hausdorff 4MSM) or from Embree shadow rays (the
// reference), transparent surfaces (alpha < 1) composited from per-pixel fragment lists (exact,
// peeling, WBOIT, MBOIT). Shadows treat every surface as opaque. No atmosphere: the straight view.
#include "refracta/render/raster_renderer.h"

#include "refracta/core/error.h"
#include "refracta/render/tile_loop.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace refracta {

void RasterRenderOptions::validate() const {
  if (shadows != "embree" && shadows != "none") shadow_map.validate();
  if (shadow_half_size && (!(*shadow_half_size > 0.0) || !std::isfinite(*shadow_half_size))) {
    throw_invalid("shadow_half_size must be > 0 (got ", *shadow_half_size, ")");
  }
  if (shadow_centre && !is_finite(*shadow_centre)) throw_invalid("shadow_centre must be finite");
  if (!(shadow_distance > 0.0)) throw_invalid("shadow_distance must be > 0 (got ", shadow_distance, ")");
  if (tile < 1) throw_invalid("tile must be >= 1 (got ", tile, ")");
  if (transparency) transparency->validate();
  if (shadow_light < -1) throw_invalid("shadow_light must be -1 (the sun) or a spot light index (got ", shadow_light, ")");
}

Image render_raster(const Scene& scene, const Lighting& all_lights, const Camera& camera,
                    const RasterRenderOptions& options, WorkControl& control, RasterRenderStats* stats) {
  options.validate();
  Lighting lighting = all_lights;
  if (!options.use_sun) lighting.sun.radiance = Vec3d::Zero();
  if (options.spots) {
    lighting.spots.clear();
    for (int k : *options.spots) {
      if (k < 0 || size_t(k) >= all_lights.spots.size()) {
        throw_invalid("lights: spot light ", k, " is not in the scene (it has ", all_lights.spots.size(), ")");
      }
      lighting.spots.push_back(all_lights.spots[k]);
    }
  }
  scene.commit();
  const auto start = std::chrono::steady_clock::now();
  const RasterView view = RasterView::from_camera(camera);
  std::vector<bool> transparent(scene.geometry_count(), false);
  bool any_transparent = false;
  if (options.transparency) {
    for (size_t g = 0; g < transparent.size(); ++g) any_transparent |= transparent[g] = scene.material(unsigned(g)).alpha < 1.0;
  }
  FragmentLists fragments;
  const VisibilityBuffer buffer =
      rasterize(scene, view, control, 32, nullptr, any_transparent ? &transparent : nullptr, any_transparent ? &fragments : nullptr);
  const Vec3d eye = camera.position();
  OitSettings oit = options.transparency.value_or(OitSettings{});
  if (any_transparent && oit.method == OitMethod::kMboit && !(oit.mboit.z_far > oit.mboit.z_near)) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const auto& list : fragments.lists) {
      for (const auto& f : list) lo = std::min(lo, double(f.depth)), hi = std::max(hi, double(f.depth));
    }
    if (hi > lo) oit.mboit.z_near = lo, oit.mboit.z_far = hi * (1.0 + 1e-6);
  }

  if (options.shadow_light >= int(lighting.spots.size())) {
    throw_invalid("shadow_light ", options.shadow_light, " is not a spot light of the scene (it has ",
                  lighting.spots.size(), ")");
  }
  const bool mapped = options.shadows != "embree" && options.shadows != "none";
  ShadowMapOptions map_options = options.shadow_map;
  if (mapped) map_options.method = parse_shadow_method(options.shadows);
  // The sun's map (when the sun shines or its shadow is asked for) covers, seen from the sun, the
  // visible points within shadow_distance.
  std::unique_ptr<ShadowMap> map;
  const bool sun_needed = lighting.sun.radiance.maxCoeff() > 0.0 || (options.output_shadow && options.shadow_light < 0);
  if (mapped && sun_needed) {
    const Vec3d along = -lighting.sun.direction.normalized();
    const Vec3d side = (std::abs(along.y()) < 0.99 ? along.cross(Vec3d::UnitY()) : along.cross(Vec3d::UnitX())).normalized();
    const Vec3d up = side.cross(along);
    Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int y = 0; y < buffer.height; ++y) {
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
    map = std::make_unique<ShadowMap>(scene, lighting.sun.direction, centre, half, map_options, control);
  }
  // One perspective map per spot light, covering its cone.
  std::vector<std::unique_ptr<ShadowMap>> spot_maps;
  if (mapped) {
    for (const SpotLight& spot : lighting.spots) {
      const Vec3d up = std::abs(spot.direction.y()) < 0.99 ? Vec3d::UnitY() : Vec3d::UnitX();
      const RasterView spot_view = RasterView::perspective(spot.position, spot.direction, up,
                                                           std::tan(0.5 * degrees_to_radians(spot.angle)),
                                                           map_options.resolution, 0.01);
      spot_maps.push_back(std::make_unique<ShadowMap>(scene, spot_view, map_options, control));
    }
  }
  const SunShadow from_map = [&](const Hit& hit, const Vec3d&) { return map->shadow(hit.point, hit.normal); };
  const SpotShadow from_spot_maps = [&](const Hit& hit, size_t k) { return spot_maps[k]->shadow(hit.point, hit.normal); };
  Lighting light = lighting;
  light.shadows = options.shadows != "none";
  const SunShadow* sun_shadow = map ? &from_map : nullptr;
  const SpotShadow* spot_shadow = mapped ? &from_spot_maps : nullptr;

  control.done = 0;
  Image image = render_tiles(camera.width(), camera.height(), options.tile, control, [&](int x, int y) {
    const auto hit = surface_at(scene, buffer, x, y, eye);
    const Vec3d dir = camera.direction(x + 0.5, y + 0.5);
    if (options.output_shadow) {  // (shadow intensity, 1) where the light reaches the surface, else (0, 0)
      if (!hit) return Vec3d::Zero().eval();
      if (options.shadow_light < 0) {
        if (hit->normal.dot(lighting.sun.direction) <= 0.0) return Vec3d::Zero().eval();
        const double s = !light.shadows ? 0.0 : map ? map->shadow(hit->point, hit->normal) : sun_occlusion(scene, *hit, lighting.sun.direction);
        return Vec3d(s, 1.0, 0.0);
      }
      const SpotLight& spot = lighting.spots[options.shadow_light];
      if (!spot.covers(hit->point) || hit->normal.dot(spot.position - hit->point) <= 0.0) return Vec3d::Zero().eval();
      const double s = !light.shadows ? 0.0
                       : mapped      ? spot_maps[options.shadow_light]->shadow(hit->point, hit->normal)
                                     : spot_occlusion(scene, *hit, spot);
      return Vec3d(s, 1.0, 0.0);
    }
    PathEnd end;
    end.direction = dir;
    end.hit = hit;
    if (hit) end.length = hit->t;
    Rng rng(0, uint64_t(y) * uint64_t(camera.width()) + uint64_t(x));
    const Vec3d behind = shade(scene, light, end, rng, false, camera.pixel_angle(), sun_shadow, spot_shadow);
    if (!any_transparent) return behind;
    const auto& list = fragments.lists[fragments.index(x, y)];
    if (list.empty()) return behind;
    std::vector<Fragment> layers;
    layers.reserve(list.size());
    for (const RasterFragment& f : list) {
      PathEnd surface;
      surface.direction = dir;
      surface.hit = surface_of(scene, f.geometry, f.primitive, f.b1, f.b2, eye);
      surface.length = surface.hit->t;
      layers.push_back({double(f.depth), scene.material(f.geometry).alpha,
                        shade(scene, light, surface, rng, false, camera.pixel_angle(), sun_shadow, spot_shadow)});
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
