// Stratified patterns over the samples of one pixel: a pseudo-random permutation of [0, n) and
// Kensler's correlated multi-jittered pattern in [0, 1)^2 (Kensler 2013, "Correlated
// Multi-Jittered Sampling", Pixar Technical Memo 13-01).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refracta {

// The largest double below 1: a stratum's far edge, which (stratum + u) / n may round up to.
inline constexpr double kOneMinusEpsilon = 1.0 - 1.0 / 9007199254740992.0;

// Element i of a pseudo-random permutation of [0, n) chosen by `seed` (Kensler 2013's permute():
// an invertible hash of the bits below n's highest, cycle-walked into [0, n)); as pbrt-v4's
// PermutationElement.
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

// Kensler 2013's correlated multi-jittered pattern (cmj()) of `count` samples in [0, 1)^2: the
// cells of a columns x rows grid (columns the largest divisor of count not above its square root,
// so columns x rows = count: 1 x count for a prime count, a Latin hypercube), one sample each;
// within its cell a sample sits in the sub-column its row's shuffle gives it and in the sub-row its
// column's shuffle gives it, the same shuffles for every cell ("correlated"): each of the count
// columns and count rows of the unit square holds exactly one sample. `seed` picks the shuffles
// (point() may take another pattern's, of the same count); point() takes the jitter.
class CmjPattern {
 public:
  CmjPattern(int count, uint32_t seed) : seed_(seed) {
    columns_ = std::max(1, int(std::floor(std::sqrt(double(count)) + 1e-9)));
    while (columns_ > 1 && count % columns_ != 0) --columns_;
    rows_ = std::max(1, count / columns_);
  }
  // Sample s in [0, count), its jitter (jx, jy) in [0, 1)^2.
  Eigen::Vector2d point(int s, double jx, double jy) const { return point(s, seed_, jx, jy); }
  Eigen::Vector2d point(int s, uint32_t seed, double jx, double jy) const {
    const uint32_t i = uint32_t(s % columns_), j = uint32_t(s / columns_);
    const uint32_t sx = permutation_element(i, uint32_t(columns_), seed * 0xa511e9b3u);
    const uint32_t sy = permutation_element(j, uint32_t(rows_), seed * 0x63d83595u);
    return Eigen::Vector2d(std::min((i + (sy + jx) / rows_) / columns_, kOneMinusEpsilon),
                           std::min((j + (sx + jy) / columns_) / rows_, kOneMinusEpsilon));
  }

 private:
  uint32_t seed_;
  int columns_ = 1, rows_ = 1;
};

}  // namespace refracta
