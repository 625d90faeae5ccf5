// Rendering a scene through an atmosphere: 'straight' (ray casting, no refraction: the
// reference), 'curved' (exact: every segment through the curved caster) and 'raster_march' (the
// original editor's method). All three share the film loop (film.h) and the integrators
// (integrator.h): they differ in how a camera ray finds what it sees.
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/parallel.h"
#include "refracta/media/index_field.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/camera.h"

namespace refracta {

// What refracta.render counted, summed over its samples (read-only; tiles add up with +).
struct RenderStats {
  int64_t samples = 0;          // camera samples traced
  int64_t chords = 0;           // Embree queries along camera paths (straight rays count one each)
  int64_t invalid_samples = 0;  // samples whose radiance was not finite (dropped; should stay 0)
};
// The counts of two renders (tiles of one image) added.
RenderStats operator+(const RenderStats& a, const RenderStats& b);

// Linear RGB radiance image (height, width, 3); with options.surface_aovs (height, width, 9):
// radiance, then the albedo and the normal of the first non-specular hit (integrator.h
// SurfaceAovs); with options.readouts (height, width, 19): those and the readouts (readouts.h);
// with options.sample_counts one channel more, the last: each pixel's number of samples.
// field may be null (then 'curved' = 'straight'). Refuses (ValueError) bad options and, before
// anything is allocated, an image that would not fit in memory (core/image.h).
Image render(const RenderScene& scene, const Camera& camera, const FieldPtr& field, const RenderOptions& options,
             WorkControl& control, RenderStats* stats = nullptr);

// The original editor's method (raster_march.cpp): rasterize, then march each pixel's curved
// ray against the depth buffer; raster pixels are shaded by the same integrator.
Image render_raster_march(const RenderScene& scene, const Camera& camera, const FieldPtr& field,
                          const RenderOptions& options, WorkControl& control, RenderStats* stats);

}  // namespace refracta
