// render_raster's lights and their shadows (raster_visibility.h).
#include "refracta/render/raster_visibility.h"

#include "refracta/core/error.h"
#include "refracta/core/frame.h"
#include "refracta/core/image.h"
#include "refracta/scene/surface_interaction.h"
#include "refracta/scene/terrain.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

// The reference for spot light shadows: the fraction of shadow rays blocked, one to the point
// light, or for an area spot (radius > 0) 8 x 8 stratified ones to its disc (soft shadows).
double spot_occlusion(const Scene& scene, const Vec3d& p_surface, const Vec3d& n, const Vec3d& extent,
                      const SpotLight& light, double radius) {
  const Vec3d p = offset_point(p_surface, n, extent);
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

// Where, seen from the sun (side, up), anything can cast a shadow on points no lower than
// `lowest` [m]: the box of every geometry's bounds but a flat horizontal one at or below `lowest`
// under a sun above the horizon (a ground can shadow nothing above it). Empty: no caster.
Eigen::AlignedBox2d caster_bounds(const Scene& scene, const Vec3d& sun_direction, const Vec3d& side, const Vec3d& up,
                                  double lowest) {
  Eigen::AlignedBox2d out;
  for (const SceneMesh& entry : scene.meshes()) {
    if (scene.removed(entry.geometry)) continue;
    Eigen::AlignedBox3d box;
    if (const TerrainGrid* terrain = scene.terrain(entry.geometry)) box.extend(terrain->lower()).extend(terrain->upper());
    for (const Vec3d& vertex : entry.mesh.vertices) box.extend(vertex);
    if (box.isEmpty() || (box.sizes().y() == 0.0 && box.max().y() <= lowest && sun_direction.y() > 0.0)) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d p = box.corner(Eigen::AlignedBox3d::CornerType(corner));
      out.extend(Eigen::Vector2d(p.dot(side), p.dot(up)));
    }
  }
  return out;
}

// The sun's orthographic map: given, or fitted (seen from the sun) to the visible points closer
// than shadow_distance to the eye that some geometry lies over (caster_bounds; a point outside
// the map is lit), 2 % wider than they are. Fitted to the visible points alone, a 2 km ground
// spread the map's texels over kilometres, and 1.6 m boxes on it lost every shadow (a trial).
std::unique_ptr<ShadowMap> sun_map(const Scene& scene, const Vec3d& sun_direction, const RasterRenderOptions& options,
                                   const VisibilityBuffer& buffer, const Vec3d& eye, WorkControl& control) {
  const Vec3d along = -sun_direction;
  const Frame sun_frame = Frame::from_z(along);
  const Vec3d side = sun_frame.s, up = sun_frame.t;
  Vec3d centre = options.shadow_centre.value_or(Vec3d::Zero());
  double half = options.shadow_half_size.value_or(1.0);
  if (!options.shadow_centre || !options.shadow_half_size) {
    Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double lowest = std::numeric_limits<double>::infinity();  // of the visible points [m]
    for (int y = 0; y < buffer.height; ++y) {
      poll_cancel();  // a serial pass over every pixel
      for (int x = 0; x < buffer.width; ++x) {
        const auto hit = surface_at(scene, buffer, x, y, eye);
        if (!hit || (hit->point - eye).norm() > options.shadow_distance) continue;
        const Vec3d q(hit->point.dot(side), hit->point.dot(up), hit->point.dot(along));
        lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
        lowest = std::min(lowest, hit->point.y());
      }
    }
    const Eigen::AlignedBox2d casters = caster_bounds(scene, sun_direction, side, up, lowest);
    if (!casters.isEmpty()) {
      lo.head<2>() = lo.head<2>().cwiseMax(casters.min());
      hi.head<2>() = hi.head<2>().cwiseMin(casters.max());
    }
    if (!(hi.x() >= lo.x() && hi.y() >= lo.y())) lo = hi = Vec3d::Zero();  // nothing visible under a caster
    const Vec3d mid = 0.5 * (lo + hi);
    if (!options.shadow_centre) centre = mid.x() * side + mid.y() * up + mid.z() * along;
    if (!options.shadow_half_size) half = std::max(0.5 * (hi - lo).head<2>().maxCoeff() * 1.02, 1e-3);
  }
  return std::make_unique<ShadowMap>(scene, sun_direction, centre, half, options.shadow_map, control);
}

// A spot light's perspective map over its cone (at most kWidestMappedSpot wide: raster_lights).
// The map stores linear depth fitted to what it sees (ShadowMap), so the near plane only clips:
// 1 cm lost a lamp shade's quad 8 mm from the light, and every shadow it cast (a trial).
constexpr double kSpotMapNear = 1e-4;  // [m]
std::unique_ptr<ShadowMap> spot_map(const Scene& scene, const SpotLight& spot, const ShadowMapOptions& options,
                                    WorkControl& control) {
  const Vec3d up = std::abs(spot.direction().y()) < 0.99 ? Vec3d::UnitY() : Vec3d::UnitX();
  const double tan_half = std::tan(0.5 * degrees_to_radians(spot.angle()));
  const RasterView view = RasterView::perspective(spot.position(), spot.direction(), up, tan_half, options.resolution,
                                                  kSpotMapNear);
  return std::make_unique<ShadowMap>(scene, view, options, control);
}

}  // namespace

