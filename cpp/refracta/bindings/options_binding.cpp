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
  return std::isfinite(x) && std::floor(x) == x;  // its range: set_field's
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

namespace {

// repr of a field's value that eval reads back: inf and nan as float('inf') and float('nan')
// (Python's repr writes bare inf, a NameError).
std::string value_repr(const py::handle& value) {
  if (PyFloat_Check(value.ptr())) {
    const double v = PyFloat_AS_DOUBLE(value.ptr());
    if (std::isnan(v)) return "float('nan')";
    if (std::isinf(v)) return v > 0 ? "float('inf')" : "-float('inf')";
  }
  return py::cast<std::string>(py::repr(value));
}

}  // namespace

std::string options_repr(const py::object& self) {
  std::string out;
  for (const auto& item : options_fields(self)) {
    out += (out.empty() ? "" : ", ") + py::cast<std::string>(py::str(item.first)) + "=" + value_repr(item.second);
  }
  return out;
}

namespace {

// target.<field> = value through the object's descriptors, bypassing its __setattr__ (which
// routes here: set_option_attribute): false where the field's setter refuses the value's type.
bool set_through_descriptor(const py::handle& target, const std::string& field, const py::handle& value) {
  if (PyObject_GenericSetAttr(target.ptr(), py::str(field).ptr(), value.ptr()) == 0) return true;
  py::error_already_set error;
  if (!error.matches(PyExc_TypeError)) throw error;
  return false;
}

// Whether a number field: it holds a number, or, unset (None), takes one (then left unset again).
bool is_number_field(const py::object& target, const std::string& field) {
  const py::object current = target.attr(field.c_str());
  if (PyBool_Check(current.ptr())) return false;
  if (PyLong_Check(current.ptr()) || PyFloat_Check(current.ptr())) return true;
  if (!current.is_none()) return false;
  if (!set_through_descriptor(target, field, py::int_(0))) return false;
  set_through_descriptor(target, field, py::none());
  return true;
}

// Whether an integer field: it holds an int, or, unset (None), takes 0 but not 0.5 (then left unset
// again): TurbulenceSettings.cells = 64.0 sets 64 as it would on a field holding a value.
bool is_integer_field(const py::object& target, const std::string& field) {
  const py::object current = target.attr(field.c_str());
  if (!current.is_none()) return is_integer(current);
  const bool integer = set_through_descriptor(target, field, py::int_(0)) &&
                       !set_through_descriptor(target, field, py::float_(0.5));
  set_through_descriptor(target, field, py::none());
  return integer;
}

// An on/off field takes True or False only: pybind11 takes None as False (differentials=None
// turned ray differentials off) and any number by its truth (spectral=2.5, adaptive=nan).
void check_on_off(const py::object& target, const std::string& field, const py::handle& value, const char* owner,
                  const std::string& keyword) {
  if (PyBool_Check(target.attr(field.c_str()).ptr()) && !py::detail::is_python_or_numpy_bool(value)) {
    throw_invalid(owner, ": ", keyword, " must be True or False (got ", py::cast<std::string>(py::repr(value)), ")");
  }
}

// The whole numbers an integer field's C++ type holds, as "lo .. hi", found by setting probes
// (the field's value restored).
std::string integer_range(const py::object& target, const std::string& field) {
  const py::object kept = target.attr(field.c_str());
  auto takes = [&](const py::object& value) { return set_through_descriptor(target, field, value); };
  const bool is_signed = takes(py::int_(-1));
  const py::object big = py::int_(is_signed ? (int64_t(1) << 31) : (int64_t(1) << 32));
  const bool wide = takes(big);
  set_through_descriptor(target, field, kept);
  if (is_signed) return wide ? "-2^63 .. 2^63 - 1" : "-2^31 .. 2^31 - 1";
  return wide ? "0 .. 2^64 - 1" : "0 .. 2^32 - 1";
}

// target.<field> = value where the field's setter refused the value's type: a whole number for an
// integer field is set as one (40.0 is 40); anything else raises ValueError naming `keyword`.
void set_refused(const py::object& target, const std::string& field, const py::handle& value, const char* owner,
                 const std::string& keyword) {
  const std::string shown = py::cast<std::string>(py::repr(value));
  const std::string type = py::cast<std::string>(py::type::handle_of(target).attr("__name__"));
  // True is not 1 sample (bindings/strict_numbers.h refuses bools for numbers), nor 'x' a count.
  if (!number_of(value) && is_number_field(target, field)) {
    throw_invalid(owner, ": ", keyword, " must be a number (got ", shown, ")");
  }
  if (is_integer_field(target, field)) {
    if (!is_whole(value)) throw_invalid(owner, ": ", keyword, " must be a whole number (got ", shown, ")");
    // A whole number the field's C++ integer cannot hold (2**31 for an int, -1 for an unsigned)
    // is refused by pybind11 with a TypeError that names neither: say which.
    const double whole = as_double(value);
    if (std::abs(whole) < 9.2e18 && set_through_descriptor(target, field, py::int_(int64_t(whole)))) return;
    throw_invalid(owner, ": ", keyword, "=", shown, " is out of the range of ", type, ".", field, " (",
                  integer_range(target, field), ")");
  }
  throw_invalid(owner, ": option ", keyword, "=", shown, " has the wrong type for ", type, ".", field,
                " (see help(refracta.", type, "))");
}

// Sets target.<field> = value (the rule in options_binding.h); `keyword` names it in messages.
void set_field(const py::object& target, const std::string& field, const py::handle& value, const char* owner,
               const std::string& keyword) {
  if (value.is_none() && PyBool_Check(target.attr(field.c_str()).ptr())) return;  // None: the default, as below
  check_on_off(target, field, value, owner, keyword);
  if (set_through_descriptor(target, field, value)) return;
  if (value.is_none()) return;  // None for a field that takes none: left unset (its default)
  set_refused(target, field, value, owner, keyword);
}

// A keyword naming a nested field ("shadow_map.moments.storage", or a name `paths` maps to one):
// walks to the object holding it and sets it; a refused value raises ValueError naming the keyword.
void set_path(const py::object& options, const std::string& keyword, const std::string& path, const py::handle& value,
              const char* owner) {
  py::object target = options;
  size_t begin = 0;
  for (size_t dot = path.find('.'); dot != std::string::npos; begin = dot + 1, dot = path.find('.', begin)) {
    const std::string name = path.substr(begin, dot - begin);
    if (!is_field(py::type::handle_of(target), name)) throw_invalid(owner, ": ", keyword, "= names ", path, ": no field ", name);
    target = target.attr(name.c_str());
    if (target.is_none()) throw_invalid(owner, ": ", keyword, "= sets ", path, ", but ", name, " is None");
  }
  const std::string field = path.substr(begin);
  if (!is_field(py::type::handle_of(target), field)) throw_invalid(owner, ": ", keyword, "= names ", path, ": no field ", field);
  try {
    set_field(target, field, value, owner, keyword);
  } catch (const py::error_already_set& error) {
    if (!error.matches(PyExc_ValueError)) throw;
    throw_invalid(owner, ": ", keyword, "=", py::cast<std::string>(py::repr(value)), ": ",
                  py::cast<std::string>(py::str(error.value())));
  }
}

}  // namespace

