// Pickle states shared by several binding files: colours, meshes and the whole Scene. Every
// state holds what a public constructor takes (parameters, arrays, texture file paths), never
// raw memory, and is rebuilt through those constructors.
#pragma once

#include "refracta/bindings/bindings.h"
#include "refracta/render/render_scene.h"
#include "refracta/shading/color.h"

#include <memory>
#include <tuple>
#include <utility>

namespace refracta {

// (kind, (r, g, b), table or None): RGB colours by their RGB, tabulated and blackbody ones by
// their 1 nm spectrum (rebuilt by Color::tabulated, which reproduces it exactly).
py::tuple color_state(const Color& color);
Color color_from_state(const py::handle& state);

// (vertices (N, 3), triangles (M, 3) int64, uvs (N, 2) or None, normals (N, 3) or None).
py::tuple mesh_state(const Mesh& mesh);
Mesh mesh_from_state(const py::handle& state);

// A scene's light as a Python object and back (PhysicalSky is bound apart from Light); any other
// object raises ValueError naming its type.
py::object light_object(const LightPtr& light);
LightPtr light_from(const py::handle& object);

// Scene: textures (paths, in id order), materials (objects), geometry (meshes / sphere sets
// with their material ids), lights (objects with the geometry they are emitted by and their
// shadow radius). Textures are referenced by absolute path: the files must exist where it is
// unpickled (a shared file system), as environment maps read from files (EnvironmentLight's pickle).
py::tuple scene_state(const RenderScene& scene);
std::shared_ptr<RenderScene> scene_from_state(const py::tuple& state);

// Pickling through a tuple of `size` items: `state` makes it from the object; `make` rebuilds the
// object from it once its size is checked (another size raises ValueError "<name>: bad pickle state").
template <class Class, class State, class Make>
void def_state_pickle(Class& cls, const char* name, size_t size, State state, Make make) {
  cls.def(py::pickle(state, [name, size, make](const py::tuple& t) {
    if (t.size() != size) throw_invalid(name, ": bad pickle state (", t.size(), " items, expected ", size, ")");
    return make(t);
  }));
}

// The same through a std::tuple of C++ values (`TypedState`): `state` gives it, `make` takes its elements.
template <class TypedState, class Class, class Get, class Make>
void def_tuple_pickle(Class& cls, const char* name, Get state, Make make) {
  def_state_pickle(
      cls, name, std::tuple_size_v<TypedState>,
      [state](const typename Class::type& self) { return py::tuple(py::cast(TypedState(state(self)))); },
      [name, make](const py::tuple& t) {
        TypedState typed;
        try {
          typed = py::cast<TypedState>(t);
        } catch (const py::cast_error&) {
          std::string types;
          for (const py::handle item : t) {
            types += (types.empty() ? "" : ", ") + std::string(Py_TYPE(item.ptr())->tp_name);
          }
          throw_invalid(name, ": bad pickle state (an item of the wrong type among ", types, ")");
        }
        return std::apply(make, std::move(typed));
      });
}

}  // namespace refracta
