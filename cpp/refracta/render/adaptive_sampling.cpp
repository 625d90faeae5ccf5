#include "refracta/render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>

namespace refracta {

int AdaptiveSampling::first_pass(int spp) { return std::max(2, int(std::lround(kFirstPass * spp))); }

int AdaptiveSampling::least(int spp) { return std::max(1, int(std::lround(kLeast * spp))); }

int AdaptiveSampling::min_spp() {
  int spp = 3;
  while (spp - first_pass(spp) <= least(spp)) ++spp;
  return spp;
}

namespace {

// Each pixel's noise: its samples' luminance deviation over sqrt(mean^2 + floor^2).
std::vector<double> pixel_noise(const std::vector<double>& mean, const std::vector<double>& variance) {
  const double block_mean = std::accumulate(mean.begin(), mean.end(), 0.0) / double(mean.size());
  const double floor = AdaptiveSampling::kFloor * std::abs(block_mean);
  std::vector<double> noise(mean.size(), 0.0);
  for (size_t p = 0; p < mean.size(); ++p) {
    const double scale = std::sqrt(mean[p] * mean[p] + floor * floor);
    const double sigma = std::sqrt(std::max(0.0, variance[p]));
    noise[p] = scale > 0.0 && std::isfinite(sigma) ? std::min(AdaptiveSampling::kMaxNoise, sigma / scale) : 0.0;
  }
  return noise;
}

// The mean noise of each pixel and its 8 neighbours inside the block.
std::vector<double> neighbour_weights(int width, int height, const std::vector<double>& noise) {
  std::vector<double> weight(noise.size(), 0.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double sum = 0.0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= width || v >= height) continue;
          sum += noise[size_t(v) * size_t(width) + size_t(u)];
          ++count;
        }
      }
      weight[size_t(y) * size_t(width) + size_t(x)] = count > 0 ? sum / count : 0.0;
    }
  }
  return weight;
}

}  // namespace

std::vector<int> adaptive_extra_samples(int width, int height, const std::vector<double>& mean,
                                        const std::vector<double>& variance, int spp, int first) {
  const size_t pixels = size_t(width) * size_t(height);
  const std::vector<double> weight = neighbour_weights(width, height, pixel_noise(mean, variance));
  // AdaptiveSampling::least(spp) each, then the rest by weight.
  const int least = std::min(AdaptiveSampling::least(spp), spp - first);
  const double cap = double(AdaptiveSampling::kMaxFactor * spp - first - least);  // >= spp - first - least: feasible
  const double budget = double(pixels) * double(spp - first - least);
  // Water-filling: shares in proportion to the weights, those above the cap held at it and the
  // rest shared again among the others.
  std::vector<double> share(pixels, 0.0);
  std::vector<char> capped(pixels, 0);
  for (;;) {
    double left = budget, weights = 0.0;
    size_t open = 0;
    for (size_t p = 0; p < pixels; ++p) {
      if (capped[p]) {
        left -= cap;
      } else {
        weights += weight[p];
        ++open;
      }
    }
    bool changed = false;
    for (size_t p = 0; p < pixels; ++p) {
      if (capped[p]) continue;
      share[p] = weights > 0.0 ? left * weight[p] / weights : left / double(open);
      if (share[p] > cap) capped[p] = 1, changed = true;
    }
    if (!changed) break;
  }
  for (size_t p = 0; p < pixels; ++p) {
    if (capped[p]) share[p] = cap;
  }
  // Largest remainders: whole samples summing exactly to the budget.
  std::vector<int> extra(pixels, least);
  int64_t given = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const int whole = int(std::floor(share[p]));
    extra[p] += whole;
    given += whole;
  }
  std::vector<size_t> order(pixels);
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return share[a] - std::floor(share[a]) > share[b] - std::floor(share[b]);
  });
  for (int64_t k = 0, left = int64_t(std::llround(budget)) - given; k < left; ++k) ++extra[order[size_t(k) % pixels]];
  return extra;
}

}  // namespace refracta
