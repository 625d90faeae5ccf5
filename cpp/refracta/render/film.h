// The pixel-sample loop every ray-traced renderer shares, on the one tile loop (tile_loop.h):
// spp samples per pixel from a correlated multi-jittered pattern (Kensler 2013: each of the
// spp columns and spp rows of the pixel holds one sample, and the samples fill the cells of an
// m x n grid, m n = spp), or with options.adaptive as many as a pilot pass says the pixel needs
// at the same total (adaptive_sampling.h), or with options.edge_spp the pixels at edges between
// surfaces again with edge_spp samples (EdgeRefinement); a random generator seeded per pixel and pass
// (results depend neither on the thread count nor on options.pixel_bounds: a part of the image
// renders as in the whole), hero wavelengths per sample in spectral rendering, each sample's
// spectrum turned to linear sRGB (shading/color.h) and averaged.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/core/rng.h"
#include "refracta/core/scratch.h"
#include "refracta/core/spectrum.h"
#include "refracta/core/wavelength_distribution.h"
#include "refracta/render/adaptive_sampling.h"
#include "refracta/render/integrator.h"
#include "refracta/render/readouts.h"
#include "refracta/render/render_options.h"
#include "refracta/render/tile_loop.h"
#include "refracta/scene/camera.h"
#include "refracta/shading/color.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <vector>

#include <cmath>
#include <cstdint>
#include <limits>

namespace refracta {

namespace detail {

// A 32-bit seed drawn from the pixel's generator.
inline uint32_t draw_seed(Sampler& sampler) { return uint32_t(sampler.rng.uniform() * 4294967296.0); }

// The running sums of one pixel's samples: radiance (and surface AOVs) in `value`, its samples'
// luminance and its square (adaptive sampling's variance), the readouts' nearest hit and the sum
// of the samples' directions at the eye.
template <int kChannels>
struct PixelSums {
  Eigen::Matrix<double, kChannels, 1> value = Eigen::Matrix<double, kChannels, 1>::Zero();
  double luminance = 0.0, luminance_squared = 0.0;
  int count = 0;
  Vec3d albedo = Vec3d::Zero(), normal = Vec3d::Zero();  // the samples' surface AOVs (when drawn)
  Vec3d directions = Vec3d::Zero();
  SurfaceAovs nearest;
  double mean_luminance() const { return count > 0 ? luminance / count : 0.0; }
  double luminance_variance() const {  // unbiased; 0 under two samples
    return count > 1 ? std::max(0.0, (luminance_squared - luminance * luminance / count) / (count - 1)) : 0.0;
  }
};

// Edge refinement (RenderOptions::edge_spp): which pixels show an edge between surfaces. A pixel
// of one or a few point samples cannot weigh the parts of an edge it holds (one sample at its
// centre gives a staircase, four a comb along thin poles); a sensor's pixel integrates them. The
// test compares the first-hit albedo and shading normal, averaged over each pixel's base samples
// (SurfaceAovs: deterministic for a given hit, so Monte Carlo noise in the radiance -- a 1-spp
// sea's glitter flags half the cold sea's pixels by radiance contrast -- does not trigger it), of
// a pixel's 8 neighbours among themselves: an edge where two of them differ by more than
//  - kAlbedoStep in any channel: a change of surface or texture a display shows (0.05 of a white
//    surface's albedo; the demo scenes' poles 0.03 against sand ~0.4, the cold sea's hulls against
//    the sea);
//  - kNormalStep in |n_p - n_q| (2 sin(theta / 2): 0.25 is 14 deg): a fold or a corner, and a
//    pixel that met a surface beside one that saw the sky (normal zero: |n| apart, 1 for a full
//    pixel).
// Never the pixel's own samples: a pixel kept (not refined) keeps them, and a choice made from
// them would bias it (a thin bar its samples happened to miss would leave it unrefined, its value
// short of the bar's coverage, every time). Chosen from its neighbours alone, its samples are
// independent of the choice and either way its value is unbiased. An edge flags the pixels either
// side of it (each has neighbours on both sides) as comparing each pixel with its own neighbours
// did; a feature inside one pixel's base samples flags its 8 neighbours, not itself.
struct EdgeRefinement {
  static constexpr double kAlbedoStep = 0.05;
  static constexpr double kNormalStep = 0.25;
  // Whether the neighbours inside `area` of pixel (x, y) of `base` (its pixel (0, 0) is `area`'s
  // (x0, y0); the albedo in channels `albedo` to albedo + 2, the normal in the next three) differ.
  static bool at_edge(const Image& base, const PixelBounds& area, int albedo, int x, int y) {
    const float* neighbours[8];
    int count = 0;
    for (int v = std::max(area.y0, y - 1); v <= std::min(area.y1 - 1, y + 1); ++v) {
      for (int u = std::max(area.x0, x - 1); u <= std::min(area.x1 - 1, x + 1); ++u) {
        if (u != x || v != y) neighbours[count++] = base.at(u - area.x0, v - area.y0);
      }
    }
    for (int i = 0; i < count; ++i) {
      for (int j = i + 1; j < count; ++j) {
        if (differ(neighbours[i], neighbours[j], albedo)) return true;
      }
    }
    return false;
  }

