// The per-pair cost functions: automatic derivatives through the templated model, or central
// differences through the double IndexField.
#include "refracta/edit/pair_cost.h"

#include "refracta/edit/jet.h"
#include "refracta/edit/pair_miss.h"
#include "refracta/edit/templated_field.h"

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/dynamic_numeric_diff_cost_function.h>

#include <cmath>

namespace refracta {

namespace {

// Jet width: free parameters are differentiated 4 at a time (ceil(m / 4) passes per pair).
constexpr int kJetStride = 4;

template <class T>
void write_residuals(const PairMiss<T>& miss, double weight, T* residuals) {
  const double scale = std::sqrt(weight);
  for (int k = 0; k < 3; ++k) residuals[k] = miss.miss[k] * scale;
}

// Shared by both kinds: the pair, its options and the full parameter vector.
struct PairCostBase {
  std::vector<double> values;
  std::vector<int> free;
  PointPair pair;
  PairOptions options;
  EvaluationContext* context;

  template <class T>
  std::vector<T> full_values(const T* block) const {
    std::vector<T> full(values.begin(), values.end());
    for (size_t i = 0; i < free.size(); ++i) full[free[i]] = block[i];
    return full;
  }
  template <class T>
  void record(const PairMiss<T>& miss) const {
    context->pair_evaluations.fetch_add(1, std::memory_order_relaxed);
    context->field_evaluations.fetch_add(miss.evaluations, std::memory_order_relaxed);
  }
};

template <class Tag>
struct ModelPairCost : PairCostBase {
  using Config = typename Tag::template Model<double>::Config;
  Config config;
  bool curved;

  ModelPairCost(PairCostBase base, Config config, bool curved)
      : PairCostBase(std::move(base)), config(std::move(config)), curved(curved) {}

  template <class T>
  bool operator()(T const* const* parameters, T* residuals) const {
    return context->guarded([&] {
      std::vector<T> full = full_values(parameters[0]);
      std::vector<double> plain(full.size());
      for (size_t i = 0; i < full.size(); ++i) plain[i] = value_of(full[i]);
      T radius(0.0);
      if (curved) {
        radius = full.back();
        full.pop_back();
        plain.pop_back();
        if (!(value_of(radius) > 0.0)) throw_invalid("earth_radius must be > 0");
      }
      Tag::template Model<double>::validate(config, plain);
      const typename Tag::template Model<T> model(config, full);
      PairMiss<T> miss;
      if (curved) {
        const FlattenedModel<typename Tag::template Model<T>, T> flat{model, radius};
        miss = pair_miss<T>(flat, pair, options, context->cancel);
      } else {
        miss = pair_miss<T>(model, pair, options, context->cancel);
      }
      record(miss);
      write_residuals(miss, pair.weight, residuals);
    });
  }
};

struct FieldPairCost : PairCostBase {
  FieldPtr field;

  FieldPairCost(PairCostBase base, FieldPtr field) : PairCostBase(std::move(base)), field(std::move(field)) {}

  bool operator()(double const* const* parameters, double* residuals) const {
    return context->guarded([&] {
      const FieldPtr at = field->with_param_values(full_values(parameters[0]));
      const PairMiss<double> miss = pair_miss<double>(*at, pair, options, context->cancel);
      record(miss);
      write_residuals(miss, pair.weight, residuals);
    });
  }
};

template <class Cost>
std::unique_ptr<ceres::CostFunction> finish(Cost* cost, int free_count) {
  cost->AddParameterBlock(free_count);
  cost->SetNumResiduals(3);
  return std::unique_ptr<ceres::CostFunction>(cost);
}

}  // namespace

const char* derivatives_name(Derivatives derivatives) {
  return derivatives == Derivatives::kAutomatic ? "automatic" : "numeric";
}

bool has_templated_model(const IndexField& field) {
  return visit_templated_model(field, [](auto, const auto&, bool) {});
}

std::vector<std::unique_ptr<ceres::CostFunction>> make_pair_costs(
    const FieldPtr& field, const std::vector<double>& values, const std::vector<int>& free,
    const std::vector<PointPair>& pairs, const PairOptions& options, Derivatives derivatives,
    EvaluationContext* context) {
  if (derivatives == Derivatives::kAutomatic && !has_templated_model(*field)) {
    throw_invalid("automatic derivatives need a field built from a templated model; ",
                  field->type_name(), " has none (use derivatives='numeric')");
  }
  const int m = int(free.size());
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  for (const PointPair& pair : pairs) {
    PairCostBase base{values, free, pair, options, context};
    if (derivatives == Derivatives::kAutomatic) {
      visit_templated_model(*field, [&](auto tag, const auto& config, bool curved) {
        using Functor = ModelPairCost<decltype(tag)>;
        costs.push_back(finish(new ceres::DynamicAutoDiffCostFunction<Functor, kJetStride>(
                                   new Functor(base, config, curved)),
                               m));
      });
    } else {
      // Central differences; the relative step balances truncation against the trace's
      // tolerance-level noise.
      ceres::NumericDiffOptions numeric;
      numeric.relative_step_size = 1e-5;
      costs.push_back(finish(new ceres::DynamicNumericDiffCostFunction<FieldPairCost, ceres::CENTRAL>(
                                 new FieldPairCost(base, field), ceres::TAKE_OWNERSHIP, numeric),
                             m));
    }
  }
  return costs;
}

}  // namespace refracta
