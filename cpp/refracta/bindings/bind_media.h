// What the media binding files (bind_media, bind_turbulence, bind_dispersion) share.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/bindings/pickle_state.h"  // def_tuple_pickle

#include <memory>
#include <type_traits>

namespace refracta {

// A shared_ptr<const T> as Python holds it (pybind11 holders are not const).
template <class T>
std::shared_ptr<std::remove_const_t<T>> unconst(const std::shared_ptr<T>& p) {
  return std::const_pointer_cast<std::remove_const_t<T>>(p);
}

}  // namespace refracta
