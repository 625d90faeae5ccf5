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

// Adds a mesh with its material and, with emission (an illuminant), its area light, emitting from
// the counter-clockwise front or from both sides (two_sided without emission: ValueError). Returns
// the geometry id.
unsigned add_surface(RenderScene& scene, const Mesh& mesh, int material, const std::optional<Color>& emission,
                     bool two_sided, const char* what);

// Adds a sphere with its material and, with emission, its sphere light. Returns the geometry id.
unsigned add_sphere(RenderScene& scene, const Vec3d& centre, double radius, int material,
                    const std::optional<Color>& emission);

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
