// The scalar-templated model behind a double IndexField, so editing can rebuild the same field
// with ceres::Jet parameters. A new model plugs in with one line in visit_templated_model (a 3D
// field needs only evaluate(); CurvedEarth needs a height-only base). Fields without a templated
// model (CustomField) are edited with numeric derivatives instead.
#pragma once

#include "refracta/media/curved_earth.h"
#include "refracta/media/fields.h"

namespace refracta {

template <template <class> class M>
struct ModelTag {
  template <class T>
  using Model = M<T>;
};

// A height-only model seen through the Earth-flattening transform (curved_earth.h).
template <class Model, class T>
struct FlattenedModel {
  const Model& base;
  T radius;
  void evaluate(const Vec3<T>& p, T* n, Vec3<T>* grad) const {
    T dn_dy;
    flattened_height(base, radius, p.y(), n, &dn_dy);
    *grad = Vec3<T>(T(0.0), dn_dy, T(0.0));
  }
};

// Calls visit(ModelTag<Model>{}, config, curved) for a field built from a templated model,
// possibly inside CurvedEarth (curved = true; its radius is then the last parameter).
// Returns false for other fields.
template <class Visit>
bool visit_templated_model(const IndexField& field, Visit&& visit) {
  // A decorator (CurvedEarth, whose radius is then the last parameter) around the model.
  const FieldPtr inner = field.decorated();
  const IndexField* base = inner ? inner.get() : &field;
  const bool curved = std::isfinite(field.earth_radius());
  if (const auto* m = dynamic_cast<const ModelField<LogisticModel>*>(base)) {
    visit(ModelTag<LogisticModel>{}, m->config(), curved);
  } else if (const auto* m = dynamic_cast<const ModelField<LinearSquaredModel>*>(base)) {
    visit(ModelTag<LinearSquaredModel>{}, m->config(), curved);
  } else if (const auto* m = dynamic_cast<const ModelField<PhysicalAtmosphereModel>*>(base)) {
    visit(ModelTag<PhysicalAtmosphereModel>{}, m->config(), curved);
  } else if (const auto* m = dynamic_cast<const ModelField<TemperatureProfileModel>*>(base)) {
    visit(ModelTag<TemperatureProfileModel>{}, m->config(), curved);
  } else {
    return false;
  }
  return true;
}

}  // namespace refracta
