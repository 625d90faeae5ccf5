#include "refracta/render/scene_building.h"

#include "refracta/core/error.h"
#include "refracta/core/sampling.h"
#include "refracta/scene/terrain.h"
#include "refracta/shading/area_light.h"
#include "refracta/shading/phong.h"
#include "refracta/shading/point_light.h"
#include "refracta/shading/sky_batch.h"  // sky_settings
#include "refracta/shading/sphere_light.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"
#include "refracta/shading/water_surface.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

namespace refracta {

unsigned geometry_id(int geometry) {
  if (geometry < 0) throw_invalid("geometry must be an id returned by add_* (got ", geometry, ")");
  return unsigned(geometry);
}

void check_uvs(const RenderScene& scene, int material, bool has_uvs, const char* what) {
  if (has_uvs || !scene.material(material).textured()) return;
  throw_invalid(what, ": ", scene.material(material).describe(),
                " has a texture but this geometry has no texture coordinates; give the mesh uvs= (add_mesh),"
                " use add_ground (its texture_size sets the repeat) or an OBJ with vt lines, or drop the texture");
}

void normalise_normals(Mesh& mesh) {
  if (mesh.normals.size() != mesh.vertices.size()) throw_invalid("normals must have one entry per vertex");
  for (Vec3d& n : mesh.normals) {
    if (!(n.norm() > 0.0)) throw_invalid("normals must be non-zero");
    n.normalize();
  }
}

MissingTextures missing_textures_from(const std::string& name) {
  if (name != "error" && name != "warn") throw_invalid("missing_textures must be 'error' or 'warn' (got '", name, "')");
  return name == "warn" ? MissingTextures::kWarn : MissingTextures::kError;
}

namespace {

void check_material_or_shorthand(const SurfaceLook& look, const char* call) {
  if (look.material && (look.kd || look.ks || look.ns || look.alpha || look.texture)) {
    throw_invalid(call, ": give `material` or the kd/ks/ns/alpha/texture shorthand, not both (the shorthand "
                  "would be ignored)");
  }
}

// The look's material added to the scene: its own, or the shorthand's BlinnPhong (texture: a scene
// texture id, -1 for none).
int material_of(RenderScene& scene, const SurfaceLook& look, int texture, double default_kd) {
  if (look.material) return scene.add_material(look.material);
  return scene.add_material(std::make_shared<BlinnPhong>(
      TexturedReflectance(look.kd.value_or(Vec3d::Constant(default_kd)), "kd", texture), look.ks.value_or(Vec3d::Zero()),
      look.ns.value_or(BlinnPhong::kDefaultNs), look.alpha.value_or(1.0)));
}

// A mesh with its material and, with the look's emission, its area light.
unsigned add_surface(RenderScene& scene, const Mesh& mesh, int material, const SurfaceLook& look, const char* what) {
  if (look.two_sided && !look.emission) {
    throw_invalid(what, ": two_sided makes an area light emit from both faces: give emission= too (a surface is seen "
                  "from both sides anyway)");
  }
  check_uvs(scene, material, !mesh.uvs.empty(), what);
  const unsigned id = scene.geometry.add_mesh(mesh, material);
  if (look.emission) scene.add_light(std::make_shared<AreaLight>(mesh, *look.emission, look.two_sided), int(id));
  return id;
}

}  // namespace

unsigned add_mesh(RenderScene& scene, Mesh mesh, const SurfaceLook& look) {
  if (!mesh.normals.empty()) normalise_normals(mesh);
  check_material_or_shorthand(look, "add_mesh");
  const int texture = look.texture ? scene.geometry.add_texture(*look.texture) : -1;
  if (texture >= 0 && mesh.uvs.empty()) throw_invalid("add_mesh: a texture needs uvs");
  return add_surface(scene, mesh, material_of(scene, look, texture, BlinnPhong::kDefaultKd), look, "add_mesh");
}

unsigned add_box(RenderScene& scene, const Vec3d& centre, const Vec3d& size, const SurfaceLook& look) {
  const Mesh mesh = box_mesh(centre, size);
  check_material_or_shorthand(look, "add_box");
  return add_surface(scene, mesh, material_of(scene, look, -1, BlinnPhong::kDefaultKd), look, "add_box");
}

unsigned add_sphere(RenderScene& scene, const Vec3d& centre, double radius, const SurfaceLook& look) {
  if (!(radius > 0.0) || !std::isfinite(radius)) throw_invalid("add_sphere: radius must be > 0 (got ", radius, ")");
  check_material_or_shorthand(look, "add_sphere");
  const int material = material_of(scene, look, -1, BlinnPhong::kDefaultKd);
  check_uvs(scene, material, false, "add_sphere");
  const unsigned id = scene.geometry.add_spheres({centre}, {radius}, material);
  if (look.emission) scene.add_light(std::make_shared<SphereLight>(centre, radius, *look.emission), int(id));
  return id;
}

unsigned add_ground(RenderScene& scene, double height, double size, const SurfaceLook& look,
                    std::optional<double> texture_size) {
  const bool uvs = look.texture || (look.material && look.material->textured());
  if (texture_size && !uvs) throw_invalid("add_ground: texture_size applies to a texture (texture= or a textured material)");
  const Mesh mesh = uvs ? ground_mesh(height, 0.5 * size, texture_size.value_or(kGroundTextureSize))
                        : ground_mesh(height, 0.5 * size);
  check_material_or_shorthand(look, "add_ground");
  const int texture = look.texture ? scene.geometry.add_texture(*look.texture) : -1;
  return scene.geometry.add_mesh(mesh, material_of(scene, look, texture, kGroundKd));
}

unsigned add_billboard(RenderScene& scene, const Vec3d& centre, double width, double height,
                       const std::string& texture, const Vec3d& facing, const std::optional<Vec3d>& kd) {
  const Mesh mesh = billboard_mesh(centre, width, height, facing);
  SurfaceLook look;
  look.kd = kd;
  const int picture = scene.geometry.add_texture(texture);
  const unsigned id = scene.geometry.add_mesh(mesh, material_of(scene, look, picture, 1.0));
  // A picture with alpha is a cut-out: a ship photographed with its sky cleared stands as a ship.
  if (scene.geometry.textures().has_alpha(picture)) scene.geometry.set_cutout(id, picture);
  return id;
}

void set_geometry_material(RenderScene& scene, int geometry, const MaterialPtr& material) {
  const unsigned g = geometry_id(geometry);
  scene.geometry.check_geometry(g, "set_material");
  if (material->textured() && !scene.geometry.has_uvs(g)) {
    throw_invalid("set_material: ", material->describe(), " has a texture but geometry ", g,
                  " has no texture coordinates (uvs)");
  }
  scene.set_material(g, material);
}

std::pair<Vec3d, Vec3d> scene_bounds(const RenderScene& scene) {
  const Vec3d lower = scene.geometry.lower(), upper = scene.geometry.upper();
  // No geometry, or all of it removed (the box is then inverted: +inf below -inf).
  if (scene.geometry.geometry_count() == 0 || !(lower.array() <= upper.array()).all()) {
    throw_invalid("Scene.bounds: the scene is empty (it holds no geometry, or all of it was removed)");
  }
  return {lower, upper};
}

namespace {

// The boxes around a scene's flat horizontal surfaces (grounds, seas) and around the rest of its
// meshes and terrain; `emitters` false leaves out the surfaces that emit light.
struct FlatAndRest {
  Eigen::AlignedBox3d planes, objects;  // empty boxes
};

FlatAndRest flat_and_rest(const RenderScene& scene, bool emitters) {
  const Scene& geometry = scene.geometry;
  FlatAndRest out;
  for (const SceneMesh& entry : geometry.meshes()) {
    if (geometry.removed(entry.geometry) || (!emitters && scene.light_of(entry.geometry) >= 0)) continue;
    Eigen::AlignedBox3d box;
    if (const TerrainGrid* terrain = geometry.terrain(entry.geometry)) {
      box.extend(terrain->lower()).extend(terrain->upper());
    }
    for (const Vec3d& vertex : entry.mesh.vertices) box.extend(vertex);
    if (box.isEmpty()) continue;
    (box.sizes().y() == 0.0 ? out.planes : out.objects).extend(box);
  }
  return out;
}

}  // namespace

std::pair<Vec3d, Vec3d> framing_bounds(const RenderScene& scene) {
  const FlatAndRest boxes = flat_and_rest(scene, true);
  const Eigen::AlignedBox3d& chosen = boxes.objects.isEmpty() ? boxes.planes : boxes.objects;
  if (chosen.isEmpty()) return scene_bounds(scene);  // its message for an empty scene
  return {chosen.min(), chosen.max()};
}

std::optional<std::pair<Vec3d, Vec3d>> ground_bounds(const RenderScene& scene) {
  const FlatAndRest boxes = flat_and_rest(scene, false);
  if (boxes.planes.isEmpty() || boxes.objects.contains(boxes.planes)) return std::nullopt;
  return std::make_pair(Vec3d(boxes.planes.min()), Vec3d(boxes.planes.max()));
}

std::optional<Hit> intersect_ray(const RenderScene& scene, const Vec3d& origin, const Vec3d& direction) {
  if (!(direction.cwiseAbs().maxCoeff() > 0.0)) throw_invalid("direction must be non-zero");
  return scene.geometry.intersect(origin, direction.stableNormalized(), kSceneReach);
}

std::optional<unsigned> dark_enclosure(const RenderScene& scene, const Vec3d& eye) {
  if (!is_finite(eye) || eye.cwiseAbs().maxCoeff() > kSceneReach) return std::nullopt;
  for (const LightPtr& light : scene.lights()) {
    if (!light->is_infinite() && light->type() != LightType::kDeltaDirection) return std::nullopt;
  }
  // kDirections rays spread evenly over the sphere (a Fibonacci lattice): a window, a door or a
  // hole lets light in wherever one of them passes, which six along the axes missed (a review: a
  // sunlit room with a 1 m window, called dark). Each ray is restarted just past each hit (at most
  // kMostCrossings: beyond, the eye is called enclosed by nothing), and the geometry it crosses an
  // odd number of times is what lies around the eye along it.
  constexpr int kDirections = 256;
  constexpr int kMostCrossings = 4096;  // a 5 km road crosses ~1 000 dash marks
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);  // azimuths turn by the golden angle
  std::set<unsigned> around;  // the opaque geometry every ray so far crossed an odd number of times
  for (int i = 0; i < kDirections; ++i) {
    const Vec3d d = sample_uniform_sphere(Vec2d((i + 0.5) / kDirections, std::fmod(i * golden, 1.0)));
    std::map<unsigned, int> crossings;
    Vec3d origin = eye;
    int k = 0;
    for (; k < kMostCrossings; ++k) {
      const auto hit = scene.geometry.intersect(origin, d, kSceneReach);
      if (!hit) break;
      ++crossings[hit->geometry];
      origin = hit->point + d * (1e-6 * (1.0 + hit->point.cwiseAbs().maxCoeff()));
    }
    if (k == kMostCrossings) return std::nullopt;
    std::set<unsigned> odd;
    for (const auto& [geometry, count] : crossings) {
      if (count % 2 == 1 && !scene.material(scene.geometry.material(geometry)).transmits()) odd.insert(geometry);
    }
    if (i > 0) {
      std::set<unsigned> both;
      std::set_intersection(around.begin(), around.end(), odd.begin(), odd.end(), std::inserter(both, both.begin()));
      odd = std::move(both);
    }
    if (odd.empty()) return std::nullopt;  // a way out along this ray
    around = std::move(odd);
  }
  return *around.begin();
}

