// The built-in fields as double IndexFields, and their factories.
#pragma once

#include "refracta/media/linear_squared_profile.h"
#include "refracta/media/logistic_profile.h"
#include "refracta/media/model_field.h"
#include "refracta/media/physical_atmosphere.h"
#include "refracta/media/temperature_profile.h"

namespace refracta {

// A ModelField of a physical air model, also exposing temperature and pressure.
template <template <class> class Model>
class AirModelField : public ModelField<Model>, public AirColumn {
 public:
  using ModelField<Model>::ModelField;
  double temperature(double h) const override {
    double t, dt;
    this->model().temperature(h, &t, &dt);
    return t;
  }
  double pressure(double h) const override { return this->model().pressure(h); }

 protected:
  std::shared_ptr<const IndexField> make(const typename ModelField<Model>::Config& config,
                                         const std::vector<double>& values) const override {
    return std::make_shared<AirModelField>(config, values);
  }
};

using LogisticProfile = ModelField<LogisticModel>;
using LinearSquaredProfile = ModelField<LinearSquaredModel>;
using PhysicalAtmosphere = AirModelField<PhysicalAtmosphereModel>;
using TemperatureProfile = AirModelField<TemperatureProfileModel>;

}  // namespace refracta
