// Light transport behind one interface: the radiance arriving along a camera ray (pbrt-v4's
// RayIntegrator). 'direct' and 'path' (render_options.h) implement it; the one film loop
// (film.h) calls it for every pixel sample of every renderer. Every segment -- camera ray,
// bounce, shadow ray toward a distant light -- is cast through the same Caster.
#pragma once

#include "refracta/core/rng.h"
#include "refracta/core/scratch.h"
#include "refracta/core/spectrum.h"
#include "refracta/render/caster.h"
#include "refracta/render/direct_lighting.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"

#include <memory>
#include <optional>

namespace refracta {

// What a camera sample's path met first that was not a perfect mirror or glass: the surface's
// directional albedo toward the path (its reflectance and transmittance, linear sRGB, in [0, 1])
// and its shading normal facing the path (world space); zero where the path met none. The
// auxiliary features Intel Open Image Denoise takes beside the noisy image (its documentation:
// albedo and normal of the first diffuse or glossy hit, following delta bounces).
// With RenderOptions::readouts the renderer also records the camera ray itself (readouts.h): its
// direction at the eye and its first hit, whatever the surface (the integrator leaves these).
struct SurfaceAovs {
  Vec3d albedo = Vec3d::Zero(), normal = Vec3d::Zero();
  Vec3d eye_direction = Vec3d::Zero();  // unit camera ray direction at the eye
  std::optional<Hit> hit;               // the camera path's first hit (none: it saw the sky)
  double distance = 0.0;                // the camera path's length to that hit [m]
};

class Integrator {
 public:
  Integrator(const RenderScene& scene, const Caster& caster, const RenderOptions& options)
      : scene_(scene),
        caster_(caster),
        options_(options),
        lighting_(scene, caster, options),
        air_(scene.aerial_perspective()),
        air_frame_(caster.air_frame()) {}
  virtual ~Integrator() = default;

  // Radiance [W/(m^2 sr)] (RGB or at lambda) arriving at `origin` along the ray leaving it in unit
  // direction `dir`; pixel_angle [rad] widens texture footprints with path length.
  Spectrum li(const Vec3d& origin, const Vec3d& dir, double pixel_angle, SampledWavelengths& lambda, Sampler& sampler,
              ScratchBuffer& scratch) const {
    return li_after(origin, dir, caster_.cast(origin, dir), pixel_angle, lambda, sampler, scratch, nullptr);
  }
  // The same, with the camera ray's end already found (raster_march finds it by marching); fills
  // `aovs` when given (without drawing from the sampler: the radiance is the same either way).
  virtual Spectrum li_after(const Vec3d& origin, const Vec3d& dir, const PathEnd& first, double pixel_angle,
                            SampledWavelengths& lambda, Sampler& sampler, ScratchBuffer& scratch,
                            SurfaceAovs* aovs) const = 0;
  // Only the albedo and normal li_after would record into `aovs`: the camera path followed through
  // mirrors and glass (choosing between reflection and transmission with `sampler`) to its first
  // non-specular surface, no light gathered (the denoiser's guide pass, RenderOptions::guide_spp).
  virtual void surface_after(const Vec3d& origin, const Vec3d& dir, const PathEnd& first, double pixel_angle,
                             SampledWavelengths& lambda, Sampler& sampler, ScratchBuffer& scratch,
                             SurfaceAovs& aovs) const = 0;
  const DirectLighting& lighting() const { return lighting_; }
  DirectLighting& lighting() { return lighting_; }

 protected:
  const RenderScene& scene_;
  const Caster& caster_;
  const RenderOptions& options_;
  DirectLighting lighting_;
  const AerialPerspective* air_;  // null without aerial perspective
  AirFrame air_frame_;
};

std::unique_ptr<Integrator> make_integrator(const RenderScene& scene, const Caster& caster, const RenderOptions& options);

}  // namespace refracta
