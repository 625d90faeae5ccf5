// Chooses one light per sample among many (shared/SHADING.md section 5): in proportion to each
// light's power() (Y of its power [W]), by kind, or uniformly; the integrator divides the light's
// contribution by the probability. Lights of zero power are never chosen under kPower and kKind;
// when every power is 0 the choice falls back to uniform.
//
// kKind (the path tracer's choice, render/direct_lighting.h): infinite lights and bounded ones as
// two kinds, each infinite light of some power as likely as all the bounded ones together
// (pbrt-v4's BVHLightSampler gives its infinite lights the same share), by power within each
// kind. An infinite light's power is taken through the scene's bounding disc: a sky over a 1 km
// ground has ~1e5 times a lamp's, and a choice by power alone all but never sampled the lamp (its
// light came as rare fireflies from BSDF samples).
//
// Integrator: build it after every light's preprocess(centre, radius) (infinite lights' power
// depends on the scene radius). For NEE: {index, p} = sample(u); contribution / p. For MIS of a
// BSDF-sampled hit on light i: the light strategy's density is pmf(i) * light.pdf_li(...).
#pragma once

#include "refracta/core/sampling.h"
#include "refracta/shading/light.h"

#include <optional>
#include <string>
#include <vector>

namespace refracta {

struct SampledLight {
  size_t index = 0;
  double probability = 0.0;
};

// Chooses one light per sample, in proportion to power ('power'), by kind ('kind') or uniformly
// ('uniform'). Build it after preprocess() of infinite lights.
class LightSampler {
 public:
  enum class Strategy { kPower, kUniform, kKind };
  // 'power', 'uniform' or 'kind' (ValueError otherwise).
  static Strategy strategy_from(const std::string& name);
  static const char* strategy_name(Strategy strategy);
  // lights must not hold null pointers (throws std::invalid_argument).
  explicit LightSampler(std::vector<LightPtr> lights, Strategy strategy = Strategy::kPower);

  // nullopt when there are no lights. u in [0, 1).
  std::optional<SampledLight> sample(double u) const;
  double pmf(size_t index) const;  // std::invalid_argument for an index out of range
  size_t size() const { return lights_.size(); }
  const LightPtr& light(size_t index) const { return lights_.at(index); }
  const std::vector<LightPtr>& lights() const { return lights_; }
  Strategy strategy() const { return strategy_; }

 private:
  std::vector<LightPtr> lights_;
  Strategy strategy_;
  PiecewiseConstant1D distribution_;
};

}  // namespace refracta
