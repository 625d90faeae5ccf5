// Rendering a scene through an atmosphere: 'straight' (ray casting, no refraction: the
// reference) and 'curved' (exact: the integrator's path cut into chords tested against the
// Embree scene, the hit refined on the continuous path, shading at the true hit).
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/parallel.h"
#include "refracta/core/rng.h"
#include "refracta/media/index_field.h"
#include "refracta/rays/ray_node.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/camera.h"
#include "refracta/scene/embree_scene.h"
#include "refracta/shading/lights.h"

#include <functional>
#include <optional>

namespace refracta {

// Where a camera ray ends: a surface hit (with the direction the light path arrives from) or
// the sky seen along `direction`.
struct PathEnd {
  std::optional<Hit> hit;
  Vec3d direction;  // unit, along the path at its end (toward the hit or the sky)
  double length = 0.0;
  int64_t chords = 0;  // straight chords tested against the scene on the way
};

// What a render did, summed over its samples.
struct RenderStats {
  int64_t samples = 0;
  int64_t chords = 0;  // Embree queries along curved paths (straight rays count one each)
};

// Tests the path segment a -> b against the scene in chords (at most options.chord long, within
// options.sagitta of the path); on a hit fills `end` and returns true.
bool hit_on_segment(const Scene& scene, const RayNode<double>& a, const RayNode<double>& b,
                    const RenderOptions& options, PathEnd* end);

// The end of the (curved, if field is given) path from origin along dir.
PathEnd follow_path(const Scene& scene, const IndexField* field, const Vec3d& origin, const Vec3d& dir,
                    const RenderOptions& options);

// The fraction of the sun a hit does not see along wi (0: lit, 1: in shadow).
using SunShadow = std::function<double(const Hit& hit, const Vec3d& wi)>;
// The reference: an Embree shadow ray (hard: 0 or 1).
double sun_occlusion(const Scene& scene, const Hit& hit, const Vec3d& wi);
// The fraction of spot light `index` a hit does not see.
using SpotShadow = std::function<double(const Hit& hit, size_t index)>;
// The reference: a shadow ray to the point light, or for an area light (radius > 0) 64 shadow
// rays to stratified points of its disc (soft shadows).
double spot_occlusion(const Scene& scene, const Hit& hit, const SpotLight& light);

// Radiance leaving the path's end toward the eye: Blinn-Phong at a hit with sky light and the sun
// (shadowed by sun_shadow, default Embree shadow rays; the sun's disc sampled when jitter), or the
// sky. Textures are filtered over the cone of angle pixel_angle [rad] (0: point sampled).
Vec3d shade(const Scene& scene, const Lighting& lighting, const PathEnd& end, Rng& rng, bool jitter,
            double pixel_angle, const SunShadow* sun_shadow = nullptr, const SpotShadow* spot_shadow = nullptr);

// The original editor's method (raster_march.cpp): rasterize, then march each pixel's curved
// ray against the depth buffer.
Image render_raster_march(const Scene& scene, const Lighting& lighting, const Camera& camera, const FieldPtr& field,
                          const RenderOptions& options, WorkControl& control, RenderStats* stats);

// Linear RGB radiance image (height, width, 3). field may be null (then 'curved' = 'straight').
Image render(const Scene& scene, const Lighting& lighting, const Camera& camera, const FieldPtr& field,
             const RenderOptions& options, WorkControl& control, RenderStats* stats = nullptr);

}  // namespace refracta
