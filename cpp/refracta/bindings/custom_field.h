// CustomField: a refractive-index field written in Python as vectorised callables
// ior(points (N,3)) -> (N,) and grad_ior(points (N,3)) -> (N,3). Slow (one Python call per
// evaluation from the integrators) but lets researchers try any field.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/media/index_field.h"

#include <atomic>

namespace refracta {

class CustomField : public IndexField {
 public:
  CustomField(py::object ior, py::object grad_ior, bool height_only);
  ~CustomField() override;

  std::string type_name() const override { return "CustomField"; }
  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override;
  bool height_only() const override { return height_only_; }
  void evaluate_height(double h, double* n, double* dn_dh) const override;
  const std::vector<ParamSpec>& param_specs() const override { return specs_; }
  std::vector<double> param_values() const override { return {}; }
  std::shared_ptr<const IndexField> with_param_values(const std::vector<double>& values) const override;

  // Vectorised calls with shape and value checks (one Python call for all points).
  std::vector<double> ior_at(const std::vector<Vec3d>& points) const override;
  std::vector<Vec3d> grad_ior_at(const std::vector<Vec3d>& points) const override;

  const py::object& ior_function() const { return *ior_; }
  const py::object& grad_function() const { return *grad_; }

  // The class's garbage-collector support (py::custom_type_setup): a field whose callables refer
  // back to it (a method of an object that holds the field) is collected. Its callables are shown
  // to the collector only while Python alone owns the field: one a scene, a CurvedEarth or a
  // render also holds stays alive whatever Python drops.
  static void setup_type(PyHeapTypeObject* heap_type);

 private:
  // At its first evaluation, by any path (inside the work that makes it, GIL held), the field is checked where
  // it is evaluated: height_only=True against n and its gradient 1 m aside (a field that is not
  // height-only would be traced as the column at x = z = 0: ValueError), and grad_ior against
  // ior's central differences (a RuntimeWarning: rays follow grad_ior; a kink there also differs).
  void check_first_evaluation(const Vec3d& p, double n, const Vec3d& grad) const;
  void check_once(const Vec3d& p) const;  // with the GIL held
  mutable std::atomic<bool> checked_{false};
  // The Python calls themselves, with their shape and value checks.
  std::vector<double> call_ior(const std::vector<Vec3d>& points) const;
  std::vector<Vec3d> call_grad(const std::vector<Vec3d>& points) const;

  // Held by pointer so the destructor can take the GIL before releasing them.
  py::object* ior_;
  py::object* grad_;
  bool height_only_;
  std::vector<ParamSpec> specs_;
};

}  // namespace refracta