void set_option_attribute(const py::object& self, const py::str& name, const py::object& value, const char* owner) {
  const std::string field = name;
  check_on_off(self, field, value, owner, field);
  if (set_through_descriptor(self, field, value)) return;
  if (value.is_none()) throw_invalid(owner, ": ", field, " cannot be None");
  set_refused(self, field, value, owner, field);
}

namespace {

// Sets one keyword (set_options_fields' rule).
void set_keyword(const py::object& options, const py::object& inner, const std::string& name, const py::handle& value,
                 const char* owner, const char* nested, const py::dict& paths) {
  const std::string path = paths.contains(name) ? py::cast<std::string>(paths[name.c_str()]) : name;
  if (path.find('.') != std::string::npos) return set_path(options, name, path, value, owner);
  py::object target = options;
  if (!is_field(py::type::handle_of(options), path)) {
    if (inner.is_none() || !is_field(py::type::handle_of(inner), path)) {
      throw_invalid(owner, ": unknown option '", name, "' (options: ", field_list(options),
                    inner.is_none() ? "" : "; and its " + std::string(nested) + "'s: " + field_list(inner), ")");
    }
    target = inner;
  }
  set_field(target, path, value, owner, name);
}

// The message of a ValueError `run` raises (without its "owner: " prefix), or "" when it raises none.
template <class Run>
std::string value_error_of(const char* owner, Run run) {
  std::string message;
  try {
    run();
    return "";
  } catch (const std::invalid_argument& error) {
    message = error.what();
  } catch (const py::error_already_set& error) {
    if (!error.matches(PyExc_ValueError)) throw;
    message = py::cast<std::string>(py::str(error.value()));
  }
  const std::string prefix = std::string(owner) + ": ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

}  // namespace

void set_options_fields(const py::object& options, const py::dict& fields, const char* owner, const char* nested,
                        const py::dict& paths) {
  const py::object inner = nested ? py::object(options.attr(nested)) : py::object(py::none());
  Problems problems(owner);  // every refused keyword, then what validate() finds in the rest
  for (const auto& item : fields) {
    const std::string name = py::cast<std::string>(py::str(item.first));
    const std::string problem =
        value_error_of(owner, [&] { set_keyword(options, inner, name, item.second, owner, nested, paths); });
    if (!problem.empty()) problems.add(problem);
  }
  if (problems.empty()) return;
  // validate() names the class ("RenderOptions: ..."), which `owner` (e.g. "render") may not be.
  const std::string type = py::cast<std::string>(py::type::handle_of(options).attr("__name__"));
  const std::string rest = value_error_of(type.c_str(), [&] { options.attr("validate")(); });
  if (!rest.empty()) problems.add(rest);
  problems.throw_if_any();
}

void check_options_type(const py::handle& cls, const py::object& options, const char* owner) {
  if (options.is_none() || py::isinstance(options, cls)) return;
  throw_invalid(owner, ": options must be a refracta.", py::cast<std::string>(cls.attr("__name__")), " or None (got ",
                py::cast<std::string>(py::type::handle_of(options).attr("__name__")), ")");
}

py::object build_options(const py::type& cls, const py::object& options, const py::dict& fields, const char* owner,
                         const py::dict& paths) {
  check_options_type(cls, options, owner);
  py::object copy = cls();
  if (!options.is_none()) {
    for (const auto& item : options_fields(options)) copy.attr(item.first) = item.second;
  }
  set_options_fields(copy, fields, owner, nullptr, paths);
  copy.attr("validate")();
  return copy;
}

}  // namespace refracta
