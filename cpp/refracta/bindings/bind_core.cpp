// Exceptions, running work and the options rule shared by all bindings (the array conversions:
// convert.cpp).
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/bindings/running_work.h"
#include "refracta/render/obj_materials.h"

#include <stdexcept>
#include <typeinfo>

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

namespace {

// `text` as UTF-8 with any byte that is not valid UTF-8 written \xNN (Python's backslashreplace).
std::string escaped(const std::string& text) {
  const auto size = py::ssize_t(text.size());
  py::object decoded = py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(text.data(), size, "backslashreplace"));
  if (!decoded) throw py::error_already_set();
  return py::cast<std::string>(decoded);
}

// Rethrows `e` with message `text` when its type is one refracta throws (exactly: a type derived
// from them, or another module's, passes unchanged); returns otherwise.
void rethrow_as(const std::exception& e, const std::string& text) {
  const std::type_info& type = typeid(e);
  if (type == typeid(TextureNotFound)) throw TextureNotFound(text);
  if (type == typeid(MissingFile)) throw MissingFile(text);
  if (type == typeid(IoError)) throw IoError(text);
  if (type == typeid(NumericalError)) throw NumericalError(text);
  if (type == typeid(std::invalid_argument)) throw std::invalid_argument(text);
  if (type == typeid(std::runtime_error)) throw std::runtime_error(text);
}

}  // namespace

void escape_undecodable_messages() {
  // Messages may quote a file's bytes (a PNG's chunk name, an OBJ's line, a file name in Latin-1);
  // pybind11's translators decode them as UTF-8, and an invalid byte raised UnicodeDecodeError in
  // place of the error (a trial: read_image's IoError lost its type and file). Registered last,
  // this translator runs first and hands the others the same exception with those bytes escaped.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      std::rethrow_exception(thrown);
    } catch (const py::error_already_set&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const std::exception& e) {
      const std::string text = e.what();
      PyObject* strict = PyUnicode_DecodeUTF8(text.data(), py::ssize_t(text.size()), nullptr);
      if (strict) {
        Py_DECREF(strict);
        throw;
      }
      PyErr_Clear();
      rethrow_as(e, escaped(text));
      throw;
    }
  });
}

}  // namespace refracta
