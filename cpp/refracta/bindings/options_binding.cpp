// Options classes across the boundary (options_binding.h).
#include "refracta/bindings/options_binding.h"

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
      const std::string type = py::cast<std::string>(py::type::handle_of(target).attr("__name__"));
      throw_invalid(owner, ": option ", name, "=", py::cast<std::string>(py::repr(item.second)),
                    " has the wrong type for ", type, ".", name, " (see help(refracta.", type, "))");
    }
  }
}

}  // namespace refracta
