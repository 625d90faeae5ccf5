// Python bindings of the wind sea's waves (scene/ocean_waves.h): refracta.OceanWaves and
// Scene.add_sea, which pairs the displaced mesh with Water materials that keep the slopes it does
// not resolve (shading/water_surface.h). Called by bind_scene, after Scene is bound.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"

#include "refracta/render/scene_building.h"
#include "refracta/scene/ocean_waves.h"
#include "refracta/shading/water_surface.h"

#include <memory>
#include <optional>

namespace refracta {

namespace {

// OceanWaves(...): the parameters, checked by OceanWaves (the seed's sign here: it is unsigned there).
std::shared_ptr<OceanWaves> make_waves(double wind_speed, const py::handle& wind_direction, double patch_size,
                                       int resolution, long long seed, double time) {
  if (seed < 0) throw_invalid("OceanWaves: seed must be >= 0 (got ", seed, ")");
  const OceanWavesParameters p{wind_speed, to_vec2(wind_direction, "wind_direction"), patch_size, resolution,
                               uint64_t(seed), time};
  return std::make_shared<OceanWaves>(p);
}

// A field over the nodes as an array (N, N) or, with two components per node, (N, N, 2).
py::array_t<double> grid_array(const OceanWaves& waves, const std::vector<double>& values, py::ssize_t components) {
  const py::ssize_t n = waves.resolution();
  if (components == 1) return py::array_t<double>({n, n}, values.data());
  return py::array_t<double>({n, n, components}, values.data());
}

}  // namespace

void bind_ocean(py::module_& m) {
  const OceanWavesParameters defaults;
  const double default_wind = WaterParameters{}.wind_speed;
  py::class_<OceanWaves, std::shared_ptr<OceanWaves>>(m, "OceanWaves", DOC(refracta, OceanWaves))
      .def(py::init([](double wind_speed, const py::handle& wind_direction, double patch_size, int resolution,
                       long long seed, double time) {
             auto waves = make_waves(wind_speed, wind_direction, patch_size, resolution, seed, time);
             if (const auto caveat = waves->patch_caveat()) warn(*caveat);  // made, not unpickled
             return waves;
           }),
           py::arg("wind_speed") = default_wind,
           py::arg("wind_direction") = py::make_tuple(defaults.wind_direction.x(), defaults.wind_direction.y()),
           py::arg("patch_size") = defaults.patch_size, py::arg("resolution") = defaults.resolution,
           py::arg("seed") = defaults.seed, py::arg("time") = defaults.time)
      .def_property_readonly("wind_speed", &OceanWaves::wind_speed, "[m/s]")
      .def_property_readonly("wind_direction", [](const OceanWaves& w) { return py::make_tuple(w.wind_direction().x(), w.wind_direction().y()); },
                             "Unit (x, z).")
      .def_property_readonly("patch_size", &OceanWaves::patch_size, "[m]")
      .def_property_readonly("resolution", &OceanWaves::resolution)
      .def_property_readonly("seed", &OceanWaves::seed)
      .def_property_readonly("time", &OceanWaves::time, "[s]")
      .def_property_readonly("spacing", &OceanWaves::spacing, "patch_size / resolution [m]")
      .def_property_readonly("wind_length", &OceanWaves::wind_length, "L_w = U^2 / g [m]")
      .def_property_readonly("significant_wave_height", &OceanWaves::significant_wave_height,
                             "Pierson-Moskowitz H_s = 0.21 U^2 / g [m] (the spectrum's 4 sigma_h)")
      .def_property_readonly_static("phillips_a", [](const py::object&) { return OceanWaves::kPhillipsA; },
                                    "Phillips' A = 2 (0.21 / 4)^2 / pi.")
      .def("spectrum", [](const OceanWaves& w, const py::object& kx, const py::object& kz) {
             return py::vectorize([&w](double x, double z) { return w.spectrum(Vec2d(x, z)); })(real_array(kx, "kx"), real_array(kz, "kz"));
           },
           py::arg("kx"), py::arg("kz"), "Phi(k) [m^4] at wavenumbers kx, kz [rad/m] (vectorised).")
      .def_property_readonly("spectrum_height_variance", &OceanWaves::spectrum_height_variance,
                             "The whole spectrum's integral (H_s / 4)^2 [m^2].")
      .def_property_readonly("expected_height_variance", &OceanWaves::expected_height_variance,
                             "sum of Phi dk^2 over the synthesised modes [m^2]: the field's expected variance.")
      .def_property_readonly("expected_slope_variance", &OceanWaves::expected_slope_variance,
                             "sum of k^2 Phi dk^2 over the synthesised modes: the expected mean-square slope.")
      .def_property_readonly("height_variance", &OceanWaves::height_variance, "This field's variance over the nodes [m^2].")
      .def_property_readonly("slope_variance", &OceanWaves::slope_variance,
                             "This field's mean of (dh/dx)^2 + (dh/dz)^2 over the nodes.")
      .def("heights", [](const OceanWaves& w) { return grid_array(w, w.heights(), 1); }, "(N, N) heights [m], [j, i].")
      .def("slopes", [](const OceanWaves& w) { return grid_array(w, w.slopes(), 2); }, "(N, N, 2) (dh/dx, dh/dz), [j, i].")
      .def("__repr__", &OceanWaves::describe)
      .def(py::pickle(
          [](const OceanWaves& w) {
            return py::make_tuple(w.wind_speed(), py::make_tuple(w.parameters().wind_direction.x(), w.parameters().wind_direction.y()),
                                  w.patch_size(), w.resolution(), w.seed(), w.time());
          },
          [](const py::tuple& t) {
            if (t.size() != 6) throw_invalid("OceanWaves: bad pickle state");
            return make_waves(t[0].cast<double>(), t[1], t[2].cast<double>(), t[3].cast<int>(), t[4].cast<long long>(), t[5].cast<double>());
          }));

  const SeaLayout layout_defaults;
  auto scene = py::reinterpret_borrow<py::class_<RenderScene, std::shared_ptr<RenderScene>>>(m.attr("Scene"));
  scene.def("add_sea",
            [](RenderScene& s, const std::optional<std::shared_ptr<OceanWaves>>& waves, double height, double size,
               const py::object& material, double detail_radius, const py::object& centre) {
              const SeaLayout layout{height, size, detail_radius, to_vec2(centre, "centre")};
              std::shared_ptr<OceanWaves> sea = waves.value_or(nullptr);
              const bool made_here = !sea;
              auto ids = add_sea(s, sea, layout, material.is_none() ? nullptr : to_material(material, ""));
              if (const auto caveat = made_here ? sea->patch_caveat() : std::nullopt) warn("add_sea: " + *caveat);
              return ids;
            },
            py::arg("waves") = py::none(), py::arg("height") = layout_defaults.height, py::arg("size") = layout_defaults.size,
            py::arg("material") = py::none(), py::arg("detail_radius") = layout_defaults.detail_radius,
            py::arg("centre") = py::make_tuple(layout_defaults.centre.x(), layout_defaults.centre.y()),
            DOC(refracta, add_sea));
}

}  // namespace refracta
