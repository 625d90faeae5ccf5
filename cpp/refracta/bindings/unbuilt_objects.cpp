// Objects made by Cls.__new__ alone refused at their first use (see refuse_unbuilt below).
#include "refracta/bindings/bindings.h"

#include <cstring>

namespace refracta {

namespace {

// pybind11 gives an object made by `Cls.__new__(Cls)` alone -- pickle's first step, before
// __setstate__ builds it -- raw uninitialised storage at its first use as a C++ object (the lazy
// allocation in pybind11's type_caster_base.h load_value; pybind11 issue #6153), and a method
// call then crashes. That allocation is reached only for such objects (constructors and
// __setstate__ build their value directly), so each class's allocator refuses instead.
[[noreturn]] void* refuse_unbuilt(size_t) {
  throw py::type_error("this refracta object was made by __new__ alone and holds nothing: make it by calling its "
                       "class (or unpickle it whole)");
}

}  // namespace

void refuse_unbuilt_objects() {
  for (auto& entry : py::detail::get_internals().registered_types_cpp) {
    py::detail::type_info* info = entry.second;
    if (std::strncmp(info->type->tp_name, "refracta.", 9) == 0) info->operator_new = &refuse_unbuilt;
  }
}

}  // namespace refracta