 private:
  static bool differ(const float* p, const float* q, int albedo) {
    double normal_step = 0.0;
    for (int c = 0; c < 3; ++c) {
      if (std::abs(double(p[albedo + c]) - double(q[albedo + c])) > kAlbedoStep) return true;
      const double d = double(p[albedo + 3 + c]) - double(q[albedo + 3 + c]);
      normal_step += d * d;
    }
    return normal_step > kNormalStep * kNormalStep;
  }
};

}  // namespace detail

// SampleRadiance: Spectrum(const Vec2d& pixel, const Vec2d& lens, double spacing, double pixel_angle,
// SampledWavelengths&, Sampler&, ScratchBuffer&, SurfaceAovs*): the sample's position (u, v) in pixel
// coordinates, its point on a thin lens in [0, 1)^2 (Camera::lens_ray; (0.5, 0.5), the lens centre,
// for a pinhole, which draws no number for it), the spacing of the samples [pixels] (1 / sqrt(spp):
// a sample stands for its share of the pixel at the average budget, adaptive or not), and its
// cone's angle [rad] (0 without texture filtering), and where to put the sample's surface AOVs
// (null without). kRadiance: 3 channels;
// kSurface: 9, the radiance then the mean albedo and normal of the pixel's samples; kReadouts:
// those 9 and the kReadoutChannels of readouts.h -- of the nearest hit among the pixel's samples
// (the first sample of the least path length: never a blend of a foreground and a background)
// its distance, position and object id, and through `geometry` its true elevation and hidden
// heights; the apparent elevation and azimuth of the mean of the samples' directions at the eye.
// `pixel_samples` (if given) becomes a one-channel image of the bounds: each pixel's number of
// samples its value averages. `samples` (if given) receives the number of samples drawn: width x
// height x spp of the bounds without adaptive sampling; with it, the whole image's width x height
// x spp (pilot included), and for a part of the image its pixels' samples and the pilots of the
// blocks it touches; with edge refinement the base pass over the bounds and the pixels around them
// plus edge_spp per refined pixel.
// A spectral render's samples draw their wavelengths from `wavelengths` (uniform by default).
enum class FilmLayout { kRadiance, kSurface, kReadouts };

template <FilmLayout kLayout, class SampleRadiance>
Image render_film(const Camera& camera, const RenderOptions& options, WorkControl& control,
                  const SampleRadiance& radiance, int64_t* samples = nullptr,
                  const ReadoutGeometry* geometry = nullptr,
                  const WavelengthDistribution& wavelengths = WavelengthDistribution(),
                  Image* pixel_samples = nullptr) {
  constexpr bool kSurfaceAovs = kLayout != FilmLayout::kRadiance;
  constexpr bool kReadouts = kLayout == FilmLayout::kReadouts;
  constexpr int kChannels = kReadouts ? kSurfaceChannels + kReadoutChannels : kSurfaceAovs ? kSurfaceChannels : 3;
  using PixelValue = Eigen::Matrix<double, kChannels, 1>;
  using Sums = detail::PixelSums<kChannels>;
  // Each sample's cone covers its share of the pixel.
  const double spacing = 1.0 / std::sqrt(double(options.spp));
  const double pixel_angle = options.texture_filter ? camera.pixel_angle() * spacing : 0.0;
  const bool thin_lens = camera.aperture_diameter() > 0.0;
  const uint64_t width = uint64_t(camera.width()), pixels = width * uint64_t(camera.height());
  tbb::enumerable_thread_specific<ScratchBuffer> scratch_per_thread;
  // Edge refinement (edge_spp above spp; not with adaptive): the base pass also draws each sample's
  // surface AOVs, which choose the pixels rendered again (detail::EdgeRefinement).
  const bool refine_edges = options.edge_spp > options.spp && !options.adaptive;
  // `count` more samples of pixel (x, y) into `sums`, from the generator of the pixel's `pass`
  // (0: the first or only one), as one pattern of that count; `surface`: also their surface AOVs
  // into sums.albedo and sums.normal.
  auto add_samples = [&](Sums& sums, int x, int y, int count, uint64_t pass, bool surface) {
    if (count < 1) return;
    ScratchBuffer& scratch = scratch_per_thread.local();
    Sampler sampler{Rng(options.seed, pass * pixels + uint64_t(y) * width + uint64_t(x))};
    // One sample of spp 1: the pixel's centre; jittered as a base pass for edge refinement, so a
    // feature between the pixels' centres may still be met (and, met, flag its neighbours).
    const bool centre = count == 1 && options.spp == 1 && !refine_edges;
    const uint32_t pattern_seed = centre ? 0u : detail::draw_seed(sampler);
    const CmjPattern pattern(count, pattern_seed);
    // The lens point, drawn only by a thin lens (pinhole renders unchanged), from a pattern of its
    // own whose samples are paired with the pixel's through a shuffle (pbrt-v4's samplers: each
    // dimension stratified, their pairing random).
    const uint32_t lens_seed = thin_lens ? detail::draw_seed(sampler) : 0u;
    const uint32_t lens_shuffle = thin_lens ? detail::draw_seed(sampler) : 0u;
    const CmjPattern lens_pattern(count, lens_seed);
    // The radiance's own draws, stratified over these samples (Sampler), their shuffles from a hash
    // of the pattern's seed (the generator's numbers, and so the samples' positions, as before).
    if (count > 1) sampler.set_pattern(count, Rng::mix(pattern_seed ^ 0x5851F42D4C957F2Dull));
    for (int s = 0; s < count; ++s) {
      poll_cancel();  // a sample through turbulence can take milliseconds (the ray's steps poll too)
      sampler.start_sample(s);
      Vec2d offset(0.5, 0.5);
      if (!centre) {
        const double jx = sampler.rng.uniform();
        offset = pattern.point(s, jx, sampler.rng.uniform());
      }
      Vec2d lens(0.5, 0.5);
      if (thin_lens) {
        const int t = int(permutation_element(uint32_t(s), uint32_t(count), lens_shuffle));
        const double jx = sampler.rng.uniform();
        lens = lens_pattern.point(t, jx, sampler.rng.uniform());
      }
      SampledWavelengths lambda = SampledWavelengths::rgb();
      if (options.spectral) {
        // One 2-D draw: the samples' sets and (through dispersive air, where only the hero counts)
        // their heroes both stratified.
        const Vec2d u = sampler.uniform2();
        lambda = wavelengths.sample(u.x(), u.y());
      }
      SurfaceAovs aovs;
      const Spectrum L = radiance(Vec2d(x + offset.x(), y + offset.y()), lens, spacing, pixel_angle, lambda, sampler,
                                  scratch, surface ? &aovs : nullptr);
      const Vec3d rgb = to_linear_srgb(L, lambda);
      ++sums.count;
      if (is_finite(rgb)) {  // a non-finite sample is dropped (the renderer counts them)
        sums.value.template head<3>() += rgb;
        const double luminance = rgb.dot(Vec3d(0.2126, 0.7152, 0.0722));  // Rec. 709 / sRGB weights
        sums.luminance += luminance;
        sums.luminance_squared += luminance * luminance;
      }
      sums.albedo += aovs.albedo;
      sums.normal += aovs.normal;
      if constexpr (kSurfaceAovs) {
        sums.value.template segment<3>(3) += aovs.albedo;
        sums.value.template segment<3>(6) += aovs.normal;
      }
      if constexpr (kReadouts) {
        sums.directions += aovs.eye_direction;
        if (aovs.hit && (!sums.nearest.hit || aovs.distance < sums.nearest.distance)) sums.nearest = aovs;
      }
    }
  };
  auto pixel_value = [&](const Sums& sums) {
    PixelValue value = sums.value / double(sums.count);
    if constexpr (kReadouts) {
      const SurfaceAovs& nearest = sums.nearest;
      auto out = value.template tail<kReadoutChannels>();
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const Vec3d position = nearest.hit ? nearest.hit->point : Vec3d::Constant(nan);
      out[kReadoutDistance] = nearest.hit ? nearest.distance : std::numeric_limits<double>::infinity();
      out.template segment<3>(kReadoutPosition) = position;
      out[kReadoutObject] = nearest.hit ? double(nearest.hit->geometry) : -1.0;
      // The direction of the sample whose hit the pixel reads (its mean where none hit): the mean's
      // at 16 spp put half a pixel (0.16 deg) of refraction between apparent and true elevation
      // over ground seen through no air at all (a trial).
      out.template segment<2>(kReadoutApparentElevation) =
          apparent_angles(nearest.hit ? nearest.eye_direction : sums.directions);
      out[kReadoutTrueElevation] = geometry->true_elevation(position);
      out[kReadoutHiddenHeight] = geometry->hidden_geometric(position);
      out[kReadoutHiddenHeight + 1] = geometry->hidden_refracted(position);
    }
    return value;
  };
  const PixelBounds bounds = options.bounds_in(camera.width(), camera.height());
  const int first = AdaptiveSampling::first_pass(options.spp);
  if (pixel_samples) *pixel_samples = Image(bounds.width(), bounds.height(), 1);
  auto count_samples = [&](int x, int y, int count) {
    if (pixel_samples) pixel_samples->at(x - bounds.x0, y - bounds.y0)[0] = float(count);
  };
  if (refine_edges) {
    // The base pass over the bounds and the pixels around them (an edge pixel's test needs its
    // neighbours: a part of the image renders as in the whole), its value then the samples' mean
    // albedo and normal; then each pixel at an edge rendered again as one pattern of edge_spp
    // samples from its second stream, replacing its base samples (one stratified pattern of
    // edge_spp, not a base pattern and a second one), and every other pixel as the base pass had
    // it. The choice never reads a pixel's own samples (EdgeRefinement): either way unbiased (Kirk
    // & Arvo 1991: samples that chose their own pixel's treatment bias it).
    const PixelBounds area{std::max(0, bounds.x0 - 1), std::max(0, bounds.y0 - 1), std::min(camera.width(), bounds.x1 + 1),
                           std::min(camera.height(), bounds.y1 + 1)};
    using BaseValue = Eigen::Matrix<double, kChannels + 6, 1>;
    control.total = tile_count(area, options.tile) + tile_count(bounds, options.tile);  // both passes
    const Image base = render_tiles(area, options.tile, control, [&](int x, int y) {
      Sums sums;
      add_samples(sums, x, y, options.spp, 0, true);
      BaseValue value;
      value << pixel_value(sums), sums.albedo / double(sums.count), sums.normal / double(sums.count);
      return value;
    }, ProgressTotal::kKeep);
    std::atomic<int64_t> refined{0};
    Image image = render_tiles(bounds, options.tile, control, [&](int x, int y) {
      if (!detail::EdgeRefinement::at_edge(base, area, kChannels, x, y)) {
        count_samples(x, y, options.spp);
        const float* kept = base.at(x - area.x0, y - area.y0);
        PixelValue value;
        for (int c = 0; c < kChannels; ++c) value[c] = double(kept[c]);
        return value;
      }
      refined.fetch_add(1, std::memory_order_relaxed);
      count_samples(x, y, options.edge_spp);
      Sums sums;
      add_samples(sums, x, y, options.edge_spp, 1, kSurfaceAovs);
      return pixel_value(sums);
    }, ProgressTotal::kKeep);
    if (samples) *samples = int64_t(area.width()) * area.height() * options.spp + refined.load() * options.edge_spp;
    return image;
  }
  if (!options.adaptive || options.spp <= first) {
    if (samples) *samples = int64_t(bounds.width()) * bounds.height() * options.spp;
    return render_tiles(bounds, options.tile, control, [&](int x, int y) {
      count_samples(x, y, options.spp);
      Sums sums;
      add_samples(sums, x, y, options.spp, 0, kSurfaceAovs);
      return pixel_value(sums);
    });
  }
  // Adaptive: blocks of the image (adaptive_sampling.h) are the units of work, each the pilot
  // over all its pixels, their sample counts, and the samples of those in the bounds.
  const int block = AdaptiveSampling::kBlock;
  const int bx0 = bounds.x0 / block, by0 = bounds.y0 / block;
  const int blocks_x = (bounds.x1 + block - 1) / block - bx0, blocks_y = (bounds.y1 + block - 1) / block - by0;
  Image image(bounds.width(), bounds.height(), kChannels);
  std::atomic<int64_t> drawn{0};
  parallel_for_each(int64_t(blocks_x) * blocks_y, 1, control, [&](int64_t index) {
    const int x0 = (bx0 + int(index % blocks_x)) * block, y0 = (by0 + int(index / blocks_x)) * block;
    const int x1 = std::min(x0 + block, camera.width()), y1 = std::min(y0 + block, camera.height());
    const int w = x1 - x0, h = y1 - y0;
    std::vector<Sums> sums(size_t(w) * size_t(h));
    std::vector<double> mean(sums.size()), variance(sums.size());
    for (size_t p = 0; p < sums.size(); ++p) {
      add_samples(sums[p], x0 + int(p % size_t(w)), y0 + int(p / size_t(w)), first, 0, kSurfaceAovs);
      mean[p] = sums[p].mean_luminance();
      variance[p] = sums[p].luminance_variance();
    }
    const std::vector<int> extra = adaptive_extra_samples(w, h, mean, variance, options.spp, first);
    int64_t count = int64_t(sums.size()) * first;
    for (size_t p = 0; p < sums.size(); ++p) {
      const int x = x0 + int(p % size_t(w)), y = y0 + int(p / size_t(w));
      if (x < bounds.x0 || x >= bounds.x1 || y < bounds.y0 || y >= bounds.y1) continue;
      Sums pixel;  // the pilot's samples only chose the count: the pixel is one pattern of its own
      add_samples(pixel, x, y, extra[p], 1, kSurfaceAovs);
      count_samples(x, y, extra[p]);
      count += extra[p];
      const PixelValue value = pixel_value(pixel);
      float* out = image.at(x - bounds.x0, y - bounds.y0);
      for (int c = 0; c < kChannels; ++c) out[c] = float(value[c]);
    }
    drawn.fetch_add(count, std::memory_order_relaxed);
  });
  if (samples) *samples = drawn.load();
  return image;
}

}  // namespace refracta
