// ModelField: wraps a scalar-templated model (Model<T>) as a double IndexField, so each model is
// written once. A model provides:
//   using Config = ...;       fixed data that is not a parameter, one type for every T (NoConfig)
//   static const char* kTypeName;
//   static std::vector<ParamSpec> param_specs(const Config&);
//   static void validate(const Config&, const std::vector<double>&);   throws invalid_argument
//   Model(const Config&, const std::vector<T>& values);
//   void evaluate(const Vec3<T>&, T* n, Vec3<T>* grad) const;
//   bool height_only() const;  (+ evaluate_height when true; HeightOnlyModel gives both)
// and, if local features can break its height dependence (hot spots, turbulence):
//   static Config height_only_config(const Config&);   the model without them: its parameters are
//                                                       the first ones of the full model's
//   std::vector<LocalRegion> local_regions() const;     where the two differ
// and, if its fixed data follows its values (hot spots' search boxes are centred on the spots):
//   static Config config_at(const Config&, const std::vector<double>& values);
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/index_field.h"

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace refracta {

namespace detail {
// Whether a model declares double uniform_above() const (see IndexField::uniform_above).
template <class M, class = void>
struct HasUniformAbove : std::false_type {};
template <class M>
struct HasUniformAbove<M, std::void_t<decltype(std::declval<const M&>().uniform_above())>> : std::true_type {};
// Whether a model has local features (height_only_config and local_regions).
template <class M, class = void>
struct HasLocalFeatures : std::false_type {};
template <class M>
struct HasLocalFeatures<M, std::void_t<decltype(std::declval<const M&>().local_regions())>> : std::true_type {};
}  // namespace detail

// Where a field or a model differs from its height-only part (none for a model without local
// features).
template <class Field>
std::vector<LocalRegion> regions_of(const Field& field) {
  if constexpr (detail::HasLocalFeatures<Field>::value) {
    return field.local_regions();
  } else {
    return {};
  }
}

namespace detail {
// Whether a model declares static Config config_at(const Config&, const std::vector<double>&).
template <class M, class = void>
struct HasConfigAt : std::false_type {};
// Whether a model's Config carries turbulence (a std::shared_ptr<const Turbulence> turbulence).
template <class C, class = void>
struct HasTurbulence : std::false_type {};
template <class C>
struct HasTurbulence<C, std::void_t<decltype(std::declval<C&>().turbulence = std::shared_ptr<const Turbulence>())>>
    : std::true_type {};
template <class M>
struct HasConfigAt<M, std::void_t<decltype(M::config_at(std::declval<const typename M::Config&>(),
                                                        std::declval<const std::vector<double>&>()))>>
    : std::true_type {};
}  // namespace detail

template <template <class> class Model>
class ModelField : public IndexField {
 public:
  using Config = typename Model<double>::Config;
  using ModelType = Model<double>;

  ModelField(Config config, std::vector<double> values)
      : config_(config_at(std::move(config), values)),
        specs_(Model<double>::param_specs(config_)),
        values_(checked(specs_, config_, std::move(values))),
        model_(config_, values_) {}

  static const char* model_name() { return Model<double>::kTypeName; }
  static std::vector<ParamSpec> param_specs_for(const Config& config) {
    return Model<double>::param_specs(config);
  }

  std::string type_name() const override { return Model<double>::kTypeName; }
  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override {
    model_.evaluate(p, n, grad);
  }
  bool height_only() const override { return model_.height_only(); }
  void evaluate_height(double h, double* n, double* dn_dh) const override {
    if (!model_.height_only()) IndexField::evaluate_height(h, n, dn_dh);  // throws
    model_.evaluate_height(h, n, dn_dh);
  }
  std::shared_ptr<const IndexField> height_only_part() const override {
    if constexpr (detail::HasLocalFeatures<Model<double>>::value) {
      if (model_.height_only()) return nullptr;
      Config base = Model<double>::height_only_config(config_);
      const size_t count = Model<double>::param_specs(base).size();
      return make(base, std::vector<double>(values_.begin(), values_.begin() + count));
    }
    return nullptr;
  }
  std::vector<LocalRegion> local_regions() const override {
    if constexpr (detail::HasLocalFeatures<Model<double>>::value) return model_.local_regions();
    return {};
  }
  const std::vector<ParamSpec>& param_specs() const override { return specs_; }
  std::vector<double> param_values() const override { return values_; }
  std::shared_ptr<const IndexField> with_param_values(
      const std::vector<double>& values) const override {
    return make_with(values);
  }
  std::vector<std::string> gauge_params() const override { return Model<double>::gauge_params(); }
  double uniform_above() const override {
    if constexpr (detail::HasUniformAbove<Model<double>>::value) return model_.uniform_above();
    return IndexField::uniform_above();
  }

  std::shared_ptr<const IndexField> with_turbulence(std::shared_ptr<const Turbulence> turbulence) const override {
    if constexpr (detail::HasTurbulence<Config>::value) {
      Config config = config_;
      config.turbulence = std::move(turbulence);
      return make(config, values_);
    } else {
      return IndexField::with_turbulence(std::move(turbulence));
    }
  }

  std::shared_ptr<const Turbulence> turbulence() const override {
    if constexpr (detail::HasTurbulence<Config>::value) {
      return config_.turbulence;
    } else {
      return IndexField::turbulence();
    }
  }

  const Config& config() const { return config_; }
  const Model<double>& model() const { return model_; }

 protected:
  // A field of the same class from a config and values (AirModelField overrides it).
  virtual std::shared_ptr<const IndexField> make(const Config& config, const std::vector<double>& values) const {
    return std::make_shared<ModelField>(config, values);
  }
  std::shared_ptr<const IndexField> make_with(const std::vector<double>& values) const { return make(config_, values); }

 private:
  // The config as if the field had been made with these values, so that its bounds are the same
  // whether it came from a constructor or from with_param_values.
  static Config config_at(Config config, const std::vector<double>& values) {
    if constexpr (detail::HasConfigAt<Model<double>>::value) {
      if (values.size() == param_specs_for(config).size()) return Model<double>::config_at(config, values);
    }
    return config;
  }
  static std::vector<double> checked(const std::vector<ParamSpec>& specs, const Config& config,
                                     std::vector<double> values) {
    if (values.size() != specs.size()) {
      throw_invalid(Model<double>::kTypeName, ": expected ", specs.size(), " parameters, got ",
                    values.size());
    }
    for (size_t i = 0; i < values.size(); ++i) {
      if (!std::isfinite(values[i])) {
        throw_invalid(Model<double>::kTypeName, ": ", specs[i].name, " must be finite (got ",
                      values[i], ")");
      }
    }
    Model<double>::validate(config, values);
    return values;
  }

  Config config_;
  std::vector<ParamSpec> specs_;
  std::vector<double> values_;
  Model<double> model_;
};

// Default values of a model's parameters, in order.
inline std::vector<double> default_values(const std::vector<ParamSpec>& specs) {
  std::vector<double> values;
  for (const auto& spec : specs) values.push_back(spec.default_value);
  return values;
}

}  // namespace refracta