std::optional<double> terrain_height(const RenderScene& scene, double x, double z) {
  if (!std::isfinite(x) || !std::isfinite(z)) throw_invalid("terrain_height: x and z must be finite (got ", x, ", ", z, ")");
  if (std::max(std::abs(x), std::abs(z)) > kSceneReach) return std::nullopt;
  const Scene& geometry = scene.geometry;
  bool any_terrain = false;  // render() asks for every scene: most hold none
  for (unsigned g = 0; g < geometry.geometry_count() && !any_terrain; ++g) {
    any_terrain = geometry.terrain(g) && !geometry.removed(g);
  }
  const Vec3d lower = geometry.lower(), upper = geometry.upper();
  if (!any_terrain || !(lower.array() <= upper.array()).all()) return std::nullopt;
  const Vec3d down(0.0, -1.0, 0.0);
  Vec3d origin(x, upper.y() + 1.0, z);
  double reach = upper.y() - lower.y() + 2.0;
  // Past every other surface on the way down (a roof, a bridge, the sea over a drowned valley):
  // each hit restarts the ray just beyond it, at most once per geometry and side.
  for (size_t k = 0; k <= 2 * geometry.geometry_count() + 2 && reach > 0.0; ++k) {
    const auto hit = geometry.intersect(origin, down, reach);
    if (!hit) return std::nullopt;
    if (geometry.terrain(hit->geometry) && hit->front_face) return hit->point.y();
    const double step = hit->t + 1e-6 * (1.0 + std::abs(hit->point.y()));
    origin.y() -= step, reach -= step;
  }
  return std::nullopt;
}

