// Number arguments refuse bools: pybind11 takes True for 1.0 and 1 (Python's bool is an int), so
// Camera(vfov=True) drew a 1-degree view and HotSpot(True, ...) stood at x = 1. Every double, float
// and integer parameter of the module converts through StrictNumberCaster, which refuses Python's
// and numpy's bools and is otherwise pybind11's rule: ints and floats for floats (and objects with
// __float__ when converting), ints and objects with __index__ for integers (never floats), within
// the C++ type's range. Included by convert.h before any binding uses a number (an explicit
// specialisation must precede its first use in every file: all binding files include it first).
// Bool parameters are the converse: pybind11 specialises type_caster<bool> itself and converts
// anything with __bool__ (a number one argument slot off passed as a flag), so each bound bool
// argument is declared py::arg(name).noconvert(), which takes Python's and numpy's bools only.
#pragma once

#include <pybind11/pybind11.h>

#include <cstring>
#include <limits>
#include <type_traits>

namespace pybind11::detail {

inline bool is_python_or_numpy_bool(handle src) {
  if (PyBool_Check(src.ptr())) return true;
  const char* type = Py_TYPE(src.ptr())->tp_name;
  return std::strcmp(type, "numpy.bool_") == 0 || std::strcmp(type, "numpy.bool") == 0;
}

template <class T>
class StrictNumberCaster {
 public:
  bool load(handle src, bool convert) {
    if (!src) return false;
    // Exact floats and ints (most arguments) are no bools; anything else may be one.
    if (!PyFloat_CheckExact(src.ptr()) && !PyLong_CheckExact(src.ptr()) && is_python_or_numpy_bool(src)) return false;
    if constexpr (std::is_floating_point_v<T>) {
      if (!convert && !PyFloat_Check(src.ptr()) && !PyLong_Check(src.ptr())) return false;
      const double d = PyFloat_AsDouble(src.ptr());
      if (d == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        return false;
      }
      value = T(d);
      return true;
    } else {
      if (PyFloat_Check(src.ptr())) return false;  // no silent truncation: 1.9 is not 1
      if (!convert && !PyLong_Check(src.ptr()) && !PyIndex_Check(src.ptr())) return false;
      const auto index = reinterpret_steal<object>(PyNumber_Index(src.ptr()));
      if (!index) {
        PyErr_Clear();
        return false;
      }
      using Wide = std::conditional_t<std::is_signed_v<T>, long long, unsigned long long>;
      const Wide wide = std::is_signed_v<T> ? Wide(PyLong_AsLongLong(index.ptr()))
                                            : Wide(PyLong_AsUnsignedLongLong(index.ptr()));
      if (PyErr_Occurred()) {  // beyond long long, or negative for an unsigned type
        PyErr_Clear();
        return false;
      }
      if constexpr (sizeof(T) < sizeof(Wide)) {
        if (wide > Wide(std::numeric_limits<T>::max())) return false;
        if constexpr (std::is_signed_v<T>) {
          if (wide < Wide(std::numeric_limits<T>::min())) return false;
        }
      }
      value = T(wide);
      return true;
    }
  }

  static handle cast(T src, return_value_policy /*policy*/, handle /*parent*/) {
    if constexpr (std::is_floating_point_v<T>) {
      return PyFloat_FromDouble(double(src));
    } else if constexpr (std::is_signed_v<T>) {
      return PyLong_FromLongLong((long long)src);
    } else {
      return PyLong_FromUnsignedLongLong((unsigned long long)src);
    }
  }

  PYBIND11_TYPE_CASTER(T, io_name<std::is_integral<T>::value>("typing.SupportsInt | typing.SupportsIndex", "int",
                                                              "typing.SupportsFloat | typing.SupportsIndex",
                                                              "float"));
};

template <>
class type_caster<double> : public StrictNumberCaster<double> {};
template <>
class type_caster<float> : public StrictNumberCaster<float> {};
template <>
class type_caster<int> : public StrictNumberCaster<int> {};
template <>
class type_caster<unsigned int> : public StrictNumberCaster<unsigned int> {};
template <>
class type_caster<long> : public StrictNumberCaster<long> {};
template <>
class type_caster<unsigned long> : public StrictNumberCaster<unsigned long> {};
template <>
class type_caster<long long> : public StrictNumberCaster<long long> {};
template <>
class type_caster<unsigned long long> : public StrictNumberCaster<unsigned long long> {};

}  // namespace pybind11::detail
