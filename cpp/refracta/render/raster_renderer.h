// render_raster: rasterized view, shading once per pixel, the sun's shadow from a shadow map
// method (raster/shadow_map.h) or Embree rays (the reference). See raster_renderer.cpp.
#pragma once

#include "refracta/core/image.h"
#include "refracta/raster/oit.h"
#include "refracta/raster/shadow_map.h"
#include "refracta/render/render_scene.h"
#include "refracta/render/renderer.h"
#include "refracta/scene/camera.h"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// Where render_raster's shadows come from: shadow maps (shadow_map's method and settings), Embree
// shadow rays (the reference), or nowhere (every light unoccluded).
enum class ShadowSource { kMap, kEmbree, kNone };
ShadowSource parse_shadow_source(const std::string& name);  // "map", "embree", "none"
const char* shadow_source_name(ShadowSource source);

// What render_raster's pixels hold: linear RGB radiance, or (shadow intensity, 1, 0) where the
// light (shadow_light) reaches the surface and (0, 0, 0) elsewhere (what compare.shadows measures).
enum class RasterOutput { kRadiance, kShadow };
RasterOutput parse_raster_output(const std::string& name);  // "radiance", "shadow"
const char* raster_output_name(RasterOutput output);

// Options of refracta.render_raster, with their defaults (defined once, here). Set any field by
// name, nested ones through .shadow_map (ShadowMapOptions) and .transparency (OitSettings or None);
// validate() reports every bad value at once.
struct RasterRenderOptions {
  ShadowSource shadows = ShadowSource::kMap;
  ShadowMapOptions shadow_map;  // ShadowMapOptions of the sun's and the spot lights' maps (shadows 'map')
  // The region the sun's map covers, seen from the sun: its centre [m]; unset (None): fitted to the
  // visible points closer than shadow_distance to the camera.
  std::optional<Vec3d> shadow_centre;
  std::optional<double> shadow_half_size;  // half the side of the sun's map [m]; None: fitted to the visible points
  // [m] the sun's map covers the visible points closer than this to the camera
  double shadow_distance = std::numeric_limits<double>::infinity();
  RasterOutput output = RasterOutput::kRadiance;
  int shadow_light = -1;  // output shadow: -1 the sun, k >= 0 the scene's spot light k
  bool use_sun = true;  // the scene's sun shines
  // Indices of the spot lights that shine (spot k is the k-th spot light in the scene's order);
  // unset (None): all. Other lights (point, area, environment) shade with Embree shadow rays.
  std::optional<std::vector<int>> spots;
  // Surfaces with material alpha < 1 are composited over the opaque ones with this method
  // (fragments from the rasterizer, culled by the opaque depth); without it they are opaque.
  // MBOIT's log-depth range, when not set, is fitted to the frame's fragments. None: every surface
  // opaque.
  std::optional<OitSettings> transparency;
  int tile = 16;  // tile size [pixels] of the parallel loop
  // Samples (n^2, n = 1 .. 64) of each light with extent other than the spots (environment, sky,
  // area lights; the sun where its disc is wider than 1 deg or cut by a surface's horizon), and as
  // many of the BSDF (not of the sun), combined by MIS, deterministic per
  // pixel: the same n^2 quasi-random points everywhere, so their quadrature error is a bias, not
  // noise. Measured at n = 8 (16, 32): a panel 0.2 m over a floor -0.9 % (+1.2 %, +0.4 %) of its
  // form factor, an environment map with a small bright sun -0.3 % (-2.5 %, -1.2 %) of its
  // integral, a sphere lamp 7e-4; a lobe taking a share F of the samples (water's reflection,
  // F ~ 0.03) gets about F n^2 of them: raise it for glossy or dielectric surfaces under bright skies.
  int light_strata = 8;

  void check(Problems& problems) const;  // adds every bad field, the nested options' included
  void validate() const;                 // throws std::invalid_argument listing them all
};

// What render_raster measured (read-only).
struct RasterRenderStats {
  double seconds = 0.0;               // the whole render [s]
  double shadow_build_seconds = 0.0;  // rasterizing, filtering and storing the shadow maps [s]
  int bytes_per_texel = 0;            // what the shadow method reads per texel
  int64_t transparent_fragments = 0;  // transparent fragments in front of the opaque surfaces
  double oit_bytes_per_pixel = 0.0;   // what the transparency method keeps per pixel (mean)
};

Image render_raster(const RenderScene& scene, const Camera& camera, const RasterRenderOptions& options,
                    WorkControl& control, RasterRenderStats* stats = nullptr);

}  // namespace refracta
