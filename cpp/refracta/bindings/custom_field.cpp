// CustomField: calls into Python with the GIL held, checking every result's shape.
#include "refracta/bindings/custom_field.h"

#include "refracta/bindings/running_work.h"
#include "refracta/core/parallel.h"

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

namespace {

// The CustomField a Python object holds, when Python alone owns it (else nullptr).
CustomField* owned_by_python_alone(PyObject* self) {
  auto* instance = reinterpret_cast<py::detail::instance*>(self);
  // Tracked from its allocation on: the first instance of a Python subclass can be visited before
  // pybind11 lays it out (its memory still zero, no holder table to read).
  if (!instance->simple_layout && instance->nonsimple.values_and_holders == nullptr) return nullptr;
  const py::detail::value_and_holder v_h = instance->get_value_and_holder();
  if (!v_h.holder_constructed()) return nullptr;
  const auto& holder = v_h.holder<std::shared_ptr<CustomField>>();
  return holder.use_count() == 1 ? holder.get() : nullptr;
}

}  // namespace

void CustomField::setup_type(PyHeapTypeObject* heap_type) {
  PyTypeObject* type = &heap_type->ht_type;
  type->tp_flags |= Py_TPFLAGS_HAVE_GC;
  type->tp_traverse = [](PyObject* self, visitproc visit, void* arg) {
    Py_VISIT(Py_TYPE(self));  // a heap type's instances own a reference to it
    if (const CustomField* field = owned_by_python_alone(self)) {
      Py_VISIT(field->ior_->ptr());
      Py_VISIT(field->grad_->ptr());
    }
    return 0;
  };
  type->tp_clear = [](PyObject* self) {
    // Only a field the collector found unreachable: later calls would meet None (a TypeError).
    if (CustomField* field = owned_by_python_alone(self)) {
      *field->ior_ = py::none();
      *field->grad_ = py::none();
    }
    return 0;
  };
}

std::vector<double> CustomField::call_ior(const std::vector<Vec3d>& points) const {
  const py::ssize_t count = py::ssize_t(points.size());
  DoubleArray out = real_array((*ior_)(points_to_array(points)), "CustomField: ior(points)");
  if (!(out.size() == count && (out.ndim() == 1 || (out.ndim() == 2 && out.shape(1) == 1) ||
                                (out.ndim() == 0 && count == 1)))) {
    throw_invalid("CustomField: ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ",)");
  }
  std::vector<double> n(out.data(), out.data() + count);
  check_returned_iors("CustomField: ior", n, points);
  return n;
}

std::vector<Vec3d> CustomField::call_grad(const std::vector<Vec3d>& points) const {
  const py::ssize_t count = py::ssize_t(points.size());
  DoubleArray out = real_array((*grad_)(points_to_array(points)), "CustomField: grad_ior(points)");
  // Exactly (N, 3), or (3,) for one point: a (3, N) array has the same size but other meaning.
  if (!((out.ndim() == 2 && out.shape(0) == count && out.shape(1) == 3) ||
        (out.ndim() == 1 && count == 1 && out.shape(0) == 3))) {
    throw_invalid("CustomField: grad_ior returned ", out.size(), " values in ", out.ndim(),
                  " dimensions for ", count, " points; expected shape (", count, ", 3)");
  }
  std::vector<Vec3d> grads(points.size());
  for (size_t i = 0; i < grads.size(); ++i) grads[i] = Vec3d(out.data() + 3 * i);
  check_returned_grads("CustomField: grad_ior", grads, points);
  return grads;
}

std::vector<double> CustomField::ior_at(const std::vector<Vec3d>& points) const {
  if (python_is_shutting_down()) throw Cancelled();
  py::gil_scoped_acquire acquire;
  std::vector<double> n = call_ior(points);  // first: a bad shape is named for the points given
  if (!points.empty()) check_once(points[0]);
  return n;
}

std::vector<Vec3d> CustomField::grad_ior_at(const std::vector<Vec3d>& points) const {
  if (python_is_shutting_down()) throw Cancelled();
  py::gil_scoped_acquire acquire;
  std::vector<Vec3d> grads = call_grad(points);
  if (!points.empty()) check_once(points[0]);
  return grads;
}

void CustomField::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  if (python_is_shutting_down()) throw Cancelled();  // never call into an exiting interpreter
  py::gil_scoped_acquire acquire;
  check_once(p);
  *n = call_ior({p})[0];
  *grad = call_grad({p})[0];
}

void CustomField::check_once(const Vec3d& p) const {
  // Claimed before the check runs: the user's functions may let other threads take the GIL, which
  // would start checks of their own. A refusal releases it, so a field refused once is refused at
  // every use.
  if (checked_.exchange(true)) return;
  try {
    check_first_evaluation(p, call_ior({p})[0], call_grad({p})[0]);
  } catch (...) {
    checked_ = false;
    throw;
  }
}

void CustomField::check_first_evaluation(const Vec3d& p, double n, const Vec3d& grad) const {
  if (height_only_) {
    const Vec3d aside = p + Vec3d(1.0, 0.0, 1.0);
    const double n_aside = call_ior({aside})[0];
    const Vec3d grad_aside = call_grad({aside})[0];
    // n's round-off is 1e-16 of it; a field that changes by 1e-12 of n over a metre aside is not height-only.
    const double horizontal = std::max({std::abs(grad.x()), std::abs(grad.z()), std::abs(grad_aside.x()),
                                        std::abs(grad_aside.z())});
    if (std::abs(n_aside - n) > 1e-12 * std::abs(n) || horizontal > 1e-12 * std::abs(n)) {
      throw_invalid("CustomField: height_only=True, but the field depends on x or z: n = ", n, " at (", p.x(), ", ",
                    p.y(), ", ", p.z(), ") and ", n_aside, " 1 m aside, grad_ior's largest horizontal component ",
                    horizontal, " 1/m (pass height_only=False)");
    }
  }
  // Central differences 1 mm apart: a smooth field's truncation (~1e-7 of its change over 1 mm)
  // and n's round-off (1e-16 / 1e-3 m) are far below the 1e-3 relative allowance.
  constexpr double kStep = 1e-3;
  std::vector<Vec3d> probes;
  for (int a = 0; a < 3; ++a) {
    Vec3d step = Vec3d::Zero();
    step[a] = kStep;
    probes.push_back(p + step);
    probes.push_back(p - step);
  }
  const std::vector<double> values = call_ior(probes);
  Vec3d differences;
  for (int a = 0; a < 3; ++a) differences[a] = (values[2 * a] - values[2 * a + 1]) / (2.0 * kStep);
  if ((differences - grad).norm() > 1e-3 * std::max(grad.norm(), differences.norm()) + 1e-12 * std::abs(n)) {
    const std::string message =
        concat("CustomField: grad_ior(", p.x(), ", ", p.y(), ", ", p.z(), ") = (", grad.x(), ", ", grad.y(), ", ",
               grad.z(), ") but ior's central differences there give (", differences.x(), ", ", differences.y(), ", ",
               differences.z(), "): rays follow grad_ior, so they bend as it says, not as ior changes");
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
  }
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
