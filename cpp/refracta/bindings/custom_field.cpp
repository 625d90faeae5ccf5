// CustomField: calls into Python with the GIL held, checking every result's shape.
#include "refracta/bindings/custom_field.h"

#include "refracta/bindings/running_work.h"
#include "refracta/core/parallel.h"
#include "refracta/media/ior_range.h"

namespace refracta {

CustomField::CustomField(py::object ior, py::object grad_ior, bool height_only)
    : ior_(new py::object(std::move(ior))), grad_(new py::object(std::move(grad_ior))),
      height_only_(height_only) {
  if (!PyCallable_Check(ior_->ptr())) throw_invalid("CustomField: ior must be callable");
  if (!PyCallable_Check(grad_->ptr())) throw_invalid("CustomField: grad_ior must be callable");
}

CustomField::~CustomField() {
  // At interpreter exit a thread without the GIL must not take it: the two objects are leaked.
  if (python_is_shutting_down() && !PyGILState_Check()) return;
  py::gil_scoped_acquire acquire;
  delete ior_;
  delete grad_;
}

DoubleArray CustomField::call_ior(const DoubleArray& points) const {
  const py::ssize_t count = points.shape(0);
  DoubleArray out = real_array((*ior_)(points), "CustomField: ior(points)");
  if (!(out.size() == count && (out.ndim() == 1 || (out.ndim() == 2 && out.shape(1) == 1) ||
                                (out.ndim() == 0 && count == 1)))) {
    throw_invalid("CustomField: ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ",)");
  }
  out = out.reshape({count});
  const double* n = out.data();
  const double* p = points.data();
  for (py::ssize_t i = 0; i < count; ++i) {
    if (!usable_ior(n[i])) {
      throw_numerical("CustomField: ior returned n = ", n[i], " at (", p[3 * i], ", ", p[3 * i + 1], ", ",
                      p[3 * i + 2], ") m; n must be finite and > 0 (in [", kMinIor, ", ", kMaxIor, "])");
    }
  }
  return out;
}

DoubleArray CustomField::call_grad(const DoubleArray& points) const {
  const py::ssize_t count = points.shape(0);
  DoubleArray out = real_array((*grad_)(points), "CustomField: grad_ior(points)");
  // Exactly (N, 3), or (3,) for one point: a (3, N) array has the same size but other meaning.
  if (!((out.ndim() == 2 && out.shape(0) == count && out.shape(1) == 3) ||
        (out.ndim() == 1 && count == 1 && out.shape(0) == 3))) {
    throw_invalid("CustomField: grad_ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ", 3)");
  }
  out = out.reshape({count, py::ssize_t(3)});
  const double* g = out.data();
  const double* p = points.data();
  for (py::ssize_t i = 0; i < 3 * count; ++i) {
    if (!std::isfinite(g[i])) {
      const py::ssize_t k = i / 3;
      throw_numerical("CustomField: grad_ior returned (", g[3 * k], ", ", g[3 * k + 1], ", ", g[3 * k + 2],
                      ") at (", p[3 * k], ", ", p[3 * k + 1], ", ", p[3 * k + 2], ") m; it must be finite");
    }
  }
  return out;
}

void CustomField::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  if (python_is_shutting_down()) throw Cancelled();  // never call into an exiting interpreter
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
