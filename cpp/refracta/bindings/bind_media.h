// What the media binding files (bind_media, bind_turbulence, bind_dispersion) share.
#pragma once

#include "refracta/bindings/bindings.h"

#include <memory>
#include <tuple>
#include <type_traits>
#include <utility>

namespace refracta {

// A shared_ptr<const T> as Python holds it (pybind11 holders are not const).
template <class T>
std::shared_ptr<std::remove_const_t<T>> unconst(const std::shared_ptr<T>& p) {
  return std::const_pointer_cast<std::remove_const_t<T>>(p);
}

// Pickling through a std::tuple of C++ values: `state` gives it, `make` rebuilds from its elements;
// a state of another length raises ValueError "<type>: bad pickle state".
template <class State, class Class, class Get, class Make>
void def_tuple_pickle(Class& cls, const char* type, Get state, Make make) {
  cls.def(py::pickle([state](const typename Class::type& self) { return py::tuple(py::cast(State(state(self)))); },
                     [type, make](const py::tuple& t) {
                       if (t.size() != std::tuple_size_v<State>) throw_invalid(type, ": bad pickle state");
                       return std::apply(make, py::cast<State>(t));
                     }));
}

}  // namespace refracta
