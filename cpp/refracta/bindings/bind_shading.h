// What the shading bindings share (bind_shading.cpp, bind_material.cpp, bind_materials.cpp,
// bind_microfacet.cpp): the materials' argument conversions and their pickling through the
// constructor's keyword arguments.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/shading/ior.h"
#include "refracta/shading/material_util.h"

#include <optional>
#include <utility>

namespace refracta {

void bind_material_base(py::module_& m);  // Material, BsdfSample (bind_material.cpp)
void bind_materials(py::module_& m);      // Diffuse ... ThinFilm (bind_materials.cpp)
void bind_microfacet(py::module_& m);     // Beckmann, TrowbridgeReitz, Fresnel, Ior (bind_microfacet.cpp)
void bind_terrain_shading(py::module_& m);  // TerrainShading (bind_terrain.cpp)

// A colour with its texture= argument (material_util.h's TexturedReflectance): None; an image
// file (str or os.PathLike), made absolute from the working directory and registered in each
// scene the material is added to; or the id of a texture a scene already holds.
TexturedReflectance to_textured(const py::object& color, const char* name, const py::object& texture);
// ior= (a number or 'bk7') or sellmeier= (B1, B2, B3, C1, C2, C3), C in um^2.
Ior to_ior(const py::object& ior, const py::object& sellmeier);
// (alpha) or (alpha_u, alpha_v): exactly one form; neither: `fallback` unless required.
std::pair<double, double> to_alphas(const py::object& alpha, const py::object& alpha_u, const py::object& alpha_v,
                                    bool required, double fallback);
// Row counts a and b broadcast (one of them may be 1).
size_t broadcast(size_t a, size_t b, const char* what);

// Pickling and `parameters` of a material: its constructor's keyword arguments, read back from
// the C++ object; unpickling calls the Python constructor with them (its checks included).
py::tuple rgb_tuple(const Vec3d& v);
py::object optional_rgb_tuple(const std::optional<Vec3d>& v);
py::object texture_argument(const TexturedReflectance& r);
void add_ior_arguments(py::dict& kwargs, const Ior& ior);  // ior= or sellmeier=

template <class T, class Class>
void add_parameters(Class& cls, py::dict (*parameters)(const T&)) {
  cls.def_property_readonly("parameters", parameters,
                            "The constructor's keyword arguments that rebuild this material (pickling uses them).");
  cls.def(py::pickle(parameters, [](const py::dict& kwargs) { return py::cast<std::shared_ptr<T>>(py::type::of<T>()(**kwargs)); }));
}

// The texture= argument of the materials with a textured reflectance.
#define TEXTURE_DOC                                                                                          \
  "texture: an image file (str or os.PathLike;\n"                                                          \
  "any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],\n"  \
  "multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);\n"     \
  "relative paths are from the working directory when the material is made. Each scene the material\n"    \
  "is added to registers the file (prepared once into the texture cache). An int is the id of a\n"       \
  "texture the scene already holds. f/pdf/sample evaluate the untextured colour."

}  // namespace refracta
