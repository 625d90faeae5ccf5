// Options classes across the boundary: pickled through their public fields, and filled from
// keywords. The defaults stay in the C++ struct initialisers; the binding only names fields.
#pragma once

#include "refracta/bindings/bindings.h"

#include <string>
#include <tuple>

namespace refracta {

// The public fields of a bound options object (its properties not starting with '_'), by name.
py::dict options_fields(const py::object& self);

// "name=value, ..." of those fields (for __repr__).
std::string options_repr(const py::object& self);

// The package's one keyword -> options rule (options_from below, and refracta._options.build for
// Python callers): sets each keyword on `options` (a bound options object), in order. A keyword
// that is not one of its fields goes to the nested options object `nested` (its attribute of that
// name, e.g. an ElevationTableOptions' `trace`) when that has it; any other name raises ValueError
// naming `owner` and listing the fields. None leaves a field that takes no None at its value
// (public signatures write x=None for "unset"), an on/off field's too, and such a field takes
// True or False only (not 1, not 2.5); a float equal to a whole number sets an integer
// field (40.0 is 40; 2.5 raises "must be a whole number"); any other value the field refuses
// raises ValueError naming the field. A keyword whose name (or its entry in `paths`, keyword ->
// dotted path) has dots sets a nested field ("shadow_map.moments.storage"); a None on the way, or
// a value the field refuses, raises ValueError naming the keyword. One ValueError lists every
// refused keyword and then what validate() finds in the fields that were set.
void set_options_fields(const py::object& options, const py::dict& fields, const char* owner,
                        const char* nested = nullptr, const py::dict& paths = py::dict());

// A copy of `options` (an instance of the bound options class `cls`, or None for its defaults)
// with `fields` set by set_options_fields, validated: options_from for a class known only in
// Python (bound as _core._build_options).
py::object build_options(const py::type& cls, const py::object& options, const py::dict& fields, const char* owner,
                         const py::dict& paths = py::dict());

// self.<name> = value, through the object's descriptors, except that an on/off field takes True
// or False only (ValueError naming `owner` and the field): pybind11's own setter takes any
// number by its truth (options.adaptive = 1, options.spectral = 0.0) and None as False.
void set_option_attribute(const py::object& self, const py::str& name, const py::object& value, const char* owner);

// ValueError unless `options` is None or an instance of `cls`.
void check_options_type(const py::handle& cls, const py::object& options, const char* owner);

// A copy of `options` (an Options, or None for the defaults) with `fields` set, validated.
template <class Options>
Options options_from(const py::object& options, const py::dict& fields, const char* owner,
                     const char* nested = nullptr) {
  check_options_type(py::type::of<Options>(), options, owner);
  py::object copy = py::cast(options.is_none() ? Options() : py::cast<Options>(options));
  set_options_fields(copy, fields, owner, nested);
  Options out = py::cast<Options>(copy);
  out.validate();
  return out;
}

// Pickling through the fields: the state is options_fields(self); unpickling sets them on a
// default-constructed object (so a field added later keeps its default).
template <class Options, class Class>
void def_options_pickle(Class& cls) {
  cls.def(py::pickle([](const py::object& self) { return options_fields(self); },
                     [](const py::dict& state) {
                       py::object options = py::cast(Options());
                       for (const auto& item : state) options.attr(item.first) = item.second;
                       return py::cast<Options>(options);
                     }));
}

// Pickling of a read-only result (RenderStats, RasterRenderStats) through the tuple of its fields,
// in the order given.
template <class Result, class... T>
void def_fields_pickle(py::class_<Result>& cls, T Result::*... fields) {
  cls.def(py::pickle([=](const Result& r) { return std::make_tuple(r.*fields...); },
                     [=](const std::tuple<T...>& state) {
                       Result r;
                       std::apply([&](const T&... values) { ((r.*fields = values), ...); }, state);
                       return r;
                     }));
}

// repr: "Owner(name=value, ...)" of the bound fields.
template <class Class>
Class& def_options_repr(Class& cls, const char* owner) {
  return cls.def("__repr__",
                 [owner](const py::object& self) { return std::string(owner) + "(" + options_repr(self) + ")"; });
}

// ==: the same class with equal public fields (nested options compared by theirs).
template <class Class>
Class& def_options_eq(Class& cls) {
  return cls.def("__eq__", [](const py::object& self, const py::object& other) -> py::object {
    if (!py::type::of(self).is(py::type::of(other))) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
    return py::bool_(options_fields(self).equal(options_fields(other)));
  });
}

// What every options class has: a constructor taking fields as keywords (validated), strict
// on/off fields (set_option_attribute), repr, ==, validate() and pickling through the fields.
template <class Options, class Class>
Class& def_options_common(Class& cls, const char* owner) {
  cls.def(py::init([owner](const py::kwargs& fields) { return options_from<Options>(py::none(), fields, owner); }),
          "The defaults, with any field set by keyword (then validated).")
      .def("validate", &Options::validate, "Raises ValueError listing every bad field (nested options included).")
      .def("__setattr__", [owner](const py::object& self, const py::str& name, const py::object& value) {
        set_option_attribute(self, name, value, owner);
      });
  def_options_repr(cls, owner);
  def_options_eq(cls);
  def_options_pickle<Options>(cls);
  return cls;
}

}  // namespace refracta
