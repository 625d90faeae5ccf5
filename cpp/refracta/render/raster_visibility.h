// render_raster's lights and what occludes them. The lights come by role from the scene's typed
// accessors (RenderScene::sun(), spots()): no type switch here. The visibility is render_raster's
// side of the LightVisibility seam (light_visibility.h): the sun's and the spot lights' shadows
// from shadow maps (or the Embree reference), every other light through the ray renderers' own
// shadow rays, so that render_raster shades through the same DirectLighting as they do.
#pragma once

#include "refracta/core/image.h"
#include "refracta/raster/rasterizer.h"
#include "refracta/raster/shadow_map.h"
#include "refracta/render/light_visibility.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/render_scene.h"

#include <memory>
#include <optional>
#include <vector>

namespace refracta {

// The scene's lights by the part they play in render_raster, as indices in RenderScene::lights().
struct RasterLights {
  std::optional<size_t> sun;   // the scene's sun (its first SunLight), shining or not
  bool sun_shines = false;     // the sun is there and options.use_sun
  std::vector<size_t> spots;   // the chosen spot lights (options.spots, all by default), in that order
  std::vector<size_t> others;  // every other light: point, area, environment, sky
};

// The widest spot light [deg] a shadow map (one perspective view of its cone) covers.
constexpr double kWidestMappedSpot = 170.0;

// Throws std::invalid_argument when options.spots names a spot light the scene does not have, or
// with shadow maps when a chosen spot light is wider than kWidestMappedSpot.
RasterLights raster_lights(const RenderScene& scene, const RasterRenderOptions& options);

class RasterVisibility : public LightVisibility {
 public:
  // With options.shadows = map, builds the maps: the sun's (when it shines or its shadow is the
  // output) covering, seen from the sun, the visible points of `buffer` (seen from eye) within
  // shadow_distance, unless shadow_centre and shadow_half_size are given; and a perspective map
  // per chosen spot light covering its cone. `rays` (kept by reference) tests the other lights:
  // the ray renderers' straight shadow rays (a DirectLighting of its own).
  RasterVisibility(const RenderScene& scene, const RasterLights& lights, const RasterRenderOptions& options,
                   const VisibilityBuffer& buffer, const Vec3d& eye, const LightVisibility& rays,
                   WorkControl& control);

  // Whether the sun or a chosen spot light (its index in the scene), unshadowed, reaches the point
  // p whose geometric normal on the viewer's side is n: n faces the light and, for a spot, p lies
  // inside its cone.
  bool reaches(size_t light, const Vec3d& p, const Vec3d& n) const;
  // The shadow intensity in [0, 1] at p (normal n, the viewer's side) of the sun or a chosen spot
  // light: the map's, the Embree reference's (the sun: one ray along its direction; an area spot
  // light of radius > 0: 8 x 8 stratified rays to its disc), or 0 with shadows 'none'. extent: the
  // primitive's under p (Hit::extent), which the reference's rays clear (offset_point).
  double shadow(size_t light, const Vec3d& p, const Vec3d& n, const Vec3d& extent) const;

  // Light from behind the viewed side (si's geometric normal) does not arrive: render_raster
  // shades reflection only. The sun and the spot lights arrive dimmed by their shadow(); the
  // other lights through the shadow rays (shadows 'map' or 'embree') or unoccluded ('none').
  Spectrum arriving(size_t light, const SurfaceInteraction& si, const Vec3d& wi, const LightLiSample& ls,
                    const SampledWavelengths& lambda) const override;

  double build_seconds() const;  // [s] of every shadow map
  int bytes_per_texel() const;   // what the shadow method reads per texel (0 without maps)

 private:
  const RenderScene& scene_;
  ShadowSource source_;
  const LightVisibility& rays_;
  std::optional<size_t> sun_;                      // the scene's sun, shining or not
  Vec3d sun_direction_ = Vec3d::UnitY();           // unit, toward it
  std::vector<const SpotLight*> spot_;             // by light index: the chosen spot lights, else null
  std::vector<double> radius_;                     // by light index: a spot's disc radius [m]
  std::vector<std::unique_ptr<ShadowMap>> maps_;   // by light index: the sun's and the spots' maps
};

}  // namespace refracta
