// Shared declarations of the binding files, and numpy <-> Eigen conversions.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <vector>

namespace refracta {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

void bind_core(py::module_& m);
void bind_media(py::module_& m);
void bind_turbulence(py::module_& m);  // called by bind_media
void bind_rays(py::module_& m);
void bind_scene(py::module_& m);
void bind_ocean(py::module_& m);  // called by bind_scene
void bind_render(py::module_& m);
void bind_raster(py::module_& m);
void bind_edit(py::module_& m);
void bind_shading(py::module_& m);
void bind_lights(py::module_& m);
void bind_spectrum(py::module_& m);
void bind_dispersion(py::module_& m);
void bind_runtime(py::module_& m);
// Moves the queued messages of Ceres (glog) to Python's logging; call with the GIL held.
void emit_library_log();

// Any array-like of real numbers (bool, integer or float dtype) as a C-contiguous double array;
// ValueError naming `what` for complex, string or object data (numpy would cast those silently).
DoubleArray real_array(const py::handle& object, const char* what);
// (N, 3) or (3,) float array -> points; ValueError naming `what` for other shapes or NaN.
std::vector<Vec3d> to_points(const py::handle& object, const char* what, bool* single = nullptr);
Vec3d to_point(const py::handle& object, const char* what);
// (N,) or scalar float array -> values.
std::vector<double> to_values(const py::handle& object, const char* what, bool* single = nullptr);

DoubleArray points_to_array(const std::vector<Vec3d>& points);
DoubleArray values_to_array(const std::vector<double>& values);

}  // namespace refracta