RasterLights raster_lights(const RenderScene& scene, const RasterRenderOptions& options) {
  const SunLight* sun = scene.sun();
  const std::vector<const SpotLight*> spots = scene.spots();
  RasterLights out;
  std::vector<size_t> spot_index;  // in the scene's light list, k-th spot light first
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const Light* light = scene.lights()[i].get();
    if (light == sun) {
      out.sun = i;
    } else if (std::find(spots.begin(), spots.end(), light) != spots.end()) {
      spot_index.push_back(i);
    } else {
      out.others.push_back(i);
    }
  }
  out.sun_shines = out.sun && options.use_sun;
  if (!options.spots) {
    out.spots = spot_index;
  } else {
    for (int k : *options.spots) {
      if (k < 0 || size_t(k) >= spot_index.size()) {
        throw_invalid("lights: spot light ", k, " is not in the scene (it has ", spot_index.size(), ")");
      }
      // Listed twice, a spot shone twice (a trial: exactly 2x its light).
      if (std::find(out.spots.begin(), out.spots.end(), spot_index[size_t(k)]) != out.spots.end()) {
        throw_invalid("lights: spot light ", k, " is listed twice");
      }
      out.spots.push_back(spot_index[size_t(k)]);
    }
  }
  if (options.shadows == ShadowSource::kMap) {  // one perspective map per spot light
    for (size_t k = 0; k < spot_index.size(); ++k) {
      const double angle = spots[k]->angle();
      const bool used = std::find(out.spots.begin(), out.spots.end(), spot_index[k]) != out.spots.end();
      if (used && angle > kWidestMappedSpot) {
        throw_invalid("spot light ", k, " is ", angle, " deg wide: a shadow map covers at most ", kWidestMappedSpot,
                      " deg (shadows='embree' traces its shadows, or narrow the light)");
      }
    }
  }
  return out;
}

RasterVisibility::RasterVisibility(const RenderScene& scene, const RasterLights& lights,
                                   const RasterRenderOptions& options, const VisibilityBuffer& buffer, const Vec3d& eye,
                                   const LightVisibility& rays, WorkControl& control)
    : scene_(scene), source_(options.shadows), rays_(rays), sun_(lights.sun) {
  const size_t count = scene.lights().size();
  spot_.assign(count, nullptr);
  radius_.assign(count, 0.0);
  maps_.resize(count);
  if (sun_) sun_direction_ = scene.sun()->direction();
  for (const SpotLight* spot : scene.spots()) {
    for (size_t i : lights.spots) {
      if (scene.lights()[i].get() != spot) continue;
      spot_[i] = spot;
      radius_[i] = scene.shadow_radius(i);
    }
  }
  if (source_ != ShadowSource::kMap) return;
  const bool sun_needed = lights.sun_shines || (options.output == RasterOutput::kShadow && options.shadow_light < 0);
  // Each map is checked alone (ShadowMapOptions); all of them live together (eleven spot lights'
  // 8192^2 moment maps took 25 GB).
  const int resolution = options.shadow_map.resolution;
  const size_t maps = lights.spots.size() + (sun_ && sun_needed ? 1 : 0);
  check_image_memory(resolution, resolution, double(maps) * options.shadow_map.bytes_per_texel(),
                     concat("render_raster's ", maps, " shadow maps").c_str());
  if (sun_ && sun_needed) maps_[*sun_] = sun_map(scene.geometry, sun_direction_, options, buffer, eye, control);
  for (size_t i : lights.spots) {
    if (!maps_[i]) maps_[i] = spot_map(scene.geometry, *spot_[i], options.shadow_map, control);
  }
}

bool RasterVisibility::reaches(size_t light, const Vec3d& p, const Vec3d& n) const {
  if (const SpotLight* spot = spot_[light]) {
    const Vec3d to = p - spot->position();
    return to.norm() > 0.0 && spot->falloff(to.normalized()) > 0.0 && n.dot(-to) > 0.0;
  }
  return n.dot(sun_direction_) > 0.0;
}

double RasterVisibility::shadow(size_t light, const Vec3d& p, const Vec3d& n, const Vec3d& extent) const {
  if (source_ == ShadowSource::kNone) return 0.0;
  if (source_ == ShadowSource::kMap) return maps_[light]->shadow(p, n);
  if (const SpotLight* spot = spot_[light]) return spot_occlusion(scene_.geometry, p, n, extent, *spot, radius_[light]);
  return scene_.geometry.occluded(offset_point(p, n, extent), sun_direction_, kSceneReach) ? 1.0 : 0.0;
}

Spectrum RasterVisibility::arriving(size_t light, const SurfaceInteraction& si, const Vec3d& wi,
                                    const LightLiSample& ls, const SampledWavelengths& lambda) const {
  // The sun and the spots light the side their maps see; the other lights arrive from any side,
  // as in the ray renderers (through a rough glass, from behind: render_raster's BSDF samples meet
  // them there too, and MIS needs both kinds of sample to cover the same directions).
  if (spot_[light] || light == sun_) {
    const Vec3d n = si.n_toward_wo();
    return wi.dot(n) <= 0.0 ? Spectrum::Zero() : Spectrum(ls.L * (1.0 - shadow(light, si.p, n, si.extent)));
  }
  return source_ == ShadowSource::kNone ? ls.L : rays_.arriving(light, si, wi, ls, lambda);
}

double RasterVisibility::build_seconds() const {
  double seconds = 0.0;
  for (const auto& map : maps_) seconds += map ? map->build_seconds() : 0.0;
  return seconds;
}

int RasterVisibility::bytes_per_texel() const {
  for (const auto& map : maps_) {
    if (map) return map->bytes_per_texel();
  }
  return 0;
}

}  // namespace refracta
