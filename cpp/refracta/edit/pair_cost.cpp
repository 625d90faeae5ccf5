// The per-pair cost functions: automatic derivatives through the templated model, or central
// differences through the double IndexField.
#include "refracta/edit/pair_cost.h"

#include "refracta/edit/jet.h"
#include "refracta/edit/pair_miss.h"
#include "refracta/edit/templated_field.h"

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/dynamic_cost_function.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

namespace refracta {

namespace {

// Jet width: free parameters are differentiated 4 at a time (ceil(m / 4) passes per pair).
constexpr int kJetStride = 4;

// sqrt(weight) times the miss vector, shortened by the pair's margin (a dead zone: zero while the
// miss is within it; outside, its length is |miss| - margin, so the cost 1/2 (|miss| - margin)^2
// and its gradient are continuous at the margin).
template <class T>
void write_residuals(const PairMiss<T>& miss, const PointPair& pair, T* residuals) {
  using std::sqrt;
  const double scale = std::sqrt(pair.weight);
  T factor(scale);
  if (pair.margin > 0.0) {
    const T length = sqrt(miss.miss.squaredNorm());
    factor = value_of(length) > pair.margin ? T(scale) * (T(1.0) - T(pair.margin) / length) : T(0.0);
  }
  for (int k = 0; k < 3; ++k) residuals[k] = miss.miss[k] * factor;
}

// Shared by both kinds: the pair, its options, the full parameter vector and the camera rig.
struct PairCostBase {
  std::vector<double> values;
  std::vector<int> free;
  PointPair pair;
  PairOptions options;
  std::shared_ptr<const CameraRig> rig;
  EvaluationContext* context;

  // The field's parameter values with the block's free ones in place; *direction: the launch
  // direction (the rig's ray through the pair's pixel, at the block's camera values).
  template <class T>
  std::vector<T> field_values(const T* block, Vec3<T>* direction) const {
    std::vector<T> full(values.begin(), values.end());
    for (size_t i = 0; i < free.size(); ++i) full[free[i]] = block[i];
    if (rig) {
      const size_t field_count = full.size() - CameraRig::kCount;
      *direction = pair.pixel ? rig->direction<T>((*pair.pixel)[0], (*pair.pixel)[1], full.data() + field_count)
                              : Vec3<T>(pair.direction.normalized().cast<T>());
      full.resize(field_count);
    } else {
      *direction = pair.direction.normalized().cast<T>();
    }
    return full;
  }
  template <class T>
  void record(const PairMiss<T>& miss) const {
    context->pair_evaluations.fetch_add(1, std::memory_order_relaxed);
    context->field_evaluations.fetch_add(miss.evaluations, std::memory_order_relaxed);
  }
};

inline bool same_value(double a, double b) { return a == b; }
template <int N>
bool same_value(const ceres::Jet<double, N>& a, const ceres::Jet<double, N>& b) {
  return a.a == b.a && a.v == b.v;
}

// The last model each thread built, per scalar type, shared by the pairs of one problem: every
// pair of an evaluation uses the same parameters, and building a model can cost more than a
// trace (PhysicalAtmosphere tabulates its hydrostatic column).
template <class Tag>
class ModelCache {
 public:
  template <class T>
  using Model = typename Tag::template Model<T>;
  using Config = typename Model<double>::Config;

  template <class T>
  const Model<T>& get(const Config& config, const std::vector<T>& values) {
    Slot<T>& slot = std::get<Slot<T>>(slots_.local());
    const bool hit = slot.model && slot.values.size() == values.size() &&
                     std::equal(values.begin(), values.end(), slot.values.begin(),
                                [](const T& a, const T& b) { return same_value(a, b); });
    if (!hit) {
      slot.model.reset();
      slot.model.emplace(config, values);
      slot.values = values;
    }
    return *slot.model;
  }

 private:
  template <class T>
  struct Slot {
    std::vector<T> values;
    std::optional<Model<T>> model;
  };
  using Jet = ceres::Jet<double, kJetStride>;
  tbb::enumerable_thread_specific<std::tuple<Slot<double>, Slot<Jet>>> slots_;
};

template <class Tag>
struct ModelPairCost : PairCostBase {
  using Config = typename Tag::template Model<double>::Config;
  Config config;
  bool curved;
  std::shared_ptr<ModelCache<Tag>> cache;

  ModelPairCost(PairCostBase base, Config config, bool curved, std::shared_ptr<ModelCache<Tag>> cache)
      : PairCostBase(std::move(base)), config(std::move(config)), curved(curved), cache(std::move(cache)) {}

  template <class T>
  bool operator()(T const* const* parameters, T* residuals) const {
    return context->guarded([&] {
      Vec3<T> direction;
      std::vector<T> full = field_values(parameters[0], &direction);
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
      const auto& model = cache->get(config, full);
      PairMiss<T> miss;
      if (curved) {
        const FlattenedModel<typename Tag::template Model<T>, T> flat{model, radius};
        miss = pair_miss_along<T>(flat, pair, direction, options, context->cancel);
      } else {
        miss = pair_miss_along<T>(model, pair, direction, options, context->cancel);
      }
      record(miss);
      write_residuals(miss, pair, residuals);
    });
  }
};

struct FieldPairCost : PairCostBase {
  FieldPtr field;

