// The light chooser (light_sampler.h).
#include "refracta/shading/light_sampler.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

LightSampler::Strategy LightSampler::strategy_from(const std::string& name) {
  if (name == "power") return Strategy::kPower;
  if (name == "uniform") return Strategy::kUniform;
  if (name == "kind") return Strategy::kKind;
  throw_invalid("LightSampler: strategy must be 'power', 'uniform' or 'kind' (got '", name, "')");
}

const char* LightSampler::strategy_name(Strategy strategy) {
  switch (strategy) {
    case Strategy::kPower: return "power";
    case Strategy::kUniform: return "uniform";
    case Strategy::kKind: return "kind";
  }
  return "?";
}

LightSampler::LightSampler(std::vector<LightPtr> lights, Strategy strategy)
    : lights_(std::move(lights)), strategy_(strategy) {
  std::vector<double> weights(lights_.size(), 1.0);
  double infinite_power = 0.0, bounded_power = 0.0;
  int infinite = 0;  // infinite lights of some power
  for (size_t i = 0; i < lights_.size(); ++i) {
    if (!lights_[i]) throw_invalid("LightSampler: lights[", i, "] is null");
    if (strategy_ == Strategy::kUniform) continue;
    const double p = lights_[i]->power();
    if (!std::isfinite(p) || p < 0.0) throw_invalid("LightSampler: lights[", i, "].power() must be finite and >= 0 (got ", p, ")");
    weights[i] = p;
    (lights_[i]->is_infinite() ? infinite_power : bounded_power) += p;
    if (lights_[i]->is_infinite() && p > 0.0) ++infinite;
  }
  if (strategy_ == Strategy::kKind) {
    const double bounded_share = bounded_power > 0.0 ? 1.0 / (infinite + 1) : 0.0;
    const double infinite_share = 1.0 - bounded_share;
    for (size_t i = 0; i < lights_.size(); ++i) {
      weights[i] *= lights_[i]->is_infinite() ? (infinite_power > 0.0 ? infinite_share / infinite_power : 0.0)
                                              : bounded_share / std::max(bounded_power, 1e-300);
    }
  }
  if (!lights_.empty()) distribution_ = PiecewiseConstant1D(weights);
}

std::optional<SampledLight> LightSampler::sample(double u) const {
  if (lights_.empty()) return std::nullopt;
  SampledLight s;
  distribution_.sample(std::clamp(u, 0.0, std::nextafter(1.0, 0.0)), nullptr, &s.index);
  s.probability = distribution_.cell_probability(s.index);
  return s;
}

double LightSampler::pmf(size_t index) const {
  if (index >= lights_.size()) throw_invalid("LightSampler.pmf: index must be in [0, ", lights_.size(), ") (got ", index, ")");
  return distribution_.cell_probability(index);
}

}  // namespace refracta