size_t add_point_light(RenderScene& scene, const Vec3d& position, const Color& intensity) {
  return scene.add_light(std::make_shared<PointLight>(position, intensity));
}

void set_sun(RenderScene& scene, const Vec3d& direction, const Color& radiance, const SunDisc& disc) {
  scene.set_sun(std::make_shared<SunLight>(direction, radiance, disc.angular_diameter, disc.limb_darkening));
}

void set_sky(RenderScene& scene, const std::optional<Vec3d>& horizon, const std::optional<Vec3d>& zenith,
             const std::optional<std::string>& environment, double scale) {
  if (environment && (horizon || zenith)) {
    throw_invalid("set_sky: give horizon and zenith, or environment, not both (the map is the whole sky)");
  }
  if (environment) return scene.set_sky(environment_from_file(*environment, scale));
  const Vec3d h = horizon.value_or(kDefaultSkyColour);
  scene.set_sky(gradient_sky(h, zenith.value_or(h), scale));
}

size_t add_spot_light(RenderScene& scene, const Vec3d& position, const Vec3d& direction, double angle,
                      const Color& intensity, double radius, std::optional<double> inner_angle) {
  // The emitter's disc, for soft shadows: a kilometre is far beyond any lamp, and keeps the disc's
  // points, where shadow rays start, within the scene (a trial's 1e300 m turned them to NaN).
  constexpr double kWidestSpot = 1e3;  // [m]
  if (!(radius >= 0.0 && radius <= kWidestSpot)) {
    throw_invalid("spot light radius must be in [0, ", kWidestSpot, "] m (got ", radius, ")");
  }
  if (inner_angle && !(*inner_angle > 0.0 && *inner_angle <= angle)) {
    throw_invalid("add_spot_light: inner_angle must be in (0, angle = ", angle, "] degrees (got ", *inner_angle, ")");
  }
  const size_t index =
      scene.add_light(std::make_shared<SpotLight>(position, direction, angle, intensity, inner_angle.value_or(-1.0)));
  if (radius > 0.0) scene.set_shadow_radius(index, radius);
  return scene.spots().size() - 1;
}

