// A small counter-based random generator (SplitMix64 hashing): reproducible per pixel and
// sample whatever the thread order, from a user seed.
#pragma once

#include <Eigen/Core>

#include <cstdint>

namespace refracta {

class Rng {
 public:
  Rng(uint64_t seed, uint64_t stream) : state_(mix(seed ^ mix(stream + 0x9E3779B97F4A7C15ull))) {}
  // Uniform in [0, 1).
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }

 private:
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint64_t next() { return mix(state_ += 0x9E3779B97F4A7C15ull); }
  uint64_t state_;
};

// The random numbers of one pixel sample.
struct Sampler {
  Rng rng;
  double uniform() { return rng.uniform(); }
  Eigen::Vector2d uniform2() {
    const double a = rng.uniform();
    return Eigen::Vector2d(a, rng.uniform());
  }
};

}  // namespace refracta
