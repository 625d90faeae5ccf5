// The density spectral rendering draws its hero wavelengths from: uniform over [kLambdaMin,
// kLambdaMax] by default, or piecewise constant on equal bins, proportional to given weights
// (importance sampling the spectrum a render's light carries: render/renderer.cpp's
// hero_wavelengths, in proportion to the sun's radiance times x-bar + y-bar + z-bar, which the
// film draws from). Four wavelengths a sample, stratified through
// the inverse of the cumulative density (the hero from u, the others from u + i/4 wrapped into
// [0, 1)), each with its own density: the estimate (1/4) sum_i L_i cmf_i / pdf_i
// (shading/color.h to_linear_srgb) stays unbiased for any density that is positive wherever the
// light is (pbrt-v4's SampleVisibleWavelengths does the same for its fixed density).
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/sample_patterns.h"
#include "refracta/core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace refracta {

class WavelengthDistribution {
 public:
  WavelengthDistribution() = default;  // uniform: SampledWavelengths::sample_uniform
  // Density proportional to weights[k] on bin k of weights.size() equal bins over
  // [kLambdaMin, kLambdaMax]; weights finite and >= 0, their sum > 0.
  explicit WavelengthDistribution(const std::vector<double>& weights) {
    double total = 0.0;
    for (double w : weights) {
      if (!(w >= 0.0 && std::isfinite(w))) throw_invalid("WavelengthDistribution: weights must be finite and >= 0 (got ", w, ")");
      total += w;
    }
    if (!(total > 0.0)) throw_invalid("WavelengthDistribution: the weights' sum must be > 0 (got ", total, ")");
    bin_width_ = (kLambdaMax - kLambdaMin) / double(weights.size());
    cdf_.assign(weights.size() + 1, 0.0);
    for (size_t k = 0; k < weights.size(); ++k) cdf_[k + 1] = cdf_[k] + weights[k] / total;
    cdf_.back() = 1.0;
    density_.resize(weights.size());
    for (size_t k = 0; k < weights.size(); ++k) density_[k] = weights[k] / (total * bin_width_);
  }

  bool uniform() const { return cdf_.empty(); }

  // The density [1/nm] at lambda_nm (0 outside the rendered range).
  double pdf(double lambda_nm) const {
    if (!(lambda_nm >= kLambdaMin && lambda_nm <= kLambdaMax)) return 0.0;
    if (uniform()) return 1.0 / (kLambdaMax - kLambdaMin);
    return density_[bin_of(lambda_nm)];
  }

  // Four wavelengths whose set is chosen by u_set and whose hero among them by u_hero, both in
  // [0, 1): the sets repeat every quarter of u (u + i/4 below), so sample((u_set + floor(4 u_hero)) / 4).
  // Stratified over a pixel's samples as one 2-D point, both the sets and the heroes are (a
  // stratified u alone would give 4 samples the same set: each quarter of u spans every set).
  SampledWavelengths sample(double u_set, double u_hero) const {
    const double quarter = std::floor(u_hero * kSpectrumSamples);
    return sample(std::min((u_set + quarter) / kSpectrumSamples, kOneMinusEpsilon));
  }

  // Four wavelengths from u in [0, 1): lambda_i at u + i/4 (wrapped) of the cumulative density.
  SampledWavelengths sample(double u) const {
    if (uniform()) return SampledWavelengths::sample_uniform(u);
    SampledWavelengths w;
    w.spectral = true;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      double v = u + double(i) / kSpectrumSamples;
      if (v >= 1.0) v -= 1.0;
      // The bin holding v (a bin of zero weight is never chosen: its cdf step is empty).
      const auto upper = std::upper_bound(cdf_.begin(), cdf_.end(), v);
      const size_t k = std::min(size_t(std::max<std::ptrdiff_t>(upper - cdf_.begin() - 1, 0)), density_.size() - 1);
      const double step = cdf_[k + 1] - cdf_[k];
      const double t = step > 0.0 ? std::clamp((v - cdf_[k]) / step, 0.0, 1.0) : 0.5;
      w.lambda[i] = kLambdaMin + (double(k) + t) * bin_width_;
      w.pdf[i] = density_[k];
    }
    return w;
  }

 private:
  size_t bin_of(double lambda_nm) const {
    return std::min(size_t(std::max(0.0, (lambda_nm - kLambdaMin) / bin_width_)), density_.size() - 1);
  }

  std::vector<double> cdf_;      // cdf_[k]: the probability below bin k; empty when uniform
  std::vector<double> density_;  // [1/nm] on each bin
  double bin_width_ = 0.0;       // [nm]
};

}  // namespace refracta
