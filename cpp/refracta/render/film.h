// The pixel-sample loop every ray-traced renderer shares, on the one tile loop (tile_loop.h):
// spp samples per pixel on a stratified jittered grid, a random generator seeded per pixel and
// sample (results depend neither on the thread count nor on options.pixel_bounds: a part of the
// image renders as in the whole), hero wavelengths per sample in spectral
// rendering, each sample's spectrum turned to linear sRGB (shading/color.h) and averaged.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/core/rng.h"
#include "refracta/core/scratch.h"
#include "refracta/core/spectrum.h"
#include "refracta/render/integrator.h"
#include "refracta/render/render_options.h"
#include "refracta/render/tile_loop.h"
#include "refracta/scene/camera.h"
#include "refracta/shading/color.h"

#include <tbb/enumerable_thread_specific.h>

#include <cmath>

namespace refracta {

// SampleRadiance: Spectrum(const Vec2d& pixel, const Vec2d& lens, double spacing, double pixel_angle,
// SampledWavelengths&, Sampler&, ScratchBuffer&): the sample's position (u, v) in pixel
// coordinates, its point on a thin lens in [0, 1)^2 (Camera::lens_ray; (0.5, 0.5), the lens centre,
// for a pinhole, which draws no number for it), the spacing of the samples [pixels] (1 / strata: a
// sample stands for a spacing x spacing square), and its cone's angle [rad] (0 without texture
// filtering).
template <class SampleRadiance>
Image render_film(const Camera& camera, const RenderOptions& options, WorkControl& control,
                  const SampleRadiance& radiance) {
  // Whole passes over a strata x strata grid, the samples left over uniform over the pixel: every
  // sample is then uniform over the pixel (a partly filled grid would leave strata unsampled).
  const int strata = std::max(1, int(std::floor(std::sqrt(double(options.spp)) + 1e-9)));
  const int stratified = options.spp / (strata * strata) * strata * strata;
  // Each sample's cone covers its share of the pixel.
  const double pixel_angle = options.texture_filter ? camera.pixel_angle() / strata : 0.0;
  const bool thin_lens = camera.aperture_diameter() > 0.0;
  tbb::enumerable_thread_specific<ScratchBuffer> scratch_per_thread;
  return render_tiles(options.bounds_in(camera.width(), camera.height()), options.tile, control, [&](int x, int y) {
    ScratchBuffer& scratch = scratch_per_thread.local();
    Sampler sampler{Rng(options.seed, uint64_t(y) * uint64_t(camera.width()) + uint64_t(x))};
    Vec3d sum = Vec3d::Zero();
    for (int s = 0; s < options.spp; ++s) {
      poll_cancel();  // a sample through turbulence can take milliseconds (the ray's steps poll too)
      double du = 0.5, dv = 0.5;
      if (options.spp > 1 && s < stratified) {  // stratified jitter over a strata x strata grid
        du = ((s % strata) + sampler.uniform()) / strata;
        dv = (((s / strata) % strata) + sampler.uniform()) / strata;
      } else if (options.spp > 1) {
        du = sampler.uniform();
        dv = sampler.uniform();
      }
      // The lens point: independent uniform numbers from the pixel's own generator (so thread
      // count and tiles change nothing), drawn only by a thin lens (pinhole renders unchanged).
      Vec2d lens(0.5, 0.5);
      if (thin_lens) lens = Vec2d(sampler.uniform(), sampler.uniform());
      SampledWavelengths lambda =
          options.spectral ? SampledWavelengths::sample_uniform(sampler.uniform()) : SampledWavelengths::rgb();
      const Spectrum L = radiance(Vec2d(x + du, y + dv), lens, 1.0 / strata, pixel_angle, lambda, sampler, scratch);
      const Vec3d rgb = to_linear_srgb(L, lambda);
      if (is_finite(rgb)) sum += rgb;  // a non-finite sample is dropped (the renderer counts them)
    }
    return Vec3d(sum / options.spp);
  });
}

}  // namespace refracta
