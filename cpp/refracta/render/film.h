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
#include "refracta/render/readouts.h"
#include "refracta/render/render_options.h"
#include "refracta/render/tile_loop.h"
#include "refracta/scene/camera.h"
#include "refracta/shading/color.h"

#include <tbb/enumerable_thread_specific.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace refracta {

namespace detail {

// Element i of a pseudo-random permutation of [0, n) chosen by `seed` (Kensler 2013, "Correlated
// Multi-Jittered Sampling", Pixar Technical Memo 13-01, permute(): an invertible hash of the bits
// below n's highest, cycle-walked into [0, n)); as pbrt-v4's PermutationElement.
inline uint32_t permutation_element(uint32_t i, uint32_t n, uint32_t seed) {
  uint32_t w = n - 1;
  w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
  do {
    i ^= seed;
    i *= 0xe170893d;
    i ^= seed >> 16;
    i ^= (i & w) >> 4;
    i ^= seed >> 8;
    i *= 0x0929eb3f;
    i ^= seed >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | seed >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + seed) % n;
}

}  // namespace detail

// SampleRadiance: Spectrum(const Vec2d& pixel, const Vec2d& lens, double spacing, double pixel_angle,
// SampledWavelengths&, Sampler&, ScratchBuffer&, SurfaceAovs*): the sample's position (u, v) in pixel
// coordinates, its point on a thin lens in [0, 1)^2 (Camera::lens_ray; (0.5, 0.5), the lens centre,
// for a pinhole, which draws no number for it), the spacing of the samples [pixels] (1 / strata: a
// sample stands for a spacing x spacing square), and its cone's angle [rad] (0 without texture
// filtering), and where to put the sample's surface AOVs (null without). kRadiance: 3 channels;
// kSurface: 9, the radiance then the mean albedo and normal of the pixel's samples; kReadouts:
// those 9 and the kReadoutChannels of readouts.h -- of the nearest hit among the pixel's samples
// (the first sample of the least path length: never a blend of a foreground and a background)
// its distance, position and object id, and through `geometry` its true elevation and hidden
// heights; the apparent elevation and azimuth of the mean of the samples' directions at the eye.
enum class FilmLayout { kRadiance, kSurface, kReadouts };

template <FilmLayout kLayout, class SampleRadiance>
Image render_film(const Camera& camera, const RenderOptions& options, WorkControl& control,
                  const SampleRadiance& radiance, const ReadoutGeometry* geometry = nullptr) {
  constexpr bool kSurfaceAovs = kLayout != FilmLayout::kRadiance;
  constexpr bool kReadouts = kLayout == FilmLayout::kReadouts;
  constexpr int kChannels = kReadouts ? kSurfaceChannels + kReadoutChannels : kSurfaceAovs ? kSurfaceChannels : 3;
  using PixelValue = Eigen::Matrix<double, kChannels, 1>;
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
    PixelValue value = PixelValue::Zero();
    Vec3d directions = Vec3d::Zero();  // readouts: the sum of the samples' directions at the eye
    SurfaceAovs nearest;               // readouts: the sample whose hit is nearest (no hit: none)
    uint32_t pass_seed = 0;  // the lens cells' shuffle of the current pass over the grid
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
      // The lens point, drawn only by a thin lens (pinhole renders unchanged) from the pixel's own
      // generator (so thread count and tiles change nothing): stratified over the same
      // strata x strata grid as the pixel, the cells shuffled per pass (pbrt-v4's
      // StratifiedSampler: each dimension stratified, their pairing random), else uniform.
      Vec2d lens(0.5, 0.5);
      if (thin_lens && s < stratified) {
        const int cells = strata * strata, k = s % cells;
        if (k == 0) pass_seed = uint32_t(sampler.uniform() * 4294967296.0);
        const int cell = int(detail::permutation_element(uint32_t(k), uint32_t(cells), pass_seed));
        const int column = cell % strata, row = cell / strata;  // the stratum's place in the strata x strata grid
        lens = Vec2d((column + sampler.uniform()) / strata, (row + sampler.uniform()) / strata);
      } else if (thin_lens) {
        lens = Vec2d(sampler.uniform(), sampler.uniform());
      }
      SampledWavelengths lambda =
          options.spectral ? SampledWavelengths::sample_uniform(sampler.uniform()) : SampledWavelengths::rgb();
      SurfaceAovs aovs;
      const Spectrum L = radiance(Vec2d(x + du, y + dv), lens, 1.0 / strata, pixel_angle, lambda, sampler, scratch,
                                  kSurfaceAovs ? &aovs : nullptr);
      const Vec3d rgb = to_linear_srgb(L, lambda);
      if (is_finite(rgb)) sum += rgb;  // a non-finite sample is dropped (the renderer counts them)
      if constexpr (kSurfaceAovs) {
        value.template segment<3>(3) += aovs.albedo;
        value.template segment<3>(6) += aovs.normal;
      }
      if constexpr (kReadouts) {
        directions += aovs.eye_direction;
        if (aovs.hit && (!nearest.hit || aovs.distance < nearest.distance)) nearest = aovs;
      }
    }
    value.template head<3>() = sum;
    value /= options.spp;
    if constexpr (kReadouts) {
      auto out = value.template tail<kReadoutChannels>();
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const Vec3d position = nearest.hit ? nearest.hit->point : Vec3d::Constant(nan);
      out[kReadoutDistance] = nearest.hit ? nearest.distance : std::numeric_limits<double>::infinity();
      out.template segment<3>(kReadoutPosition) = position;
      out[kReadoutObject] = nearest.hit ? double(nearest.hit->geometry) : -1.0;
      out.template segment<2>(kReadoutApparentElevation) = apparent_angles(directions);
      out[kReadoutTrueElevation] = geometry->true_elevation(position);
      out[kReadoutHiddenHeight] = geometry->hidden_geometric(position);
      out[kReadoutHiddenHeight + 1] = geometry->hidden_refracted(position);
    }
    return value;
  });
}

}  // namespace refracta
