// Shared declarations of the binding files (conversions: convert.h).
#pragma once

#include "refracta/bindings/convert.h"  // the converters every binding uses
#include "refracta/core/error.h"
#include "refracta/core/math.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace refracta {

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
// Last: every refracta class's objects made by __new__ alone raise TypeError when used (unbuilt_objects.cpp).
void refuse_unbuilt_objects();
// Last too (tried first): a message that is not UTF-8 reaches Python with its bytes escaped (bind_core.cpp).
void escape_undecodable_messages();
// A UserWarning of `message` (with the GIL held); a warning turned into an error raises.
void warn(const std::string& message);
// Moves the queued messages of Ceres (glog) to Python's logging; call with the GIL held.
void emit_library_log();

}  // namespace refracta
