// Python bindings of terrain (scene/terrain.h, shading/terrain_shading.h): the array-only
// Scene._add_terrain_grid that refracta.terrain.add_terrain (the public Scene.add_terrain) calls
// after reading files and placing samples, and the TerrainShading material.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/bind_shading.h"

#include "refracta/scene/terrain.h"
#include "refracta/shading/terrain_shading.h"

#include <memory>
#include <vector>

namespace refracta {

void bind_terrain(py::module_& m) {
  auto scene = py::reinterpret_borrow<py::class_<RenderScene, std::shared_ptr<RenderScene>>>(m.attr("Scene"));
  scene.def(
      "_add_terrain_grid",
      [](RenderScene& s, const py::array_t<float, py::array::c_style | py::array::forcecast>& positions,
         const py::object& material, const py::array_t<double, py::array::c_style | py::array::forcecast>& uv_from_index) {
        const std::shared_ptr<Material> terrain_material = to_material(material, "add_terrain: ");
        std::vector<float> values(positions.data(), positions.data() + positions.size());
        std::shared_ptr<const TerrainGrid> grid;
        {
          py::gil_scoped_release release;  // building the grid takes seconds for a large tile
          grid = terrain_grid({positions.shape(), positions.shape() + positions.ndim()}, std::move(values),
                              {uv_from_index.shape(), uv_from_index.shape() + uv_from_index.ndim()},
                              {uv_from_index.data(), uv_from_index.data() + uv_from_index.size()});
        }
        return s.geometry.add_terrain(grid, s.add_material(terrain_material));
      },
      py::arg("positions"), py::arg("material"), py::arg("uv_from_index"),
      "Terrain as Embree grid geometry (private: use Scene.add_terrain). positions: (rows, cols, 3) [m]\n"
      "float32, row-major, rows along +z and columns along +x so the front is up; a sample with a NaN\n"
      "coordinate is a hole. uv_from_index (2, 3): (u, v) = A (col, row, 1). Returns the geometry id.");
}

void bind_terrain_shading(py::module_& m) {
  const TerrainShadingParameters d;
  py::class_<TerrainShading, Material, std::shared_ptr<TerrainShading>> terrain(m, "TerrainShading", DOC(refracta, TerrainShading));
  terrain
      .def(py::init([](double snow_line, double tree_line, double rock_slope, double earth_radius, const py::object& vegetation,
                       const py::object& rock, const py::object& snow) {
             TerrainShadingParameters p;
             p.snow_line = snow_line, p.tree_line = tree_line, p.rock_slope = rock_slope, p.earth_radius = earth_radius;
             p.vegetation = to_rgb(vegetation, "vegetation"), p.rock = to_rgb(rock, "rock"), p.snow = to_rgb(snow, "snow");
             return std::make_shared<TerrainShading>(p);
           }),
           py::arg("snow_line") = d.snow_line, py::arg("tree_line") = d.tree_line, py::arg("rock_slope") = d.rock_slope,
           py::arg("earth_radius") = d.earth_radius, py::kw_only(), py::arg("vegetation") = rgb_tuple(d.vegetation),
           py::arg("rock") = rgb_tuple(d.rock), py::arg("snow") = rgb_tuple(d.snow))
      .def(
          "reflectance",
          [](const TerrainShading& t, double height, double slope) {
            if (!std::isfinite(height)) throw_invalid("TerrainShading.reflectance: height must be finite (got ", height, ")");
            if (!(slope >= 0.0 && slope <= 90.0)) {
              throw_invalid("TerrainShading.reflectance: slope must be in [0, 90] deg (got ", slope, ")");
            }
            return rgb_tuple(t.reflectance(height, slope));
          },
          py::arg("height"), py::arg("slope"),
          "The linear RGB albedo at true height `height` [m] on ground sloping `slope` [deg] in [0, 90].");
  add_parameters<TerrainShading>(terrain, [](const TerrainShading& t) {
    const TerrainShadingParameters& p = t.parameters();
    return py::dict(py::arg("snow_line") = p.snow_line, py::arg("tree_line") = p.tree_line, py::arg("rock_slope") = p.rock_slope,
                    py::arg("earth_radius") = p.earth_radius, py::arg("vegetation") = rgb_tuple(p.vegetation),
                    py::arg("rock") = rgb_tuple(p.rock), py::arg("snow") = rgb_tuple(p.snow));
  });
}

}  // namespace refracta
