// Exceptions and array conversions shared by all bindings.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/running_work.h"

#include <cmath>

namespace refracta {


DoubleArray real_array(const py::handle& object, const char* what) {
  py::array raw;
  try {
    raw = py::array::ensure(object);
  } catch (const py::error_already_set&) {
    raw = py::array();
  }
  if (!raw) throw_invalid(what, " must be an array of numbers");
  const char kind = raw.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f') {
    throw_invalid(what, " must hold real numbers (got dtype ", py::str(raw.dtype()).cast<std::string>(), ")");
  }
  return py::cast<DoubleArray>(raw);
}

std::vector<Vec3d> to_points(const py::handle& object, const char* what, bool* single) {
  DoubleArray array;
  try {
    array = real_array(object, what);
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be an array of numbers with shape (N, 3) or (3,)");
  }
  const bool one = array.ndim() == 1;
  if (!((one && array.shape(0) == 3) || (array.ndim() == 2 && array.shape(1) == 3))) {
    std::string shape = "(";
    for (py::ssize_t i = 0; i < array.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(array.shape(i));
    throw_invalid(what, " must have shape (N, 3) or (3,) (got ", shape, array.ndim() == 1 ? ",)" : ")");
  }
  if (single) *single = one;
  const py::ssize_t count = one ? 1 : array.shape(0);
  std::vector<Vec3d> points(count);
  const double* data = array.data();
  for (py::ssize_t i = 0; i < count; ++i) {
    points[i] = Vec3d(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
    if (!is_finite(points[i])) {
      throw_invalid(what, one ? "" : concat("[", i, "]"), " must be finite (got (", points[i].x(),
                    ", ", points[i].y(), ", ", points[i].z(), "))");
    }
  }
  return points;
}

Vec3d to_point(const py::handle& object, const char* what) {
  bool single = false;
  std::vector<Vec3d> points = to_points(object, what, &single);
  if (!single) throw_invalid(what, " must be one point of shape (3,)");
  return points[0];
}

std::vector<double> to_values(const py::handle& object, const char* what, bool* single) {
  DoubleArray array;
  try {
    array = real_array(object, what);
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be a number or an array of numbers");
  }
  if (array.ndim() > 1) throw_invalid(what, " must be a number or a 1-D array (got ", array.ndim(), " dimensions)");
  if (single) *single = array.ndim() == 0;
  std::vector<double> values(array.data(), array.data() + array.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) throw_invalid(what, " must be finite (got ", values[i], ")");
  }
  return values;
}

DoubleArray points_to_array(const std::vector<Vec3d>& points) {
  DoubleArray out({py::ssize_t(points.size()), py::ssize_t(3)});
  double* data = out.mutable_data();
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) data[3 * i + k] = points[i][k];
  }
  return out;
}

DoubleArray values_to_array(const std::vector<double>& values) {
  DoubleArray out(py::ssize_t(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

void bind_core(py::module_& m) {
  py::register_exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  py::register_exception<IoError>(m, "IoError", PyExc_OSError);
  // Interpreter exit with a daemon thread inside render or trace_rays: cancel the work and wait
  // for it (GIL released) before Python finalizes. Cancellation takes < 1 s (the Ctrl-C tests);
  // 10 s leaves a wide margin for a slow machine.
  m.def("_shutdown_running_work", &shutdown_running_work, py::arg("timeout_seconds") = 10.0,
        py::call_guard<py::gil_scoped_release>());
  py::module_::import("atexit").attr("register")(m.attr("_shutdown_running_work"));
  // Ctrl-C during a sweep on a thread pool (refracta._sweep.map_ordered): the signal reaches the
  // main thread only, so it cancels the work of the pool's threads.
  m.def("_cancel_thread_work", &cancel_thread_work, py::arg("thread_ids"),
        "Cancels the refracta calls of the given Python threads (threading.get_ident()): those running "
        "and those they start until _end_thread_cancel; returns how many were running.");
  m.def("_end_thread_cancel", &end_thread_cancel, py::arg("thread_id"),
        "Lets the thread's refracta calls run again after _cancel_thread_work.");
}

}  // namespace refracta
