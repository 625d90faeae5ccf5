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
// A light reflects by its material too (as pbrt-v4's area lights do; Mitsuba 3's emitters are
// black unless given a BSDF): material=Diffuse(0.0) for a black lamp. Returns its id.
unsigned add_mesh(RenderScene& scene, Mesh mesh, const SurfaceLook& look);

// Add an axis-aligned box (faces outward): centre (3,) and size (3,) [m]. Without `material`, the
// kd/ks/ns/alpha shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1),
// alpha (default 1; < 1: transparent in render_raster)).
unsigned add_box(RenderScene& scene, const Vec3d& centre, const Vec3d& size, const SurfaceLook& look);

// Add a sphere (exact, not tessellated); emission makes it a spherical light (reflecting by its
// material too, as add_mesh's). Without `material`, the kd/ks/ns shorthand: BlinnPhong(kd (default
// 0.5 grey), ks (default 0), ns (default 1)). Its shading tangent (an anisotropic material's u,
// e.g. RoughConductor's alpha_u) runs around the +y axis, along the lines of latitude.
unsigned add_sphere(RenderScene& scene, const Vec3d& centre, double radius, const SurfaceLook& look);

// Add a square ground of side `size` [m] at y = height, centred on the origin, facing up. Without
// `material`, the kd/ks/ns shorthand (BlinnPhong; kd default 0.3 grey) and a texture multiplying
// kd; a texture (or a textured material's) repeats every texture_size [m] (u along +x, v along -z;
// None: 1 m).
unsigned add_ground(RenderScene& scene, double height, double size, const SurfaceLook& look,
                    std::optional<double> texture_size);

// Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at
// `centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the
// -x side), upright; kd (default 1: the picture's own colours) multiplies the texture. Where the
// picture has alpha (an RGBA or grey-alpha image) it is a cut-out: rays and shadows pass through
// its clear parts (a ray meets a point of alpha a with probability a; render_raster draws where
// a >= 1/2).
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

// The box around the scene's ground or sea, for render()'s "camera at or below the ground" hint:
// its flat horizontal surfaces when they reach outside the other geometry's box or are all it
// holds; nullopt for a scene of objects alone (a floor inside a room's walls is the room's). A
// surface that emits light is no ground: a lone light panel overhead is not a floor.
std::optional<std::pair<Vec3d, Vec3d>> ground_bounds(const RenderScene& scene);

// The first hit of a straight ray from origin along a non-zero direction (normalised here).
std::optional<Hit> intersect_ray(const RenderScene& scene, const Vec3d& origin, const Vec3d& direction);

// The height [m] of the highest terrain surface (Scene.add_terrain's grids, seen from above)
// over (x, z), or nullopt where no terrain lies there; other geometry above it is looked through.
// Where an eye stands on the terrain: Camera positions, and render()'s "camera below the ground" hint.
std::optional<double> terrain_height(const RenderScene& scene, double x, double z);

// The geometry that keeps every light from `eye`, if one does: every light of the scene is at
// infinity (sun, sky, environment) and one opaque geometry lies around the eye (256 rays spread
// over the sphere each cross it an odd number of times; a material that transmits, water or glass,
// is seen through, and a ray through an opening finds none). No surface in view is then lit:
// render()'s "camera inside an object" hint (a trial's eye 1 mm up inside the hot road's 2 mm road
// slab). A room lit from within, or a furnace whose walls glow, has a light that is not at
// infinity, and is no mistake; an opening narrower than the rays' spacing (~0.2 rad) can be missed.
std::optional<unsigned> dark_enclosure(const RenderScene& scene, const Vec3d& eye);

// Add a point light at `position` [m] of `intensity` [W/sr, RGB] (irradiance I cos / d^2). Returns
// its index.
size_t add_point_light(RenderScene& scene, const Vec3d& position, const Color& intensity);

// Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg]
// (in (0, 360]) with `intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 gives
// render_raster's 'embree' reference soft shadows of a disc that size. inner_angle [deg] in
// (0, angle]: a smooth falloff from it to angle (lights.SpotLight's, pbrt-v4's smoothstep); none: a
// hard edge. Returns its index among the spot lights.
size_t add_spot_light(RenderScene& scene, const Vec3d& position, const Vec3d& direction, double angle,
                      const Color& intensity, double radius, std::optional<double> inner_angle = std::nullopt);

// The sun (replacing any): direction toward it, disc radiance [W/(m^2 sr), RGB], angular diameter
// [deg], limb darkening u (I(mu) = 1 - u (1 - mu)). Seen through the air along curved rays.
// With wavelengths (M,) [nm, increasing], radiance is a spectrum (M,) [W/(m^2 sr nm)] instead (e.g.
// refracta.spectrum.PhysicalSky(...).sun_radiance(wavelengths): the sun through the air's extinction).
void set_sun(RenderScene& scene, const Vec3d& direction, const Color& radiance, const SunDisc& disc);

