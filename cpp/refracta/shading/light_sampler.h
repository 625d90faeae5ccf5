// Chooses one light per sample among many (shared/SHADING.md section 5): in proportion to each
// light's power() (Y of its power [W]) or uniformly; the integrator divides the light's
// contribution by the probability. Lights of zero power are never chosen under kPower; when
// every power is 0 the choice falls back to uniform.
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

// Chooses one light per sample, in proportion to power ('power') or uniformly ('uniform'). Build
// it after preprocess() of infinite lights.
class LightSampler {
 public:
  enum class Strategy { kPower, kUniform };
  // 'power' or 'uniform' (ValueError otherwise).
  static Strategy strategy_from(const std::string& name);
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
