// What the scene, camera, image and render bindings share: the Python-side scene (geometry +
// lights) and float32 images.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/core/image.h"
#include "refracta/scene/camera.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/embree_scene.h"

#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>

namespace refracta {

// A file path argument: a str or an os.PathLike (pybind11's std::filesystem caster calls os.fspath).
using FilePath = std::filesystem::path;

py::array_t<float> image_to_float32(const Image& image);
py::array_t<float> image_to_float32(Image&& image);  // without copying the pixels

// A refracta.shading material given as `material=` (ValueError prefixed by what, e.g. "add_terrain: ").
std::shared_ptr<Material> to_material(const py::object& material, const char* what);  // bind_scene.cpp

// Called by bind_scene.
void bind_scene_lights(py::class_<RenderScene, std::shared_ptr<RenderScene>>& scene);  // bind_scene_lights.cpp
void bind_camera(py::module_& m);                                                     // bind_camera.cpp
void bind_image_io(py::module_& m);                                                   // bind_image_io.cpp
void bind_terrain(py::module_& m);                                                    // bind_terrain.cpp (Scene._add_terrain_grid)

}  // namespace refracta
