// Pickle states shared by several binding files: colours, meshes and the whole Scene. Every
// state holds what a public constructor takes (parameters, arrays, texture file paths), never
// raw memory, and is rebuilt through those constructors.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/render/render_scene.h"
#include "refracta/shading/color.h"

#include <memory>

namespace refracta {

// (kind, (r, g, b), table or None): RGB colours by their RGB, tabulated and blackbody ones by
// their 1 nm spectrum (rebuilt by Color::tabulated, which reproduces it exactly).
py::tuple color_state(const Color& color);
Color color_from_state(const py::handle& state);

// (vertices (N, 3), triangles (M, 3) int64, uvs (N, 2) or None, normals (N, 3) or None).
py::tuple mesh_state(const Mesh& mesh);
Mesh mesh_from_state(const py::handle& state);

// Scene: textures (paths, in id order), materials (objects), geometry (meshes / sphere sets
// with their material ids), lights (objects with the geometry they are emitted by and their
// shadow radius). Textures are referenced by absolute path: the files must exist where it is
// unpickled (a shared file system), as environment maps read from files (EnvironmentLight's pickle).
py::tuple scene_state(const RenderScene& scene);
std::shared_ptr<RenderScene> scene_from_state(const py::tuple& state);

}  // namespace refracta
