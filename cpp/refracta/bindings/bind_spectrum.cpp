// Python bindings of spectral colour (shading/spectrum_batch.h) and the physical sky (sky_batch.h):
// private _core functions wrapped by python/refracta/spectrum.py (which documents and shapes them).
#include "generated/docstrings.h"
#include "refracta/bindings/bind_shading.h"
#include "refracta/core/spectrum.h"
#include "refracta/shading/sky_batch.h"
#include "refracta/shading/sky_presets.h"  // SunDisc

#include <pybind11/eigen.h>

namespace refracta {

namespace {

// In nm: below 1 nm a value is a unit mistake (0.55: micrometres), not a wavelength whose colour is
// 0 (what the colour functions returned for it).
std::vector<double> wavelengths(const py::handle& object) {
  std::vector<double> values = to_values(object, "wavelengths");
  for (double x : values) {
    if (!(x >= 1.0)) {
      throw_invalid("wavelengths are in nm and must be >= 1 (got ", x, x > 0.0 ? ": micrometres?)" : ")");
    }
  }
  return values;
}
// The sky's spectra are tabulated over the rendered range: outside it a ValueError, not 0.
std::vector<double> sky_wavelengths(const py::handle& object) {
  std::vector<double> values = to_values(object, "wavelengths");
  for (double x : values) checked_wavelength(x, "wavelengths");
  return values;
}

void bind_spectrum_functions(py::module_& m) {
  m.def(
      "_spectrum_rgb_to_spectrum",
      [](const py::object& rgb, const py::object& lambda, const std::string& kind, const std::string& method) {
        return spectral::rgb_to_spectrum(to_points(rgb, "rgb"), wavelengths(lambda), color_kind_from(kind),
                                         spectral::upsampling_from(method));
      },
      py::arg("rgb"), py::arg("wavelengths"), py::arg("kind"), py::arg("method"), "Rows of spectra (spectrum.py).");
  m.def(
      "_spectrum_coefficients",
      [](const py::object& rgb, const std::string& method) {
        return spectral::reflectance_coefficients(to_points(rgb, "rgb"), spectral::upsampling_from(method));
      },
      py::arg("rgb"), py::arg("method"), "Rows of (c0, c1, c2, residual) (spectrum.py).");
  m.def(
      "_spectrum_tabulated_to_rgb",
      [](const py::object& lambda, const py::object& values, const std::string& kind) {
        return Color::tabulated(wavelengths(lambda), to_values(values, "values"), color_kind_from(kind)).rgb();
      },
      py::arg("wavelengths"), py::arg("values"), py::arg("kind"), "RGB of a tabulated spectrum (spectrum.py).");
  m.def(
      "_spectrum_blackbody",
      [](double temperature, const py::object& lambda, std::optional<double> luminance) {
        return spectral::blackbody(temperature, wavelengths(lambda), luminance);
      },
      py::arg("temperature"), py::arg("wavelengths"), py::arg("luminance"), "Planck's law (spectrum.py).");
  m.def(
      "_spectrum_cie_xyz", [](const py::object& lambda) { return spectral::cie_xyz(wavelengths(lambda)); },
      py::arg("wavelengths"), "The CIE 1931 functions (spectrum.py).");
  m.def(
      "_spectrum_d65",
      [](const py::object& lambda, bool normalised) { return spectral::d65(wavelengths(lambda), normalised); },
      py::arg("wavelengths"), py::arg("normalised").noconvert(), "D65 (spectrum.py).");
  m.def("_spectrum_cie_y_integral", &spectral::cie_y_integral, "integral y (spectrum.py).");
  m.def(
      "_spectrum_xyz_to_linear_srgb",
      [](const py::object& xyz) { return spectral::xyz_to_linear_srgb(to_points(xyz, "xyz")); }, py::arg("xyz"),
      "XYZ rows to linear sRGB (spectrum.py).");
  m.def(
      "_spectrum_sample_wavelengths",
      [](const py::object& u, bool terminate) { return spectral::sample_wavelengths(to_values(u, "u"), terminate); },
      py::arg("u"), py::arg("terminate").noconvert(), "Hero wavelengths and pdfs (spectrum.py).");
  m.def(
      "_spectrum_to_linear_srgb",
      [](const py::object& radiance, const py::object& lambda, const py::object& pdf) {
        return spectral::to_linear_srgb(to_rows4(radiance, "radiance"), to_rows4(lambda, "wavelengths"),
                                        to_rows4(pdf, "pdf"));
      },
      py::arg("radiance"), py::arg("wavelengths"), py::arg("pdf"), "The spectral estimate's RGB (spectrum.py).");
  m.def(
      "_spectrum_measure_table",
      [](int resolution, int quadrature_step_nm, int polish_steps, int samples, unsigned seed) {
        const spectral::TableMeasurement t = [&] {
          py::gil_scoped_release release;
          return spectral::measure_table(resolution, quadrature_step_nm, polish_steps, samples, seed);
        }();
        return py::dict(py::arg("build_seconds") = t.build_seconds, py::arg("max_error") = t.max_error,
                        py::arg("mean_error") = t.mean_error, py::arg("worst_fit_residual") = t.worst_fit_residual,
                        py::arg("lookup_seconds") = t.lookup_seconds);
      },
      py::arg("resolution"), py::arg("quadrature_step_nm"), py::arg("polish_steps"), py::arg("samples"),
      py::arg("seed"), "Builds and measures a coefficient table (spectrum.py).");
}

void bind_physical_sky(py::module_& m) {
  const PhysicalSkySettings defaults;
  py::class_<PhysicalSkyLight, std::shared_ptr<PhysicalSkyLight>>(m, "PhysicalSky", DOC(refracta, PhysicalSkyLight))
      .def(py::init([](const py::object& sun, std::optional<double> aerosol, double ozone_du, double ground_albedo, double altitude,
                       double rayleigh_scale, const std::string& below_horizon, std::optional<double> visibility,
                       bool multiple_scattering) {
             const PhysicalSkySettings s = sky_settings(to_point(sun, "sun_direction"), aerosol, ozone_du, ground_albedo,
                                                        altitude, rayleigh_scale, below_horizon, visibility, multiple_scattering);
             if (const auto caveat = fog_caveat(s)) warn("PhysicalSky: " + *caveat);
             py::gil_scoped_release release;
             return std::make_shared<PhysicalSkyLight>(s);
           }),
           py::arg("sun_direction"), py::arg("aerosol") = py::none(), py::arg("ozone_du") = defaults.ozone_du,
           py::arg("ground_albedo") = defaults.ground_albedo, py::arg("altitude") = defaults.altitude,
           py::arg("rayleigh_scale") = defaults.rayleigh_scale, py::kw_only(), py::arg("below_horizon") = "ground",
           py::arg("visibility") = py::none(), py::arg("multiple_scattering").noconvert() = defaults.multiple_scattering)
      .def_property_readonly("aerosol", [](const PhysicalSkyLight& l) { return l.settings().aerosol; },
                             "The Mie density scale (set from `visibility` when that was given).")
      .def("radiance",
           [](const PhysicalSkyLight& l, const py::object& dirs, const py::object& lambda, bool direct) {
             return sky_radiance(l.sky(), to_unit_vectors(dirs, "dirs"), sky_wavelengths(lambda), direct);
           },
           py::arg("dirs"), py::arg("wavelengths"), py::arg("direct").noconvert() = false, DOC(refracta, sky_radiance))
      .def("rgb_radiance",
           [](const PhysicalSkyLight& l, const py::object& dirs) {
             return sky_rgb_radiance(l.sky(), to_unit_vectors(dirs, "dirs"));
           },
           py::arg("dirs"), DOC(refracta, sky_rgb_radiance))
      .def("sun_transmittance",
           [](const PhysicalSkyLight& l, const py::object& lambda) {
             return per_value(lambda, "wavelengths", [&](double x) {
               return l.sky().sun_transmittance(checked_wavelength(x, "wavelengths"));
             });
           },
           py::arg("wavelengths"), DOC(refracta, PhysicalSky, sun_transmittance))
      .def("sun_radiance",
           [](const PhysicalSkyLight& l, const py::object& lambda, double diameter) {
             return per_value(lambda, "wavelengths", [&](double x) {
               return l.sky().sun_radiance(checked_wavelength(x, "wavelengths"), diameter);
             });
           },
           py::arg("wavelengths"), py::arg("angular_diameter_deg") = SunDisc().angular_diameter, DOC(refracta, PhysicalSky, sun_radiance))
      .def("sun_radiance_rgb", [](const PhysicalSkyLight& l, double d) { return l.sky().sun_radiance_rgb(d); },
           py::arg("angular_diameter_deg") = SunDisc().angular_diameter, DOC(refracta, PhysicalSky, sun_radiance_rgb))
      .def_static("solar_irradiance",
                  [](const py::object& lambda) {
                    return per_value(lambda, "wavelengths", &PhysicalSky::solar_irradiance);
                  },
                  py::arg("wavelengths"), DOC(refracta, PhysicalSky, solar_irradiance))
      .def("rayleigh_optical_depth", [](const PhysicalSkyLight& l, double x) { return l.sky().rayleigh_optical_depth(x); },
           py::arg("wavelength"), DOC(refracta, PhysicalSky, rayleigh_optical_depth))
      .def("optical_depth", [](const PhysicalSkyLight& l, double x) { return l.sky().optical_depth(x); },
           py::arg("wavelength"), DOC(refracta, PhysicalSky, optical_depth))
      .def("sample_li",
           [](const PhysicalSkyLight& l, const py::object& u) { return sample_sky(l, to_sample_rows(u, "u", 2)); },
           py::arg("u"), DOC(refracta, sample_sky))
      .def("pdf_li",
           [](const PhysicalSkyLight& l, const py::object& dirs) { return sky_pdf(l, to_unit_vectors(dirs, "dirs")); },
           py::arg("dirs"), DOC(refracta, sky_pdf))
      .def("power", &PhysicalSkyLight::power)
      .def("preprocess", [](PhysicalSkyLight& l, const py::object& c, double r) { l.preprocess(to_point(c, "centre"), r); },
           py::arg("centre"), py::arg("radius"))
      .def_property_readonly("build_seconds", [](const PhysicalSkyLight& l) { return l.sky().build_seconds(); })
      .def("__repr__", &PhysicalSkyLight::describe)
      // Pickled as its settings; unpickling rebuilds the sky's table (1-3 s).
      .def(py::pickle([](const PhysicalSkyLight& l) { return sky_state(l.settings()); },
                      [](const PhysicalSkyState& state) {
                        const PhysicalSkySettings s = sky_settings_from_state(state);
                        py::gil_scoped_release release;
                        return std::make_shared<PhysicalSkyLight>(s);
                      }));
}

void bind_aerial_perspective(py::module_& m) {
  py::class_<AerialPerspective, std::shared_ptr<AerialPerspective>>(m, "AerialPerspective", DOC(refracta, AerialPerspective))
      .def(py::init([](const std::shared_ptr<PhysicalSkyLight>& sky, double scale) {
             if (!sky) throw_invalid("sky must be a refracta.spectrum.PhysicalSky");
             return std::make_shared<AerialPerspective>(PhysicalSky::shared(sky->settings()), scale);
           }),
           py::arg("sky"), py::arg("scale") = 1.0)
      .def("__repr__",
           [](const AerialPerspective& air) { return concat("AerialPerspective(scale=", air.scale(), ")"); })
      .def("along",
           [](const AerialPerspective& air, const py::object& a, const py::object& b, double wavelength, double earth_radius) {
             return air.along_at(to_point(a, "a"), to_point(b, "b"), AirFrame{earth_radius}, wavelength);
           },
           py::arg("a"), py::arg("b"), py::arg("wavelength"), py::arg("earth_radius") = AirFrame{}.earth_radius,
           "(transmittance, in-scatter [W/(m^2 sr nm)] x scale) at one wavelength [nm] in [360, 830].")
      .def("along_rgb",
           [](const AerialPerspective& air, const py::object& a, const py::object& b, double earth_radius) {
             return along_rgb(air, to_point(a, "a"), to_point(b, "b"), earth_radius);
           },
           py::arg("a"), py::arg("b"), py::arg("earth_radius") = AirFrame{}.earth_radius,
           "(transmittance, in-scatter) as RGB renders apply them: linear sRGB, the sky's Le convention.")
      .def("inscatter_reference",
           [](const AerialPerspective& air, const py::object& a, const py::object& b, double wavelength, int steps,
              double earth_radius) {
             const Vec3d pa = to_point(a, "a"), pb = to_point(b, "b");
             py::gil_scoped_release release;
             return air.inscatter_reference(pa, pb, AirFrame{earth_radius}, wavelength, steps);
           },
           py::arg("a"), py::arg("b"), py::arg("wavelength"), py::arg("steps") = 4096,
           py::arg("earth_radius") = AirFrame{}.earth_radius,
           "The same in-scatter by brute force: `steps` midpoints on the chord, each point's sun column traced.")
      .def("sun_transmittance",
           [](const AerialPerspective& air, double height, double elevation_deg, double wavelength) {
             return air.sun_transmittance(height, degrees_to_radians(elevation_deg), wavelength);
           },
           py::arg("height"), py::arg("elevation_deg"), py::arg("wavelength"),
           "The sun's transmittance to `height` [m] above sea level where it stands `elevation_deg` above the local horizon.")
      .def_property_readonly("scale", &AerialPerspective::scale)
      // Pickled as its sky's settings and scale; unpickling rebuilds the tables.
      .def(py::pickle([](const AerialPerspective& air) {
                        return std::make_pair(sky_state(air.sky().settings()), air.scale());
                      },
                      [](const std::pair<PhysicalSkyState, double>& state) {
                        const PhysicalSkySettings s = sky_settings_from_state(state.first);
                        py::gil_scoped_release release;
                        return std::make_shared<AerialPerspective>(PhysicalSky::shared(s), state.second);
                      }));
}

}  // namespace

void bind_spectrum(py::module_& m) {
  bind_spectrum_functions(m);
  bind_physical_sky(m);
  bind_aerial_perspective(m);
}

}  // namespace refracta
