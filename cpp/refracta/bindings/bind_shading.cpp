// Python bindings of the BSDF library (shared/SHADING.md): bind_shading calls one function per
// part -- the Material interface and BsdfSample (bind_material.cpp), the materials
// (bind_materials.cpp), microfacets, Fresnel and indices (bind_microfacet.cpp) -- and binds the
// sea water here (water.h, water_surface.h).
#include "refracta/bindings/bind_shading.h"

#include "refracta/shading/water.h"
#include "refracta/shading/water_surface.h"

namespace refracta {

namespace {

void bind_water(py::module_& m) {
  m.def("water_ior", vectorize_real(&water_ior, {"wavelength_nm", "temperature_c", "salinity"}), py::arg("wavelength_nm"), py::arg("temperature_c") = 20.0,
        py::arg("salinity") = 0.0,
        "Refractive index of water relative to vacuum: pure water by IAPWS R9-97 at the density of\n"
        "Tanaka et al. 2001 (atmospheric pressure), plus Quan & Fry 1995's salinity terms. wavelength_nm\n"
        "in [200, 1100], temperature_c in [0, 40] deg C, salinity [g/kg] in [0, 40]. Vectorised.");
  m.def("water_density", vectorize_real(&water_density, {"temperature_c"}), py::arg("temperature_c"),
        "Density of air-free pure water at 101 325 Pa [kg/m^3] (Tanaka et al. 2001), temperature_c in\n"
        "[0, 40] deg C. Vectorised.");
  m.def("water_absorption", vectorize_real(&water_absorption, {"wavelength_nm"}), py::arg("wavelength_nm"),
        "Absorption coefficient of pure water [1/m] at wavelength_nm in [360, 830]: Pope & Fry 1997 (380-725 nm),\n"
        "Smith & Baker 1981 below, Kou et al. 1993 above; linear between 5 nm nodes. Vectorised.");
  m.def("water_backscattering", vectorize_real(&water_backscattering, {"wavelength_nm", "salinity"}), py::arg("wavelength_nm"),
        py::arg("salinity") = 0.0,
        "Backscattering coefficient of pure (sea) water [1/m]: half of Morel 1974's molecular scattering\n"
        "0.00222 (1 + 0.3 S / 37) (lambda / 500)^-4.32, salinity S [g/kg] in [0, 40]. Vectorised.");
  m.def("water_body_reflectance", vectorize_real(&water_body_reflectance, {"wavelength_nm", "salinity"}), py::arg("wavelength_nm"),
        py::arg("salinity") = 0.0,
        "Irradiance reflectance just beneath the surface of deep pure (sea) water, R = 0.33 b_b / (a + b_b)\n"
        "(Morel & Prieur 1977; Gordon et al. 1975), from water_absorption and water_backscattering. Vectorised.");
  m.def("cox_munk_mean_square_slope", vectorize_real(&cox_munk_mean_square_slope, {"wind_speed"}), py::arg("wind_speed"),
        "Total mean-square slope of a clean sea surface, 0.003 + 5.12e-3 U (Cox & Munk 1954), wind_speed U\n"
        "[m/s] 12.5 m above the sea in [0, 30]. The Water material's Beckmann alpha^2. Vectorised.");

  const WaterParameters water_defaults;
  def_material<Water>(m, "Water",
      "The sea: a wind-roughened water surface over a deep water body (water_surface.h).\n\n"
      "The interface is a Beckmann microfacet dielectric (Walter et al. 2007; Mitsuba 3's roughdielectric\n"
      "with distribution='beckmann') whose alpha^2 is Cox & Munk 1954's total mean-square slope\n"
      "0.003 + 5.12e-3 wind_speed (alpha = 0.17 at 5 m/s) and whose index is water_ior(lambda, temperature_c,\n"
      "salinity): per wavelength in spectral rendering, at 630, 532 and 465 nm per RGB channel (directions\n"
      "sampled at 550 nm). body=True (default): the deep water under it absorbs (Pope & Fry 1997) and\n"
      "backscatters (Morel 1974) the light refracted in and returns R = 0.33 b_b / (a + b_b) of it as\n"
      "isotropic light leaving through the rough interface, T(cos_i) T(cos_o) R / (pi eta^2 (1 - R Fbar_int))\n"
      "(T = transmittance(mu), Fbar_int = internal_reflectance());\n"
      "reflection-only and two-sided, nothing continues below. body=False: the bare interface, reflecting\n"
      "and transmitting, bounding a medium of the water's index (priority for nested dielectrics).\n"
      "Defaults: wind_speed 5 m/s (a gentle breeze), temperature_c 20 deg C, salinity 35 g/kg (the open ocean).\n"
      "resolved_slope_variance: the mean-square slope a displaced wave mesh under it already resolves\n"
      "(Scene.add_sea sets it): alpha^2 = Cox-Munk's total - it, so that resolved + unresolved = total.\n"
      "wind_speed in [0, 30] m/s, temperature_c in [0, 40], salinity in [0, 40] g/kg.",
      py::init([](const py::object& wind_speed, const py::object& temperature_c, const py::object& salinity, bool body,
                  int priority, double resolved) {
        return std::make_shared<Water>(WaterParameters{to_number(wind_speed, "Water: wind_speed"),
                                                       to_number(temperature_c, "Water: temperature_c"),
                                                       to_number(salinity, "Water: salinity"), body, priority, resolved});
      }),
      [](const Water& w) {
        const WaterParameters& p = w.parameters();
        return py::dict(py::arg("wind_speed") = p.wind_speed, py::arg("temperature_c") = p.temperature_c,
                        py::arg("salinity") = p.salinity, py::arg("body") = p.body, py::arg("priority") = p.priority,
                        py::arg("resolved_slope_variance") = p.resolved_slope_variance);
      },
      py::arg("wind_speed") = water_defaults.wind_speed, py::arg("temperature_c") = water_defaults.temperature_c,
           py::arg("salinity") = water_defaults.salinity, py::arg("body") = water_defaults.body,
           py::arg("priority") = water_defaults.priority, py::arg("resolved_slope_variance") = water_defaults.resolved_slope_variance)
      .def_property_readonly("wind_speed", [](const Water& w) { return w.parameters().wind_speed; }, "[m/s] 12.5 m above the sea")
      .def_property_readonly("temperature_c", [](const Water& w) { return w.parameters().temperature_c; }, "[deg C]")
      .def_property_readonly("salinity", [](const Water& w) { return w.parameters().salinity; }, "[g/kg]")
      .def_property_readonly("body", [](const Water& w) { return w.parameters().body; }, "Whether a deep water body is under the surface.")
      .def_property_readonly("mean_square_slope", &Water::mean_square_slope, "Cox & Munk's total sigma^2.")
      .def_property_readonly("resolved_slope_variance", [](const Water& w) { return w.parameters().resolved_slope_variance; },
                             "The mean-square slope a displaced wave mesh already shows (Scene.add_sea); the microfacets keep\n"
                             "alpha^2 = mean_square_slope - resolved_slope_variance.")
      .def_property_readonly("alpha", &Water::alpha, "The Beckmann roughness alpha = sqrt(mean_square_slope - resolved_slope_variance).")
      .def("ior", [](const Water& w, const py::object& wavelength) {
             return per_value(wavelength, "wavelength_nm",
                              [&](double x) { return w.ior(checked_wavelength(x, "Water.ior: wavelength_nm")); });
           },
           py::arg("wavelength_nm"), "The water's index relative to vacuum at wavelength_nm [nm] (a number or an array).")
      .def("transmittance", [](const Water& w, const py::object& mu, double wavelength) {
             return per_value(mu, "mu", [&](double x) { return w.transmittance(x, wavelength); });
           },
           py::arg("mu"), py::arg("wavelength_nm") = Ior::kRgbWavelength,
           "The rough interface's directional transmittance T(mu) from above (the share of the energy arriving at\n"
           "cos theta = mu that crosses into the water), as the water body's term uses it, at the water's index\n"
           "at wavelength_nm under vacuum. Tabulated (33 mu x 5 eta nodes).")
      .def("internal_reflectance", &Water::internal_reflectance,
           py::arg("wavelength_nm") = Ior::kRgbWavelength,
           "Fbar_int = 1 - 2 int T(mu) mu dmu / eta^2: what of isotropic light under the rough surface is sent\n"
           "back down (the flat surface's fresnel_diffuse_reflectance(1 / eta) when alpha -> 0).");
}

}  // namespace

RowMatrixX4d to_rows4(const py::handle& object, const char* what) {
  const DoubleArray a = real_array(object, what);
  if (!((a.ndim() == 1 && a.shape(0) == 4) || (a.ndim() == 2 && a.shape(1) == 4))) {
    throw_invalid(what, " must have shape (4,) or (N, 4)");
  }
  const RowMatrixX4d rows = Eigen::Map<const RowMatrixX4d>(a.data(), a.size() / 4, 4);
  if (!rows.allFinite()) throw_invalid(what, " must be finite");
  return rows;
}

RowMatrixXd to_sample_rows(const py::handle& object, const char* what, int dims) {
  const Samples s = to_samples(object, what, dims);
  return Eigen::Map<const RowMatrixXd>(s.values.data(), Eigen::Index(s.rows), dims);
}

void bind_shading(py::module_& m) {
  bind_material_base(m);
  bind_materials(m);
  bind_water(m);
  bind_microfacet(m);
  bind_terrain_shading(m);
}

}  // namespace refracta