// A sky (replacing any environment): radiance toward the horizon (and below) and straight up,
// linear in the sine of the elevation (zenith default: the horizon's, a constant sky), or an
// equirectangular environment map file (refracta.lights.EnvironmentLight's orientation), times
// `scale`.
void set_sky(RenderScene& scene, const std::optional<Vec3d>& horizon, const std::optional<Vec3d>& zenith,
             const std::optional<std::string>& environment, double scale);

// Scene.set_physical_sky's keywords as settings: the sun direction non-zero (normalised here),
// below_horizon 'horizon' or 'ground', visibility [km] (when given) setting the aerosol.
PhysicalSkySettings physical_sky_settings(const Vec3d& sun_direction, std::optional<double> aerosol, double ozone_du,
                                          double ground_albedo, double altitude, const std::string& below_horizon,
                                          const std::optional<double>& visibility);

// The physical sky (replacing every environment, sky and sun): refracta.spectrum.PhysicalSky's
// single scattering (Nishita et al. 1993) plus Hillaire 2020's multiple scattering, for the sun
// toward `sun_direction` (normalised, y up), `aerosol` (Mie density scale; None: 1, a clear sky),
// `ozone_du` [Dobson units, at most 10 000; the Earth's column is 100-600], observer `altitude` [m]. Below the horizon `below_horizon`: 'horizon'
// (default) continues the sky from the horizon at each azimuth (Scene.set_sky's convention: the
// ground is geometry, and a ray ending its max_length still heading slightly down sees the horizon
// sky, importance-sampled over the whole sphere); 'ground' shows the Lambertian ground of
// `ground_albedo` (which must be 0 with 'horizon'). And the sun: a disc of `sun_angular_diameter`
// [deg] with linear limb darkening u, its radiance the 5778 K solar spectrum through the
// atmosphere's extinction (reddened toward the horizon; within the horizon's refraction, 33', below
// the planet's limb the grazing column's, as the render's curved rays still reach it; none further
// below). Units: spectral radiance
// W/(m^2 sr nm) in spectral renders, its CIE-Y-weighted mean in RGB (linear sRGB of XYZ / integral
// ybar, as Color.illuminant: times 106.86 nm gives W/(m^2 sr)); RGB and spectral renders agree.
// `scale` multiplies sky and sun (e.g. an exposure). Builds the sky's table (1-3 s; `build_sky`).
// aerial_perspective (default True): the same air dims and lights every segment the renderers cast
// (refracta.spectrum.AerialPerspective: transmittance and scattered sunlight, the sky's multiple
// scattering included), so distant objects grey and blue into the sky; False keeps surfaces as
// seen through empty space. visibility [km, at least 0.001]: meteorological visibility at the
// ground (Koschmieder: extinction at 550 nm = 3.912 / V), setting the aerosol in its place (give
// one of them; an aerosol thicker than 1 m of visibility is refused too). The
// scene's y = 0 lies `altitude` above the sky's sea level.
void set_physical_sky(RenderScene& scene, const PhysicalSkySettings& settings, const SunDisc& sun, double scale,
                      bool aerial_perspective, const SkyBuilder& build_sky);

// Add a sea at y = height with waves near `centre` (x, z) [m] (put it under the camera).
//
// Within detail_radius [m] of centre: the waves (an OceanWaves; default OceanWaves(wind_speed=the
// material's), whose 100 m patch holds a fully developed sea up to ~12 m/s: above, pass
// OceanWaves(wind_speed, patch_size=10 U^2/g), which warns when too small) tiled on a mesh of
// their nodes with shading normals from their slopes; over the outer 30 % of the radius they blend
// into a coarse level, the same sea at a quarter of the resolution (exactly its longer waves) on
// nodes 4 cells apart, which reaches 4 detail_radius and fades to flat over its outer 30 %; beyond,
// a flat square of side `size` [m] centred on the origin (as add_ground). The levels meet without a
// crack. (Waves with resolution < 32 have no coarse level.)
//
// material: default shading.Water(wind_speed=waves.wind_speed). With a Water (its wind_speed must
// equal the waves'), every displaced band (per level the full waves, then 3 fade rings) gets a copy
// with resolved_slope_variance set to the mean-square slope its mesh's normals show, so that
// resolved + microfacet = Cox & Munk's total and the statistical roughness grows with distance as the
// resolved slopes fall; the flat plane keeps the full Water. Any other material is used as given
// everywhere.
//
// Returns the geometry ids: the displaced meshes (fine full waves, its fade rings, coarse full waves,
// its fade rings; empty ones left out), then the flat plane. A null `waves` is set to the default
// sea it made (whose patch_caveat the binding warns with).
std::vector<unsigned> add_sea(RenderScene& scene, std::shared_ptr<OceanWaves>& waves, const SeaLayout& layout,
                              MaterialPtr material);

}  // namespace refracta