PhysicalSkySettings physical_sky_settings(const Vec3d& sun_direction, std::optional<double> aerosol, double ozone_du,
                                          double ground_albedo, double altitude, const std::string& below_horizon,
                                          const std::optional<double>& visibility) {
  return sky_settings(sun_direction, aerosol, ozone_du, ground_albedo, altitude, PhysicalSkySettings().rayleigh_scale,
                      below_horizon, visibility);
}

void set_physical_sky(RenderScene& scene, const PhysicalSkySettings& settings, const SunDisc& sun, double scale,
                      bool aerial_perspective, const SkyBuilder& build_sky) {
  const SkyAndSun lights = physical_sky_with_sun(settings, sun, scale, build_sky);
  scene.remove_infinite_lights();
  for (const LightPtr& light : {lights.sky, lights.sun}) {
    if (light) scene.add_light(light);
  }
  if (aerial_perspective && scale > 0.0) scene.enable_aerial_perspective();
}

std::vector<unsigned> add_sea(RenderScene& scene, std::shared_ptr<OceanWaves>& waves, const SeaLayout& layout,
                              MaterialPtr material) {
  std::shared_ptr<const Water> water = std::dynamic_pointer_cast<const Water>(material);
  if (!waves) {
    OceanWavesParameters p;
    p.wind_speed = water ? water->parameters().wind_speed : WaterParameters{}.wind_speed;
    if (!(p.wind_speed > 0.0)) {  // the waves' own check would name an OceanWaves the caller never made
      throw_invalid("add_sea: the Water material's wind_speed is ", p.wind_speed,
                    " m/s: calm water has no waves to add; lay it flat with add_ground(material=...) instead");
    }
    waves = std::make_shared<OceanWaves>(p);
  } else if (water && water->parameters().wind_speed != waves->parameters().wind_speed) {
    throw_invalid("add_sea: wind_speed of the waves (", waves->parameters().wind_speed,
                  " m/s) and of the Water material (", water->parameters().wind_speed, " m/s) must agree");
  }
  if (!material) {
    WaterParameters p;
    p.wind_speed = waves->parameters().wind_speed;
    water = std::make_shared<Water>(p);
    material = water;
  }
  if (water && water->parameters().resolved_slope_variance != 0.0) {
    throw_invalid("add_sea: the material's resolved_slope_variance must be 0 (add_sea sets it per band; got ",
                  water->parameters().resolved_slope_variance, ")");
  }
  const SeaMeshes meshes = sea_meshes(*waves, layout);
  std::vector<unsigned> ids;
  for (size_t b = 0; b < meshes.bands.size(); ++b) {
    if (meshes.bands[b].triangles.empty()) continue;
    MaterialPtr band_material = material;
    if (water) {  // the microfacets keep what the band's shading normals do not show
      WaterParameters p = water->parameters();
      p.resolved_slope_variance = meshes.band_slope_variance[b];
      const double most = water->mean_square_slope() - Water::kMinUnresolvedSlopeVariance;
      if (p.resolved_slope_variance > most) {
        throw_invalid("add_sea: the waves resolve a mean-square slope of ", p.resolved_slope_variance,
                      ", more than the Water's Cox-Munk total ", water->mean_square_slope(),
                      " allows: lower the waves' resolution or raise their patch_size");
      }
      band_material = std::make_shared<Water>(p);
    }
    ids.push_back(scene.geometry.add_mesh(meshes.bands[b], scene.add_material(band_material)));
  }
  ids.push_back(scene.geometry.add_mesh(meshes.flat, scene.add_material(material)));
  return ids;
}

}  // namespace refracta
