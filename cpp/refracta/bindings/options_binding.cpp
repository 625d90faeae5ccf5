// Options classes across the boundary (options_binding.h).
#include "refracta/bindings/options_binding.h"

#include <cmath>

namespace refracta {

namespace {

bool is_field(const py::handle& type, const std::string& name) {
  if (name.empty() || name[0] == '_' || !py::hasattr(type, name.c_str())) return false;
  const py::object property = py::module_::import("builtins").attr("property");
  return py::isinstance(type.attr(name.c_str()), property);
}

std::string field_list(const py::object& options) {
  std::string out;
  for (const auto& item : options_fields(options)) out += (out.empty() ? "" : ", ") + py::cast<std::string>(item.first);
  return out;
}

double as_double(const py::handle& value) {
  return py::cast<double>(py::float_(py::reinterpret_borrow<py::object>(value)));
}

// An int (not a bool): the value of an integer field.
bool is_integer(const py::handle& value) { return PyLong_Check(value.ptr()) && !PyBool_Check(value.ptr()); }

// A real number (not a bool) equal to a whole number: 40.0, numpy.float64(3.0).
bool is_whole(const py::handle& value) {
  if (PyBool_Check(value.ptr())) return false;
  if (!py::isinstance(value, py::module_::import("numbers").attr("Real"))) return false;
  const double x = as_double(value);
  return std::isfinite(x) && std::floor(x) == x && std::abs(x) < 9.0e18;  // fits an int64
}

}  // namespace

py::dict options_fields(const py::object& self) {
  py::dict state;
  const py::handle type = py::type::handle_of(self);
  for (const py::handle name : py::module_::import("builtins").attr("dir")(type)) {
    if (is_field(type, py::cast<std::string>(name))) state[name] = self.attr(name);
  }
  return state;
}

std::string options_repr(const py::object& self) {
  std::string out;
  for (const auto& item : options_fields(self)) {
    out += (out.empty() ? "" : ", ") + py::cast<std::string>(py::str(item.first)) + "=" +
           py::cast<std::string>(py::repr(item.second));
  }
  return out;
}

void set_options_fields(const py::object& options, const py::dict& fields, const char* owner, const char* nested) {
  py::object inner = py::none();
  if (nested) inner = options.attr(nested);
  for (const auto& item : fields) {
    const std::string name = py::cast<std::string>(py::str(item.first));
    py::object target = options;
    if (!is_field(py::type::handle_of(options), name)) {
      if (inner.is_none() || !is_field(py::type::handle_of(inner), name)) {
        throw_invalid(owner, ": unknown option '", name, "' (options: ", field_list(options),
                      inner.is_none() ? "" : "; and its " + std::string(nested) + "'s: " + field_list(inner), ")");
      }
      target = inner;
    }
    try {
      target.attr(name.c_str()) = item.second;
    } catch (const py::error_already_set& error) {
      if (!error.matches(PyExc_TypeError)) throw;
      if (item.second.is_none()) continue;  // None for a field that takes none: left unset (its default)
      const std::string value = py::cast<std::string>(py::repr(item.second));
      if (is_integer(target.attr(name.c_str()))) {
        if (!is_whole(item.second)) throw_invalid(owner, ": ", name, " must be a whole number (got ", value, ")");
        target.attr(name.c_str()) = py::int_(int64_t(as_double(item.second)));
        continue;
      }
      const std::string type = py::cast<std::string>(py::type::handle_of(target).attr("__name__"));
      throw_invalid(owner, ": option ", name, "=", value, " has the wrong type for ", type, ".", name,
                    " (see help(refracta.", type, "))");
    }
  }
}

void check_options_type(const py::handle& cls, const py::object& options, const char* owner) {
  if (options.is_none() || py::isinstance(options, cls)) return;
  throw_invalid(owner, ": options must be a refracta.", py::cast<std::string>(cls.attr("__name__")), " or None (got ",
                py::cast<std::string>(py::type::handle_of(options).attr("__name__")), ")");
}

py::object build_options(const py::type& cls, const py::object& options, const py::dict& fields, const char* owner) {
  check_options_type(cls, options, owner);
  py::object copy = cls();
  if (!options.is_none()) {
    for (const auto& item : options_fields(options)) copy.attr(item.first) = item.second;
  }
  set_options_fields(copy, fields, owner);
  copy.attr("validate")();
  return copy;
}

}  // namespace refracta
