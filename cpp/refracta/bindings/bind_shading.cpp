// Python bindings of the BSDF library (shared/SHADING.md): bind_shading calls one function per
// part -- the Material interface and BsdfSample (bind_material.cpp), the materials
// (bind_materials.cpp), microfacets, Fresnel and indices (bind_microfacet.cpp) -- and binds the
// sea water here (water.h, water_surface.h).
#include "generated/docstrings.h"
#include "refracta/bindings/bind_shading.h"

#include "refracta/shading/water.h"
#include "refracta/shading/water_surface.h"

namespace refracta {

namespace {

void bind_water(py::module_& m) {
  m.def("water_ior", vectorize_real(&water_ior, {"wavelength_nm", "temperature_c", "salinity"}), py::arg("wavelength_nm"),
        py::arg("temperature_c") = kWaterTableTemperature, py::arg("salinity") = kPureWaterSalinity, vectorised_doc(DOC(refracta, water_ior)).c_str());
  m.def("water_density", vectorize_real(&water_density, {"temperature_c"}), py::arg("temperature_c"),
        vectorised_doc(DOC(refracta, water_density)).c_str());
  m.def("water_absorption", vectorize_real(&water_absorption, {"wavelength_nm"}), py::arg("wavelength_nm"),
        vectorised_doc(DOC(refracta, water_absorption)).c_str());
  m.def("water_backscattering", vectorize_real(&water_backscattering, {"wavelength_nm", "salinity"}),
        py::arg("wavelength_nm"), py::arg("salinity") = kPureWaterSalinity, vectorised_doc(DOC(refracta, water_backscattering)).c_str());
  m.def("water_body_reflectance", vectorize_real(&water_body_reflectance, {"wavelength_nm", "salinity"}),
        py::arg("wavelength_nm"), py::arg("salinity") = kPureWaterSalinity, vectorised_doc(DOC(refracta, water_body_reflectance)).c_str());
  m.def("cox_munk_mean_square_slope", vectorize_real(&cox_munk_mean_square_slope, {"wind_speed"}), py::arg("wind_speed"),
        vectorised_doc(DOC(refracta, cox_munk_mean_square_slope)).c_str());

  // Water.alpha was the roughness, where every other material's alpha is its raster opacity: kept
  // one release, with a warning.
  const auto deprecated_water_alpha = [](const Water& w) {
    if (PyErr_WarnEx(PyExc_DeprecationWarning,
                     "Water.alpha is its roughness and will be its opacity (Material.alpha) in the next release: "
                     "use Water.roughness",
                     1) != 0) {
      throw py::error_already_set();
    }
    return w.roughness();
  };
  const WaterParameters water_defaults;
  def_material<Water>(m, "Water", DOC(refracta, Water),
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
           py::arg("salinity") = water_defaults.salinity, py::arg("body").noconvert() = water_defaults.body,
           py::arg("priority") = water_defaults.priority, py::arg("resolved_slope_variance") = water_defaults.resolved_slope_variance)
      .def_property_readonly("wind_speed", [](const Water& w) { return w.parameters().wind_speed; }, "[m/s] 12.5 m above the sea")
      .def_property_readonly("temperature_c", [](const Water& w) { return w.parameters().temperature_c; }, "[deg C]")
      .def_property_readonly("salinity", [](const Water& w) { return w.parameters().salinity; }, "[g/kg]")
      .def_property_readonly("body", [](const Water& w) { return w.parameters().body; }, "Whether a deep water body is under the surface.")
      .def_property_readonly("mean_square_slope", &Water::mean_square_slope, "Cox & Munk's total sigma^2.")
      .def_property_readonly("resolved_slope_variance", [](const Water& w) { return w.parameters().resolved_slope_variance; },
                             DOC(refracta, WaterParameters, resolved_slope_variance))
      .def_property_readonly("roughness", &Water::roughness,
                             "The Beckmann roughness alpha = sqrt(mean_square_slope - resolved_slope_variance).")
      .def_property_readonly("alpha", deprecated_water_alpha,
                             "Deprecated: the roughness (use Water.roughness); Material.alpha, the raster's opacity, "
                             "is 1 for water.")
      .def("ior", [](const Water& w, const py::object& wavelength) {
             return per_value(wavelength, "wavelength_nm",
                              [&](double x) { return w.ior(checked_wavelength(x, "Water.ior: wavelength_nm")); });
           },
           py::arg("wavelength_nm"), "The water's index relative to vacuum at wavelength_nm [nm] (a number or an array).")
      .def("transmittance", [](const Water& w, const py::object& mu, double wavelength) {
             return per_value(mu, "mu", [&](double x) { return w.transmittance(x, wavelength); });
           },
           py::arg("mu"), py::arg("wavelength_nm") = Ior::kRgbWavelength, DOC(refracta, Water, transmittance))
      .def("internal_reflectance", &Water::internal_reflectance, py::arg("wavelength_nm") = Ior::kRgbWavelength,
           DOC(refracta, Water, internal_reflectance));
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
