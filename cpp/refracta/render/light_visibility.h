// How much of a light sample reaches a point: the seam between the light evaluation every
// renderer shares (DirectLighting, direct_lighting.h) and the way each renderer finds what is in
// the way -- pbrt-v4's Integrator::Unoccluded, widened to return the radiance that arrives.
//   - the ray renderers: a shadow ray through the caster, curved toward distant lights (which are
//     then seen along the path's exit direction) and straight to finite ones (DirectLighting's
//     own implementation);
//   - render_raster: a shadow map lookup for the sun and the spot lights, Embree rays for the
//     rest, or no occlusion at all (RasterVisibility, raster_visibility.h).
#pragma once

#include "refracta/core/spectrum.h"
#include "refracta/scene/surface_interaction.h"
#include "refracta/shading/light.h"

#include <cstddef>

namespace refracta {

class LightVisibility {
 public:
  virtual ~LightVisibility() = default;
  // The radiance of sample `ls` of the scene's light `light` (its index in RenderScene::lights())
  // that arrives at si along the unit direction wi (the sample's own wi, or the launch direction
  // of a curved shadow ray): ls.L unoccluded, zero when blocked, ls.L times the visible fraction
  // for a filtered shadow map, or what the curved path meets where it leaves the air.
  virtual Spectrum arriving(size_t light, const SurfaceInteraction& si, const Vec3d& wi, const LightLiSample& ls,
                            const SampledWavelengths& lambda) const = 0;
};

}  // namespace refracta
