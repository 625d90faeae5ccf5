// Python classes of the raster renderer's options and statistics (bind_raster_options.cpp).
#pragma once

#include "refracta/bindings/bindings.h"

namespace refracta {

// MomentShadowSettings, ShadowMapOptions, MboitSettings, OitSettings, RasterRenderOptions and
// RasterRenderStats; called by bind_raster before the functions that take them.
void bind_raster_options(py::module_& m);

}  // namespace refracta
