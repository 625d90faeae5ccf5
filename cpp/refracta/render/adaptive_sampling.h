// Adaptive pixel sampling at an equal budget (RenderOptions::adaptive; the film loop, film.h,
// draws the samples): a pilot pass gives every pixel the same few samples, only to choose how
// many samples each pixel then gets; the pixel's value is one correlated multi-jittered pattern
// of that many.
//
// The rule, per block of kBlock x kBlock pixels aligned to the image (the budget is shared inside
// a block only, so each block renders on its own: a part of the image, a tile or any thread count
// gives every pixel as in the whole image):
// - each pixel's noise from its pilot (first_pass(spp) samples): the standard deviation of its
//   samples' luminance over sqrt(mean^2 + floor^2), floor = kFloor x the block's mean luminance,
//   at most kMaxNoise (a firefly in a two-sample pilot would otherwise draw the block's budget).
//   Spending n_p samples where that is e_p minimises the summed relative MSE sum e_p^2 / n_p for
//   n_p proportional to e_p (Lagrange; the per-pixel variance rule of Mitchell 1987, "Generating
//   antialiased images at low sampling densities", and of pbrt-v4's discussion of adaptive
//   sampling, here normalised to a fixed budget as in Rousselle et al. 2011, "Adaptive sampling
//   and reconstruction using greedy error minimization").
// - a pixel's weight is the mean noise of the 3 x 3 pixels around it in the block (a two-sample
//   pilot's deviation is itself noisy; edges are lines, so the neighbours' speaks for the pixel).
// - the block's budget left after the pilot, pixels x (spp - first), gives every pixel
//   least(spp) samples (a pilot that saw no variation can be wrong) and splits the rest in
//   proportion to the weights with no pixel above kMaxFactor x spp in all (water-filling),
//   rounded by largest remainders (ties to the lower index); weights all zero (a block of sky):
//   evenly. The block's total, pilot included, is exactly its pixels x spp: the image's
//   width x height x spp.
// - unbiased: the pilot's samples only choose the counts and are not averaged into the pixel
//   (Kirk & Arvo 1991, "Unbiased sampling techniques for image synthesis": averaging the samples
//   that chose the count biases the mean); the pixel's own samples come from another stream.
//   Its price: the pilot's share of the budget, kFirstPass.
#pragma once

#include <vector>

namespace refracta {

struct AdaptiveSampling {
  static constexpr int kBlock = 32;          // pixels: the side of the blocks sharing a budget
  static constexpr double kFirstPass = 0.125;  // the pilot's share of the budget
  static constexpr double kFloor = 0.1;       // of the block's mean luminance: dark pixels' noise floor
  static constexpr int kMaxFactor = 8;        // no pixel gets more than this x spp samples
  static constexpr double kMaxNoise = 1.0;    // a pixel's noise counts up to this (a firefly's pilot)
  static constexpr double kLeast = 0.5;       // of spp: every pixel's fewest samples
  // The pixels' fewest samples for `spp` (at least 1).
  static int least(int spp);
  // The pilot's samples per pixel for `spp`: at least 2 (a variance needs two).
  static int first_pass(int spp);
  // The fewest spp at which the budget left after the pilot exceeds every pixel's fewest
  // samples, so that some can go where they are needed (6: below it, every pixel would simply get
  // spp - 2, fewer than without adaptive sampling, at the same cost).
  static int min_spp();
};

// The samples of each pixel of a width x height block (row-major) after the pilot, given each
// pixel's pilot (`first` samples): the mean and unbiased sample variance of its samples'
// luminance. Each is at least least(spp); their sum is width x height x (spp - first).
std::vector<int> adaptive_extra_samples(int width, int height, const std::vector<double>& mean,
                                        const std::vector<double>& variance, int spp, int first);

}  // namespace refracta
