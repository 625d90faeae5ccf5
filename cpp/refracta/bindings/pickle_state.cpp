// Pickle states of colours, meshes and scenes (pickle_state.h).
#include "refracta/bindings/pickle_state.h"

#include "refracta/shading/physical_sky.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <filesystem>
#include <string>

namespace refracta {

namespace {

// The version of the Scene state (bump when its layout changes; older states are refused).
constexpr int kSceneStateVersion = 4;  // 2: aerial perspective; 3: cut-outs; 4: masks, lights as objects

void check_size(const py::tuple& t, size_t size, const char* what) {
  if (t.size() != size) throw_invalid(what, ": bad pickle state (", t.size(), " items, expected ", size, ")");
}

}  // namespace

LightPtr light_from(const py::handle& object) {
  if (py::isinstance<Light>(object)) return py::cast<std::shared_ptr<Light>>(object);
  if (py::isinstance<PhysicalSkyLight>(object)) return py::cast<std::shared_ptr<PhysicalSkyLight>>(object);
  throw_invalid("a light must be a refracta.lights.Light or a refracta.spectrum.PhysicalSky (got ",
                std::string(py::str(py::type::handle_of(object))), ")");
}

py::object light_object(const LightPtr& light) {
  if (auto sky = std::dynamic_pointer_cast<PhysicalSkyLight>(light)) return py::cast(sky);
  return py::cast(light);
}

py::tuple color_state(const Color& color) {
  const Vec3d& rgb = color.rgb();
  py::object table = py::none();
  if (color.table()) table = values_to_array(*color.table());
  return py::make_tuple(int(color.kind()), py::make_tuple(rgb.x(), rgb.y(), rgb.z()), table);
}

Color color_from_state(const py::handle& object) {
  const py::tuple t = py::cast<py::tuple>(object);
  check_size(t, 3, "Color");
  const int kind_id = py::cast<int>(t[0]);
  if (kind_id < 0 || kind_id > int(Color::Kind::kIlluminant)) throw_invalid("Color: bad pickle state (kind ", kind_id, ")");
  const auto kind = Color::Kind(kind_id);
  if (!t[2].is_none()) {
    const std::vector<double> values = py::cast<std::vector<double>>(t[2]);
    std::vector<double> lambda(values.size());
    for (size_t i = 0; i < lambda.size(); ++i) lambda[i] = spectral::kTableMin + double(i);
    return Color::tabulated(lambda, values, kind);
  }
  const Vec3d rgb = to_point(t[1], "Color rgb");
  switch (kind) {
    case Color::Kind::kReflectance: return Color::reflectance(rgb);
    case Color::Kind::kUnbounded: return Color::unbounded(rgb);
    case Color::Kind::kIlluminant: return Color::illuminant(rgb);
  }
  return Color();
}

py::tuple mesh_state(const Mesh& mesh) {
  static_assert(sizeof(Vec2d) == 2 * sizeof(double) && sizeof(mesh.triangles[0]) == 3 * sizeof(int));
  const py::array_t<int> triangles({py::ssize_t(mesh.triangles.size()), py::ssize_t(3)},
                                   mesh.triangles.empty() ? nullptr : mesh.triangles[0].data());
  py::object uvs = py::none(), normals = py::none();
  if (!mesh.uvs.empty()) uvs = DoubleArray({py::ssize_t(mesh.uvs.size()), py::ssize_t(2)}, mesh.uvs[0].data());
  if (!mesh.normals.empty()) normals = points_to_array(mesh.normals);
  return py::make_tuple(points_to_array(mesh.vertices), triangles.attr("astype")("int64"), uvs, normals);
}

Mesh mesh_from_state(const py::handle& object) {
  const py::tuple t = py::cast<py::tuple>(object);
  check_size(t, 4, "Mesh");
  Mesh mesh;
  if (py::len(t[0]) > 0) mesh.vertices = to_points(t[0], "vertices");
  mesh.triangles = to_triangles(t[1], "Mesh triangles", mesh.vertices.size());
  if (!t[2].is_none()) mesh.uvs = to_uvs(t[2], "Mesh uvs", mesh.vertices.size());
  if (!t[3].is_none()) mesh.normals = to_points(t[3], "normals");
  return mesh;
}

py::tuple scene_state(const RenderScene& scene) {
  const Scene& geometry = scene.geometry;
  py::list textures, materials, parts, lights;
  // Absolute paths: a worker may run in another working directory (the files must be there).
  for (int id = 0; id < int(geometry.textures().size()); ++id) {
    textures.append(py::make_tuple(std::filesystem::absolute(geometry.textures().path(id)).string(),
                                   geometry.textures().is_mask(id)));
  }
  for (size_t id = 0; id < scene.material_count(); ++id) {
    materials.append(py::cast(std::const_pointer_cast<Material>(scene.material_ptr(int(id)))));
  }
  for (unsigned g = 0; g < geometry.geometry_count(); ++g) {
    if (geometry.removed(g)) {  // kept as a place: the ids after it stay the same
      parts.append(py::make_tuple("removed"));
    } else if (const Scene::Spheres* spheres = geometry.spheres(g)) {
      parts.append(py::make_tuple("spheres", points_to_array(spheres->centres), values_to_array(spheres->radii),
                                  geometry.material(g)));
    } else if (const TerrainGrid* grid = geometry.terrain(g)) {
      // Positions (rows, cols, 3) float32 with NaN at holes, and the uv map (2, 3).
      py::array_t<float> positions({py::ssize_t(grid->rows()), py::ssize_t(grid->cols()), py::ssize_t(3)});
      const std::vector<float> values = grid->positions_with_holes();
      std::copy(values.begin(), values.end(), positions.mutable_data());
      py::array_t<double> uv({py::ssize_t(2), py::ssize_t(3)});
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 3; ++j) uv.mutable_at(i, j) = grid->uv_from_index()(i, j);
      }
      parts.append(py::make_tuple("terrain", positions, uv, geometry.material(g)));
    } else {
      parts.append(py::make_tuple("mesh", mesh_state(geometry.meshes().at(g).mesh), geometry.material(g),
                                  geometry.cutout(g)));
    }
  }
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    lights.append(py::make_tuple(light_object(scene.lights()[i]), scene.emitter_of(i), scene.shadow_radius(i)));
  }
  return py::make_tuple(kSceneStateVersion, textures, materials, parts, lights, scene.aerial_perspective() != nullptr);
}

