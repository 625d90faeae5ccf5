// Exceptions, running work and the options rule shared by all bindings (the array conversions:
// convert.cpp).
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/bindings/running_work.h"

namespace refracta {

void bind_core(py::module_& m) {
  py::register_exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  py::register_exception<IoError>(m, "IoError", PyExc_OSError);
  // Registered after IoError, so tried before it; `except FileNotFoundError` catches it (a trial:
  // a missing OBJ, image or texture file was an IoError only).
  py::register_exception<MissingFile>(
      m, "MissingFileError", py::make_tuple(m.attr("IoError"), py::handle(PyExc_FileNotFoundError)))
      .attr("__doc__") = "A file that is not there: a refracta.IoError and a FileNotFoundError.";
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
  m.def(
      "_build_options",
      [](const py::type& cls, const py::object& options, const std::string& owner, const py::dict& fields,
         const py::dict& paths) { return build_options(cls, options, fields, owner.c_str(), paths); },
      py::arg("cls"), py::arg("options"), py::arg("owner"), py::arg("fields"), py::arg("paths") = py::dict(),
      "A validated copy of options (a cls, or None) with fields set (paths: keyword -> dotted nested field): "
      "refracta._options.build's rule.");
  m.def("_end_thread_cancel", &end_thread_cancel, py::arg("thread_id"),
        "Lets the thread's refracta calls run again after _cancel_thread_work.");
}

}  // namespace refracta
