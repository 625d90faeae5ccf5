// Building a RenderScene from the parts the Python API gives: each Scene.add_* / set_* with its
// validation (ValueError naming the argument), so that bindings/bind_scene*.cpp, bind_ocean.cpp and
// bind_terrain.cpp only convert arguments.
#pragma once

#include "refracta/render/obj_materials.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/ocean_waves.h"
#include "refracta/shading/color.h"
#include "refracta/shading/physical_sky.h"
#include "refracta/shading/sky_presets.h"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace refracta {

// add_ground's texture repeat [m] when none is given.
constexpr double kGroundTextureSize = 1.0;

// A geometry id given by a caller: negative ids name nothing (ValueError).
unsigned geometry_id(int geometry);

// Refuses a textured material on geometry without texture coordinates, saying how (what: the function).
void check_uvs(const RenderScene& scene, int material, bool has_uvs, const char* what);

// Normalises a mesh's shading normals (given) in place: one per vertex, each non-zero (ValueError otherwise).
void normalise_normals(Mesh& mesh);

// add_obj's missing_textures: 'error' or 'warn'.
MissingTextures missing_textures_from(const std::string& name);

// The look an add_* call gives its geometry: `material` (any refracta.shading material), or else
// the Blinn-Phong shorthand of the MTL files and the early API -- BlinnPhong(kd (the call's default
// grey), ks (default 0), ns (default 1), alpha (default 1; < 1: transparent in render_raster)), an
// image file `texture` multiplying kd. `material` with any of the shorthand is refused (it would be
// ignored). `emission` [W/(m^2 sr), RGB] makes the geometry an area or sphere light, one-sided on
// the triangles' counter-clockwise front unless `two_sided`.
struct SurfaceLook {
  MaterialPtr material;
  std::optional<Vec3d> kd, ks;
  std::optional<double> ns, alpha;
  std::optional<std::string> texture;
  std::optional<Color> emission;
  bool two_sided = false;
};

// add_ground's default kd: a darker grey than objects' (BlinnPhong::kDefaultKd).
constexpr double kGroundKd = 0.3;

// Add a triangle mesh: vertices (N, 3) [m], triangles (M, 3) indices (front: counter-clockwise);
// optional per-vertex normals (N, 3) (shading normals, interpolated; any length but 0) and uvs
// (N, 2) texture coordinates (u right, v up); emission makes it an area light. Without `material`,
// the kd/ks/ns/alpha shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1),
// alpha (default 1; < 1: transparent in render_raster)). A texture (an image file) multiplies kd.
// Returns its id.
unsigned add_mesh(RenderScene& scene, Mesh mesh, const SurfaceLook& look);

// Add an axis-aligned box (faces outward): centre (3,) and size (3,) [m]. Without `material`, the
// kd/ks/ns/alpha shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1),
// alpha (default 1; < 1: transparent in render_raster)).
unsigned add_box(RenderScene& scene, const Vec3d& centre, const Vec3d& size, const SurfaceLook& look);

// Add a sphere (exact, not tessellated); emission makes it a spherical light. Without `material`,
// the kd/ks/ns shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1)).
unsigned add_sphere(RenderScene& scene, const Vec3d& centre, double radius, const SurfaceLook& look);

// Add a square ground of side `size` [m] at y = height, centred on the origin, facing up. Without
// `material`, the kd/ks/ns shorthand (BlinnPhong; kd default 0.3 grey) and a texture multiplying
// kd; a texture (or a textured material's) repeats every texture_size [m] (u along +x, v along -z;
// None: 1 m).
unsigned add_ground(RenderScene& scene, double height, double size, const SurfaceLook& look,
                    std::optional<double> texture_size);

// Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at
// `centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the
// -x side), upright; kd (default 1: the picture's own colours) multiplies the texture.
unsigned add_billboard(RenderScene& scene, const Vec3d& centre, double width, double height,
                       const std::string& texture, const Vec3d& facing, const std::optional<Vec3d>& kd);

// Gives a geometry another material (its emission stays); a textured one needs the geometry's uvs.
void set_geometry_material(RenderScene& scene, int geometry, const MaterialPtr& material);

// The corners (lower, upper) of the box around every geometry (ValueError for an empty scene).
std::pair<Vec3d, Vec3d> scene_bounds(const RenderScene& scene);

// The box Camera.framing shows: around every geometry but flat horizontal ones (grounds, water
// planes: a 20 km ground would frame the plane, not the scene on it), which count only when the
// scene has nothing else (ValueError for an empty scene).
std::pair<Vec3d, Vec3d> framing_bounds(const RenderScene& scene);

// The first hit of a straight ray from origin along a non-zero direction (normalised here).
std::optional<Hit> intersect_ray(const RenderScene& scene, const Vec3d& origin, const Vec3d& direction);

// The height [m] of the highest terrain surface (Scene.add_terrain's grids, seen from above)
// over (x, z), or nullopt where no terrain lies there; other geometry above it is looked through.
// Where an eye stands on the terrain: Camera positions, and render()'s "camera below the ground" hint.
std::optional<double> terrain_height(const RenderScene& scene, double x, double z);

// Adds a spot light (angle in (0, 360] deg, SpotLight; shadow disc radius >= 0: render_raster's 'embree'
// reference soft shadows when > 0). Returns its index among the spot lights.
size_t add_spot_light(RenderScene& scene, const Vec3d& position, const Vec3d& direction, double angle,
                      const Color& intensity, double radius);

// Scene.set_physical_sky's keywords as settings: the sun direction non-zero (normalised here),
// below_horizon 'horizon' or 'ground', visibility [km] (when given) setting the aerosol.
PhysicalSkySettings physical_sky_settings(const Vec3d& sun_direction, std::optional<double> aerosol, double ozone_du,
                                          double ground_albedo, double altitude, const std::string& below_horizon,
                                          const std::optional<double>& visibility);

// The physical sky and its sun (replacing every environment, sky and sun), and, with
// aerial_perspective and scale > 0, the same air's aerial perspective. build_sky builds the table.
void set_physical_sky(RenderScene& scene, const PhysicalSkySettings& settings, const SunDisc& sun, double scale,
                      bool aerial_perspective, const SkyBuilder& build_sky);

// Scene.add_sea: the sea's meshes (sea_meshes) with their materials. waves null: OceanWaves of the
// Water material's wind speed; material null: Water of the waves' wind speed. With a Water (its
// wind speed must be the waves'; its resolved_slope_variance 0), each displaced band gets a copy
// whose resolved_slope_variance is what the band's normals show. Returns the geometry ids (empty
// bands left out), the flat plane last.
std::vector<unsigned> add_sea(RenderScene& scene, std::shared_ptr<OceanWaves> waves, const SeaLayout& layout,
                              MaterialPtr material);

}  // namespace refracta