std::shared_ptr<RenderScene> scene_from_state(const py::tuple& state) {
  check_size(state, 6, "Scene");
  if (py::cast<int>(state[0]) != kSceneStateVersion) {
    throw_invalid("Scene: pickle state version ", py::cast<int>(state[0]), " (this refracta reads ", kSceneStateVersion, ")");
  }
  auto scene = std::make_shared<RenderScene>();
  Scene& geometry = scene->geometry;
  int expected_id = 0;
  for (const py::handle item : state[1]) {  // Textures::add numbers new textures in turn: the same ids
    const py::tuple entry = py::cast<py::tuple>(item);
    check_size(entry, 2, "Scene texture");
    const std::string path = py::cast<std::string>(entry[0]);
    if (geometry.textures().add(path, py::cast<bool>(entry[1])) != expected_id++) {
      throw_invalid("Scene: bad pickle state (texture '", path, "' listed twice)");
    }
  }
  for (const py::handle material : state[2]) scene->add_material(py::cast<std::shared_ptr<Material>>(material));
  const auto material_id = [&scene](const py::handle& id) {
    const int material = py::cast<int>(id);
    if (material < 0 || size_t(material) >= scene->material_count()) {
      throw_invalid("Scene: bad pickle state (material ", material, " of ", scene->material_count(), ")");
    }
    return material;
  };
  for (const py::handle item : state[3]) {
    const py::tuple part = py::cast<py::tuple>(item);
    const std::string kind = py::cast<std::string>(part[0]);
    if (kind == "spheres") {
      check_size(part, 4, "Scene spheres");
      geometry.add_spheres(to_points(part[1], "centres"), to_values(part[2], "radii"), material_id(part[3]));
    } else if (kind == "mesh") {
      check_size(part, 4, "Scene mesh");
      const unsigned id = geometry.add_mesh(mesh_from_state(part[1]), material_id(part[2]));
      if (const int cutout = py::cast<int>(part[3]); cutout >= 0) geometry.set_cutout(id, cutout);
    } else if (kind == "terrain") {
      check_size(part, 4, "Scene terrain");
      const auto positions = py::cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(part[1]);
      const auto uv = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(part[2]);
      if (positions.ndim() != 3 || positions.shape(2) != 3 || uv.ndim() != 2 || uv.shape(0) != 2 || uv.shape(1) != 3) {
        throw_invalid("Scene: bad pickle state (terrain)");
      }
      Eigen::Matrix<double, 2, 3> uv_from_index;
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 3; ++j) uv_from_index(i, j) = uv.at(i, j);
      }
      std::vector<float> values(positions.data(), positions.data() + positions.size());
      geometry.add_terrain(std::make_shared<const TerrainGrid>(int(positions.shape(0)), int(positions.shape(1)),
                                                               std::move(values), uv_from_index),
                           material_id(part[3]));
    } else if (kind == "removed") {  // Scene.remove'd: a stand-in removed again keeps the ids
      Mesh stand_in;
      stand_in.vertices = {Vec3d::Zero(), Vec3d::UnitX(), Vec3d::UnitZ()};
      stand_in.triangles = {{0, 1, 2}};
      geometry.remove(geometry.add_mesh(stand_in, 0));
    } else {
      throw_invalid("Scene: bad pickle state (geometry kind '", kind, "')");
    }
  }
  for (const py::handle item : state[4]) {
    const py::tuple entry = py::cast<py::tuple>(item);
    check_size(entry, 3, "Scene light");
    const size_t index = scene->add_light(light_from(entry[0]), py::cast<int>(entry[1]));
    const double radius = py::cast<double>(entry[2]);
    if (radius > 0.0) scene->set_shadow_radius(index, radius);
  }
  if (py::cast<bool>(state[5])) scene->enable_aerial_perspective();  // rebuilt from the physical sky light
  return scene;
}

}  // namespace refracta
