// Python bindings of the scene (render/render_scene.h): geometry, materials and OBJ files. Its
// lights: bind_scene_lights.cpp; the camera: bind_camera.cpp; image files: bind_image_io.cpp.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/bindings/pickle_state.h"

#include "refracta/render/obj_materials.h"
#include "refracta/render/scene_building.h"

#include <cmath>
#include <optional>
#include <tuple>

namespace refracta {

std::shared_ptr<Material> to_material(const py::object& material, const char* what) {
  std::shared_ptr<Material> m;
  try {
    m = py::cast<std::shared_ptr<Material>>(material);
  } catch (const py::cast_error&) {
    throw_invalid(what, "material must be a refracta.shading material (got ", std::string(py::str(py::type::of(material))), ")");
  }
  if (!m) throw_invalid(what, "material must be a refracta.shading material (got None)");
  return m;
}

namespace {

// An add_* call's SurfaceLook from its arguments (None: unset).
struct LookArgs {
  py::object material = py::none(), emission = py::none(), kd = py::none(), ks = py::none(), ns = py::none(),
             alpha = py::none();
  std::optional<FilePath> texture;
  bool two_sided = false;
};

SurfaceLook look_of(const LookArgs& args) {
  SurfaceLook look;
  if (!args.material.is_none()) look.material = to_material(args.material, "");
  if (!args.emission.is_none()) look.emission = to_illuminant(args.emission, "emission");
  if (!args.kd.is_none()) look.kd = to_rgb(args.kd, "kd");
  if (!args.ks.is_none()) look.ks = to_rgb(args.ks, "ks");
  if (!args.ns.is_none()) look.ns = to_number(args.ns, "ns");
  if (!args.alpha.is_none()) look.alpha = to_number(args.alpha, "alpha");
  if (args.texture) look.texture = args.texture->string();
  look.two_sided = args.two_sided;
  return look;
}

// add_mesh's arrays: vertices (N, 3), triangles (M, 3), optional normals (N, 3) and uvs (N, 2).
Mesh mesh_from(const py::object& vertices, const py::object& triangles, const py::object& normals, const py::object& uvs) {
  Mesh mesh;
  mesh.vertices = to_points(vertices, "vertices");
  mesh.triangles = to_triangles(triangles, "triangles", mesh.vertices.size());
  if (!uvs.is_none()) mesh.uvs = to_uvs(uvs, "uvs", mesh.vertices.size());
  if (!normals.is_none()) mesh.normals = to_points(normals, "normals");
  return mesh;
}

// refracta.TextureNotFoundError: a refracta.MissingFileError (what every missing file raises, bound
// in bind_core: an IoError and a FileNotFoundError).
void register_texture_not_found(py::module_& m) {
  auto& error = py::register_exception<TextureNotFound>(
      m, "TextureNotFoundError", py::make_tuple(m.attr("MissingFileError")));
  error.attr("__doc__") =
      "A texture an MTL file names is in none of the folders searched (a refracta.IoError and a FileNotFoundError).";
}

// Folders given as one path or a sequence of paths (str or os.PathLike).
std::vector<std::string> to_folders(const py::object& dirs) {
  const py::object fspath = py::module_::import("os").attr("fspath");
  if (py::isinstance<py::str>(dirs) || py::hasattr(dirs, "__fspath__")) return {py::cast<std::string>(fspath(dirs))};
  std::vector<std::string> out;
  try {
    for (const auto& item : dirs) out.push_back(py::cast<std::string>(fspath(item)));
  } catch (const py::error_already_set& error) {
    if (!error.matches(PyExc_TypeError)) throw;
    throw_invalid("texture_dirs must be a folder or a sequence of folders (str or os.PathLike)");
  }
  return out;
}

// Portland's 236 textures take ~11 s to prepare, a small model's few well under a second: the bar
// shows once preparing has taken this long, so a cached or small model loads without one.
constexpr double kQuietSeconds = 1.0;

// add_obj's progress= as ObjOptions::progress: True (a refracta._progress.ProgressBar), False or a
// callable progress(done, total). Ctrl-C stops between textures.
std::function<void(size_t, size_t)> texture_progress(const py::object& progress) {
  py::object callback;
  if (py::isinstance<py::bool_>(progress)) {
    if (progress.cast<bool>()) {
      callback = py::module_::import("refracta._progress").attr("ProgressBar")("preparing textures", py::arg("quiet_seconds") = kQuietSeconds);
    }
  } else if (PyCallable_Check(progress.ptr())) {
    callback = progress;
  } else {
    throw_invalid("progress must be True, False or a callable progress(done, total)");
  }
  return [callback](size_t done, size_t total) {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (callback) callback(done, total);
  };
}

// add_obj's settings (an ObjOptions and/or its fields as keywords; None: left as they are) with
// Python's callbacks: warnings.warn and the progress bar.
ObjOptions obj_options(const py::object& given, const py::dict& keywords, const py::object& progress) {
  py::dict fields;
  for (const auto& [name, value] : keywords) {
    if (!value.is_none()) fields[name] = value;
  }
  ObjOptions options = options_from<ObjOptions>(given, fields, "add_obj");
  options.warn = [](const std::string& message) {
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();  // warnings as errors
  };
  options.progress = texture_progress(progress);
  return options;
}

void bind_scene_geometry(py::class_<RenderScene, std::shared_ptr<RenderScene>>& scene) {
  scene
      .def("add_mesh",
           [](RenderScene& s, const py::object& vertices, const py::object& triangles, const py::object& material,
              const py::object& emission, bool two_sided, const py::object& normals, const py::object& uvs,
              const py::object& kd, const py::object& ks, const py::object& ns, std::optional<FilePath> texture,
              const py::object& alpha) {
             Mesh mesh = mesh_from(vertices, triangles, normals, uvs);
             return add_mesh(s, std::move(mesh), look_of({material, emission, kd, ks, ns, alpha, texture, two_sided}));
           },
           py::arg("vertices"), py::arg("triangles"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::arg("two_sided").noconvert() = false, py::arg("normals") = py::none(), py::kw_only(), py::arg("uvs") = py::none(),
           py::arg("kd") = py::none(), py::arg("ks") = py::none(), py::arg("ns") = py::none(),
           py::arg("texture") = py::none(), py::arg("alpha") = py::none(), DOC(refracta, add_mesh))
      .def("add_obj",
           [](RenderScene& s, const FilePath& path, const py::object& offset, const py::object& scale,
              const py::object& options, const py::object& texture_dirs, const py::object& missing_textures,
              const py::object& progress) {
             using namespace py::literals;
             const py::dict fields("offset"_a = offset, "scale"_a = scale, "texture_dirs"_a = texture_dirs,
                                   "missing_textures"_a = missing_textures);
             const ObjOptions settings = obj_options(options, fields, progress);
             std::vector<MaterialMesh> parts;
             {
               py::gil_scoped_release release;  // a 2.4 M-triangle OBJ parses for 4 s (a trial)
               parts = load_obj(path.string());
             }
             return add_loaded_obj(s, std::move(parts), path.string(), settings);
           },
           py::arg("path"), py::arg("offset") = py::none(), py::arg("scale") = py::none(), py::kw_only(),
           py::arg("options") = py::none(), py::arg("texture_dirs") = py::none(),
           py::arg("missing_textures") = py::none(), py::arg("progress") = true, DOC(refracta, add_obj))
      .def("add_ground",
           [](RenderScene& s, double height, double size, const py::object& material, const py::object& kd,
              const py::object& ks, const py::object& ns, std::optional<FilePath> texture,
              std::optional<double> texture_size) {
             return add_ground(s, height, size, look_of({material, py::none(), kd, ks, ns, py::none(), texture, false}), texture_size);
           },
           py::arg("height") = 0.0, py::arg("size") = 20000.0, py::arg("material") = py::none(),
           py::arg("kd") = py::none(), py::arg("ks") = py::none(), py::arg("ns") = py::none(), py::kw_only(),
           py::arg("texture") = py::none(), py::arg("texture_size") = py::none(), DOC(refracta, add_ground))
      .def("add_billboard",
           [](RenderScene& s, const py::object& centre, double width, double height, const FilePath& texture,
              const py::object& facing, const py::object& kd) {
             return add_billboard(s, to_point(centre, "centre"), width, height, texture.string(), to_point(facing, "facing"),
                                  to_optional_rgb(kd, "kd"));
           },
           py::arg("centre"), py::arg("width"), py::arg("height"), py::arg("texture"),
           py::arg("facing") = py::make_tuple(-1.0, 0.0, 0.0), py::arg("kd") = py::none(), DOC(refracta, add_billboard))
      .def("add_box",
           [](RenderScene& s, const py::object& centre, const py::object& size, const py::object& material,
              const py::object& emission, const py::object& kd, const py::object& ks, const py::object& ns,
              const py::object& alpha) {
             return add_box(s, to_point(centre, "centre"), to_point(size, "size"),
                            look_of({material, emission, kd, ks, ns, alpha, std::nullopt, false}));
           },
           py::arg("centre"), py::arg("size"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::kw_only(), py::arg("kd") = py::none(), py::arg("ks") = py::none(), py::arg("ns") = py::none(),
           py::arg("alpha") = py::none(), DOC(refracta, add_box))
      .def("add_sphere",
           [](RenderScene& s, const py::object& centre, double radius, const py::object& material,
              const py::object& emission, const py::object& kd, const py::object& ks, const py::object& ns) {
             return add_sphere(s, to_point(centre, "centre"), radius, look_of({material, emission, kd, ks, ns, py::none(), std::nullopt, false}));
           },
           py::arg("centre"), py::arg("radius"), py::arg("material") = py::none(), py::arg("emission") = py::none(),
           py::kw_only(), py::arg("kd") = py::none(), py::arg("ks") = py::none(), py::arg("ns") = py::none(),
           DOC(refracta, add_sphere));
}

// A box's (lower, upper) corners as arrays (3,).
std::tuple<DoubleArray, DoubleArray> box_tuple(const std::pair<Vec3d, Vec3d>& box) {
  return {vector_to_array(box.first), vector_to_array(box.second)};
}

void bind_scene_queries(py::class_<RenderScene, std::shared_ptr<RenderScene>>& scene) {
  scene.def_property_readonly("geometry_count", [](const RenderScene& s) { return s.geometry.geometry_count(); })
      .def("__repr__",
           [](const RenderScene& s) {
             return concat("Scene(geometry_count=", s.geometry.geometry_count(), ", lights=", s.lights().size(),
                           ", aerial_perspective=", s.aerial_perspective() ? "True" : "False", ")");
           })
      .def_property_readonly(
          "bounds",
          [](const RenderScene& s) { return box_tuple(scene_bounds(s)); },
          "(lower, upper): corners (3,) [m] of the axis-aligned box around every geometry (spheres\n"
          "exact; a ground counts at its full size). ValueError for an empty scene.")
      .def_property_readonly(
          "object_bounds",
          [](const RenderScene& s) { return box_tuple(framing_bounds(s)); },
          "(lower, upper) of the scene's objects, as Camera.framing frames them: flat horizontal surfaces\n"
          "(a ground, a sea) count only when there is nothing else. ValueError for an empty scene.")
      .def_property_readonly(
          "ground_bounds",
          [](const RenderScene& s) -> std::optional<std::tuple<DoubleArray, DoubleArray>> {
            if (const auto box = ground_bounds(s)) return box_tuple(*box);
            return std::nullopt;
          },
          "(lower, upper) of the scene's ground or sea: its flat horizontal surfaces when they reach outside\n"
          "the other geometry or are all it holds, else None (a floor inside a room's walls, a scene of\n"
          "objects alone); surfaces that emit light are no ground.")
      .def("material",
           [](const RenderScene& s, int geometry) {
             s.geometry.check_geometry(geometry_id(geometry), "material");
             return std::const_pointer_cast<Material>(s.material_ptr(s.geometry.material(unsigned(geometry))));
           },
           py::arg("geometry"),
           "The material of a geometry (an id returned by add_*), as a refracta.shading object (a material\n"
           "with a texture file: the scene's copy, its file registered here).")
      .def("set_material",
           [](RenderScene& s, int geometry, const py::object& given) {
             set_geometry_material(s, geometry, to_material(given, "set_material: "));
           },
           py::arg("geometry"), py::arg("material"),
           "Give a geometry (an id returned by add_*, e.g. one part of add_obj) another refracta.shading material.\n"
           "Its emission, if any, stays. Not while a render of this scene runs (RuntimeError).")
      .def("remove", [](RenderScene& s, int geometry) { s.remove(geometry_id(geometry)); }, py::arg("geometry"),
           "Remove a geometry (an id returned by add_*, e.g. an OBJ's terrain) and the area light it emits.\n"
           "The other ids stay valid (a removed id is not reused; geometry_count still counts it); the\n"
           "acceleration structure is rebuilt before the next render. Not while a render of this scene runs.")
      .def("intersect",
           [](const RenderScene& s, const py::object& origin, const py::object& direction) -> py::object {
             const auto hit = intersect_ray(s, to_point(origin, "origin"), to_point(direction, "direction"));
             if (!hit) return py::none();
             return py::make_tuple(vector_to_array(hit->point), hit->t, hit->geometry);
           },
           py::arg("origin"), py::arg("direction"),
           "First hit of a straight ray: (point, distance, geometry id), or None.")
      .def("terrain_height", &terrain_height, py::arg("x"), py::arg("z"),
           "The scene height y [m] of the highest terrain surface (add_terrain's) over scene point (x, z), or\n"
           "None where none lies there; other geometry above it is looked through. An eye 1.7 m above the\n"
           "ground there, in scene coordinates: Camera((x, scene.terrain_height(x, z) + 1.7, z), ...). Over a\n"
           "geo.LocalFrame's curved Earth y is the flat frame's, short of the height above the ellipsoid by\n"
           "h^2 / R (3.9 m at 5 000 m) that frame.camera and Camera.geographic take: use\n"
           "frame.ground_height(scene, (lat, lon)) there.")
      .def("_dark_enclosure", [](const RenderScene& s, const py::object& eye) { return dark_enclosure(s, to_point(eye, "eye")); },
           py::arg("eye"), DOC(refracta, dark_enclosure))
      // Pickled as its content (pickle_state.h): meshes, materials, lights, texture paths.
      .def(py::pickle(&scene_state, &scene_from_state));
}

}  // namespace

void bind_obj_options(py::module_& m) {
  using O = ObjOptions;
  py::class_<O> cls(m, "ObjOptions", DOC(refracta, ObjOptions));
  def_options_common<O>(cls, "ObjOptions");
  cls.def_property(
         "offset", [](const O& o) { return py::make_tuple(o.offset.x(), o.offset.y(), o.offset.z()); },
         [](O& o, const py::object& v) { o.offset = to_point(v, "offset"); }, DOC(refracta, ObjOptions, offset))
      .def_readwrite("scale", &O::scale, DOC(refracta, ObjOptions, scale))
      .def_property(
          "texture_dirs", [](const O& o) { return o.texture_dirs; },
          [](O& o, const py::object& v) { o.texture_dirs = to_folders(v); }, DOC(refracta, ObjOptions, texture_dirs));
  def_enum_property(cls, "missing_textures", &O::missing_textures, missing_textures_name, missing_textures_from,
                    DOC(refracta, ObjOptions, missing_textures));
}

void bind_scene(py::module_& m) {
  register_texture_not_found(m);
  bind_obj_options(m);
  py::class_<RenderScene, std::shared_ptr<RenderScene>> scene(m, "Scene", DOC(refracta, RenderScene));
  scene.def(py::init<>());
  m.attr("_SCENE_REACH") = kSceneReach;  // [m] how far from the origin scene coordinates may lie
  bind_scene_geometry(scene);
  bind_scene_queries(scene);
  bind_scene_lights(scene);
  bind_camera(m);
  bind_image_io(m);
  bind_ocean(m);  // OceanWaves and Scene.add_sea
  bind_terrain(m);  // Scene._add_terrain_grid (refracta.terrain: Scene.add_terrain)
}

}  // namespace refracta
