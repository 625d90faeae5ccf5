// What the shading bindings share (bind_shading.cpp, bind_material.cpp, bind_materials.cpp,
// bind_microfacet.cpp, bind_spectrum.cpp): the argument conversions of materials and spectra, and
// the materials' pickling through the constructor's keyword arguments.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/shading/ior.h"
#include "refracta/shading/material_util.h"
#include "refracta/shading/spectrum_batch.h"

#include <memory>
#include <optional>
#include <string>
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
// ior= (a number or a glass's name, Ior::named) or sellmeier= (B1, B2, B3, C1, C2, C3), C in um^2.
Ior to_ior(const py::object& ior, const py::object& sellmeier);
// Rows of four finite numbers, (N, 4) or one row (4,): wavelengths [nm], spectral samples.
RowMatrixX4d to_rows4(const py::handle& object, const char* what);
// Rows of `dims` sample numbers in [0, 1) (convert.h's to_samples): (N, dims).
RowMatrixXd to_sample_rows(const py::handle& object, const char* what, int dims);

// f at each of the numbers `object` holds (convert.h's to_values): a float for a scalar, else (N,).
template <class F>
py::object per_value(const py::handle& object, const char* what, const F& f) {
  bool single = false;
  std::vector<double> values = to_values(object, what, &single);
  for (double& x : values) x = f(x);
  return single ? py::object(py::float_(values[0])) : py::object(values_to_array(values));
}

// Pickling and `parameters` of a material: its constructor's keyword arguments, read back from
// the C++ object; unpickling calls the Python constructor with them (its checks included).
py::tuple rgb_tuple(const Vec3d& v);
py::object optional_rgb_tuple(const std::optional<Vec3d>& v);
py::object texture_argument(const TexturedReflectance& r);
py::dict with_ior(py::dict kwargs, const Ior& ior);  // kwargs and ior=n or sellmeier=(B1, B2, B3, C1, C2, C3)

template <class T, class Class>
void add_parameters(Class& cls, py::dict (*parameters)(const T&)) {
  cls.def_property_readonly("parameters", parameters,
                            "The constructor's keyword arguments that rebuild this material (pickling uses them).");
  cls.def(py::pickle(parameters, [](const py::dict& kwargs) { return py::cast<std::shared_ptr<T>>(py::type::of<T>()(**kwargs)); }));
}

// A material class T in one call: its constructor (py::init(...) and its arguments) and add_parameters.
template <class T, class Init, class... Args>
py::class_<T, Material, std::shared_ptr<T>> def_material(py::module_& m, const char* name, const char* doc, Init&& init,
                                                         py::dict (*parameters)(const T&), const Args&... args) {
  py::class_<T, Material, std::shared_ptr<T>> cls(m, name, doc);
  cls.def(std::forward<Init>(init), args...);
  add_parameters<T>(cls, parameters);
  return cls;
}

// A vectorised function's docstring (vectorize_real): the library's comment, then how it is called.
inline std::string vectorised_doc(const char* doc) {
  return std::string(doc) + "\nVectorised: numbers or arrays of them (numpy broadcasting).";
}

// The texture= argument of the materials with a textured reflectance.
#define TEXTURE_DOC                                                                                          \
  "texture: an image file (str or os.PathLike;\n"                                                          \
  "any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],\n"  \
  "multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);\n"     \
  "relative paths are from the working directory when the material is made. Each scene the material\n"    \
  "is added to registers the file (prepared once into the texture cache). An int is the id of a\n"       \
  "texture the scene already holds. f/pdf/sample evaluate the untextured colour."

// A textured material's docstring: its class comment, then TEXTURE_DOC.
inline std::string textured_doc(const char* doc) { return std::string(doc) + " " + TEXTURE_DOC; }

}  // namespace refracta
