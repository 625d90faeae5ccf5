// What the scene and render bindings share: the Python-side scene (geometry + lights).
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/core/image.h"
#include "refracta/scene/camera.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/embree_scene.h"

namespace refracta {

py::array_t<float> image_to_float32(const Image& image);
py::array_t<float> image_to_float32(Image&& image);  // without copying the pixels

}  // namespace refracta
