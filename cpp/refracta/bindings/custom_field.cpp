// CustomField: calls into Python with the GIL held, checking every result's shape.
#include "refracta/bindings/custom_field.h"

namespace refracta {

CustomField::CustomField(py::object ior, py::object grad_ior, bool height_only)
    : ior_(new py::object(std::move(ior))), grad_(new py::object(std::move(grad_ior))),
      height_only_(height_only) {
  if (!PyCallable_Check(ior_->ptr())) throw_invalid("CustomField: ior must be callable");
  if (!PyCallable_Check(grad_->ptr())) throw_invalid("CustomField: grad_ior must be callable");
}

CustomField::~CustomField() {
  py::gil_scoped_acquire acquire;
  delete ior_;
  delete grad_;
}

DoubleArray CustomField::call_ior(const DoubleArray& points) const {
  const py::ssize_t count = points.shape(0);
  DoubleArray out = py::cast<DoubleArray>((*ior_)(points));
  if (!(out.size() == count && (out.ndim() == 1 || (out.ndim() == 2 && out.shape(1) == 1) ||
                                (out.ndim() == 0 && count == 1)))) {
    throw_invalid("CustomField: ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ",)");
  }
  return out.reshape({count});
}

DoubleArray CustomField::call_grad(const DoubleArray& points) const {
  const py::ssize_t count = points.shape(0);
  DoubleArray out = py::cast<DoubleArray>((*grad_)(points));
  if (!(out.size() == 3 * count && (out.ndim() == 2 || (out.ndim() == 1 && count == 1)))) {
    throw_invalid("CustomField: grad_ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ", 3)");
  }
  return out.reshape({count, py::ssize_t(3)});
}

void CustomField::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  py::gil_scoped_acquire acquire;
  DoubleArray point({py::ssize_t(1), py::ssize_t(3)});
  std::copy(p.data(), p.data() + 3, point.mutable_data());
  *n = call_ior(point).at(0);
  const DoubleArray g = call_grad(point);
  *grad = Vec3d(g.at(0, 0), g.at(0, 1), g.at(0, 2));
}

void CustomField::evaluate_height(double h, double* n, double* dn_dh) const {
  if (!height_only_) IndexField::evaluate_height(h, n, dn_dh);
  Vec3d grad;
  evaluate(Vec3d(0.0, h, 0.0), n, &grad);
  *dn_dh = grad.y();
}

std::shared_ptr<const IndexField> CustomField::with_param_values(const std::vector<double>& values) const {
  if (!values.empty()) throw_invalid("CustomField has no parameters");
  py::gil_scoped_acquire acquire;
  return std::make_shared<CustomField>(*ior_, *grad_, height_only_);
}

}  // namespace refracta