  FieldPairCost(PairCostBase base, FieldPtr field) : PairCostBase(std::move(base)), field(std::move(field)) {}

  bool operator()(double const* const* parameters, double* residuals) const {
    return context->guarded([&] { evaluate(parameters, residuals); });
  }

  // As operator(), but a failure is not recorded: a derivative's probe step may leave the model's
  // domain where the point itself is inside it.
  bool quietly(double const* const* parameters, double* residuals) const {
    try {
      evaluate(parameters, residuals);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  }

 private:
  void evaluate(double const* const* parameters, double* residuals) const {
    Vec3d direction;
    const FieldPtr at = field->with_param_values(field_values(parameters[0], &direction));
    const PairMiss<double> miss = pair_miss_along<double>(*at, pair, direction, options, context->cancel);
    record(miss);
    write_residuals(miss, pair, residuals);
  }
};

// Numeric derivatives of a FieldPairCost: central differences with Ceres' step (relative
// kRelativeStep, at least sqrt(epsilon)), one-sided where one of the two steps leaves the
// model's domain -- a parameter on its edge, as humidity's default 0: Ceres' central step to
// -1.5e-8 failed every solve and Jacobian with humidity free (a trial). The relative step
// balances truncation against the trace's tolerance-level noise.
class NumericPairCost final : public ceres::DynamicCostFunction {
 public:
  explicit NumericPairCost(std::unique_ptr<FieldPairCost> cost) : cost_(std::move(cost)) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    if (!(*cost_)(parameters, residuals)) return false;
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;
    constexpr double kRelativeStep = 1e-5;
    const int m = parameter_block_sizes()[0];
    std::vector<double> x(parameters[0], parameters[0] + m);
    const double* at[] = {x.data()};
    double ahead[3], behind[3];
    for (int j = 0; j < m; ++j) {
      const double x0 = x[size_t(j)];
      const double h = std::max(std::sqrt(std::numeric_limits<double>::epsilon()), kRelativeStep * std::abs(x0));
      x[size_t(j)] = x0 + h;
      const bool up = cost_->quietly(at, ahead);
      x[size_t(j)] = x0 - h;
      const bool down = cost_->quietly(at, behind);
      x[size_t(j)] = x0;
      if (!up && !down) {
        x[size_t(j)] = x0 + h;
        return (*cost_)(at, ahead);  // false, with the reason recorded
      }
      for (int k = 0; k < 3; ++k) {
        jacobians[0][k * m + j] = up && down ? (ahead[k] - behind[k]) / (2.0 * h)
                                  : up       ? (ahead[k] - residuals[k]) / h
                                             : (residuals[k] - behind[k]) / h;
      }
    }
    return true;
  }

 private:
  std::unique_ptr<FieldPairCost> cost_;
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

Derivatives parse_derivatives(const std::string& name, const IndexField& field) {
  if (name == "automatic") return Derivatives::kAutomatic;
  if (name == "numeric") return Derivatives::kNumeric;
  if (name == "auto") return has_templated_model(field) ? Derivatives::kAutomatic : Derivatives::kNumeric;
  throw_invalid("derivatives must be 'auto', 'automatic' or 'numeric' (got '", name, "')");
}

std::vector<std::unique_ptr<ceres::CostFunction>> make_pair_costs(
    const FieldPtr& field, const std::vector<double>& values, const std::vector<int>& free,
    const std::vector<PointPair>& pairs, const PairOptions& options, Derivatives derivatives,
    const std::shared_ptr<const CameraRig>& rig, EvaluationContext* context) {
  if (derivatives == Derivatives::kAutomatic && !has_templated_model(*field)) {
    throw_invalid("automatic derivatives need a field built from a templated model; ",
                  field->type_name(), " has none (use derivatives='numeric')");
  }
  const int m = int(free.size());
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  std::shared_ptr<void> cache;  // one ModelCache for all pairs
  for (const PointPair& pair : pairs) {
    PairCostBase base{values, free, pair, options, rig, context};
    if (derivatives == Derivatives::kAutomatic) {
      visit_templated_model(*field, [&](auto tag, const auto& config, bool curved) {
        using Tag = decltype(tag);
        using Functor = ModelPairCost<Tag>;
        if (!cache) cache = std::make_shared<ModelCache<Tag>>();
        costs.push_back(finish(new ceres::DynamicAutoDiffCostFunction<Functor, kJetStride>(new Functor(
                                   base, config, curved, std::static_pointer_cast<ModelCache<Tag>>(cache))),
                               m));
      });
    } else {
      costs.push_back(finish(new NumericPairCost(std::make_unique<FieldPairCost>(base, field)), m));
    }
  }
  return costs;
}

}  // namespace refracta
