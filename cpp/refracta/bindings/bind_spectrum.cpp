// Python bindings of spectral colour (shading/color.h, spectral.h) and the physical sky: private
// _core functions wrapped by python/refracta/spectrum.py (which documents and shapes them).
#include "refracta/bindings/bindings.h"
#include "refracta/shading/aerial_perspective.h"
#include "refracta/shading/color.h"
#include "refracta/shading/physical_sky.h"
#include "refracta/shading/spectral.h"

#include <chrono>
#include <random>

namespace refracta {

namespace {

using spectral::Coefficients;

// A C-contiguous float64 array of exactly `ndim` dimensions, the last one of size `last` (0: any).
DoubleArray as_array(const py::handle& object, const char* what, int ndim, py::ssize_t last = 0) {
  DoubleArray array;
  try {
    array = real_array(object, what);
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be a float array");
  }
  if (array.ndim() != ndim || (last > 0 && array.shape(ndim - 1) != last)) {
    throw_invalid(what, " must have ", ndim, " dimensions", last > 0 ? concat(", the last of size ", last) : "",
                  " (got ", array.ndim(), " dimensions)");
  }
  const double* d = array.data();
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    if (!std::isfinite(d[i])) throw_invalid(what, " must be finite (got ", d[i], ")");
  }
  return array;
}

std::vector<Vec3d> unit_directions(const py::handle& object) {
  const DoubleArray a = as_array(object, "dirs", 2, 3);
  std::vector<Vec3d> out(a.shape(0));
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = Vec3d(a.at(i, 0), a.at(i, 1), a.at(i, 2));
    if (std::abs(out[i].norm() - 1.0) > 1e-6) throw_invalid("dirs must be unit vectors (row ", i, " has norm ", out[i].norm(), ")");
  }
  return out;
}

Color::Kind parse_kind(const std::string& kind) {
  if (kind == "reflectance") return Color::Kind::kReflectance;
  if (kind == "unbounded") return Color::Kind::kUnbounded;
  if (kind == "illuminant") return Color::Kind::kIlluminant;
  throw_invalid("kind must be 'reflectance', 'unbounded' or 'illuminant' (got '", kind, "')");
}

py::tuple sky_settings_state(const PhysicalSkySettings& s) {
  return py::make_tuple(py::make_tuple(s.sun_direction.x(), s.sun_direction.y(), s.sun_direction.z()), s.aerosol,
                        s.ozone_du, s.ground_albedo, s.altitude, s.rayleigh_scale, int(s.below_horizon));
}

PhysicalSkySettings sky_settings_from_state(const py::tuple& t) {
  if (t.size() != 7) throw_invalid("PhysicalSky: bad pickle state (", t.size(), " items)");
  PhysicalSkySettings s;
  s.sun_direction = to_point(t[0], "sun_direction");
  s.aerosol = py::cast<double>(t[1]), s.ozone_du = py::cast<double>(t[2]), s.ground_albedo = py::cast<double>(t[3]);
  s.altitude = py::cast<double>(t[4]), s.rayleigh_scale = py::cast<double>(t[5]);
  const int below = py::cast<int>(t[6]);
  if (below != int(BelowHorizon::kGround) && below != int(BelowHorizon::kHorizon)) throw_invalid("PhysicalSky: bad pickle state");
  s.below_horizon = BelowHorizon(below);
  return s;
}

}  // namespace

void bind_spectrum(py::module_& m) {
  m.def(
      "_spectrum_rgb_to_spectrum",
      [](const py::object& rgb_object, const py::object& lambda_object, const std::string& kind_name,
         const std::string& method) {
        const DoubleArray rgb = as_array(rgb_object, "rgb", 2, 3);
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
        const Color::Kind kind = parse_kind(kind_name);
        if (method != "fit" && method != "table") throw_invalid("method must be 'fit' or 'table' (got '", method, "')");
        if (method == "table" && kind != Color::Kind::kReflectance) throw_invalid("method='table' serves reflectances only");
        const py::ssize_t n = rgb.shape(0), k = lambda.shape(0);
        DoubleArray out({n, k});
        double* o = out.mutable_data();
        for (py::ssize_t i = 0; i < n; ++i) {
          const Vec3d c(rgb.at(i, 0), rgb.at(i, 1), rgb.at(i, 2));
          if (method == "table") {
            for (int d = 0; d < 3; ++d) {
              if (!(c[d] >= 0.0 && c[d] <= 1.0)) throw_invalid("rgb must be in [0, 1] for a reflectance (got ", c[d], ")");
            }
            const Coefficients coefficients = spectral::rgb_to_spectrum_table().coefficients(c);
            for (py::ssize_t j = 0; j < k; ++j) {
              const double l = lambda.at(j);
              o[i * k + j] = l >= kLambdaMin && l <= kLambdaMax ? spectral::sigmoid_polynomial(coefficients, l) : 0.0;
            }
          } else {
            const Color color = kind == Color::Kind::kReflectance ? Color::reflectance(c)
                                : kind == Color::Kind::kUnbounded ? Color::unbounded(c)
                                                                  : Color::illuminant(c);
            for (py::ssize_t j = 0; j < k; ++j) o[i * k + j] = color.evaluate(lambda.at(j));
          }
        }
        return out;
      },
      py::arg("rgb"), py::arg("wavelengths"), py::arg("kind"), py::arg("method"));
  m.def(
      "_spectrum_coefficients",
      [](const py::object& rgb_object, const std::string& method) {
        const DoubleArray rgb = as_array(rgb_object, "rgb", 2, 3);
        if (method != "fit" && method != "table") throw_invalid("method must be 'fit' or 'table' (got '", method, "')");
        const py::ssize_t n = rgb.shape(0);
        DoubleArray out({n, py::ssize_t(4)});
        for (py::ssize_t i = 0; i < n; ++i) {
          const Vec3d c(rgb.at(i, 0), rgb.at(i, 1), rgb.at(i, 2));
          spectral::FitResult fit;
          if (method == "table") {
            for (int d = 0; d < 3; ++d) {
              if (!(c[d] >= 0.0 && c[d] <= 1.0)) throw_invalid("rgb must be in [0, 1] (got ", c[d], ")");
            }
            fit.c = spectral::rgb_to_spectrum_table().coefficients(c);
          } else {
            fit = spectral::fit_reflectance_robust(c);
          }
          for (int d = 0; d < 3; ++d) out.mutable_at(i, d) = fit.c[d];
          out.mutable_at(i, 3) = fit.residual;
        }
        return out;
      },
      py::arg("rgb"), py::arg("method"));
  m.def(
      "_spectrum_tabulated_to_rgb",
      [](const py::object& lambda_object, const py::object& values_object, const std::string& kind) {
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
        const DoubleArray values = as_array(values_object, "values", 1);
        const Color c = Color::tabulated(std::vector<double>(lambda.data(), lambda.data() + lambda.size()),
                                         std::vector<double>(values.data(), values.data() + values.size()),
                                         parse_kind(kind));
        return points_to_array({c.rgb()}).reshape({py::ssize_t(3)});
      },
      py::arg("wavelengths"), py::arg("values"), py::arg("kind"));
  m.def(
      "_spectrum_blackbody",
      [](double temperature, const py::object& lambda_object, std::optional<double> luminance) {
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
        std::vector<double> out(lambda.size());
        if (luminance) {
          const Color c = Color::blackbody(temperature, *luminance);
          for (size_t i = 0; i < out.size(); ++i) out[i] = c.evaluate(lambda.at(i));
        } else {
          for (size_t i = 0; i < out.size(); ++i) out[i] = spectral::planck(lambda.at(i), temperature);
        }
        return values_to_array(out);
      },
      py::arg("temperature"), py::arg("wavelengths"), py::arg("luminance"));
  m.def(
      "_spectrum_cie_xyz",
      [](const py::object& lambda_object) {
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
        std::vector<Vec3d> out(lambda.size());
        for (size_t i = 0; i < out.size(); ++i) out[i] = spectral::cie_xyz(lambda.at(i));
        return points_to_array(out);
      },
      py::arg("wavelengths"));
  m.def(
      "_spectrum_d65",
      [](const py::object& lambda_object, bool normalised) {
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
        std::vector<double> out(lambda.size());
        for (size_t i = 0; i < out.size(); ++i) {
          out[i] = normalised ? spectral::d65_normalised(lambda.at(i)) : spectral::d65(lambda.at(i));
        }
        return values_to_array(out);
      },
      py::arg("wavelengths"), py::arg("normalised"));
  m.def("_spectrum_cie_y_integral", &spectral::cie_y_integral);
  m.def(
      "_spectrum_xyz_to_linear_srgb",
      [](const py::object& xyz_object) {
        const DoubleArray xyz = as_array(xyz_object, "xyz", 2, 3);
        std::vector<Vec3d> out(xyz.shape(0));
        for (size_t i = 0; i < out.size(); ++i) {
          out[i] = spectral::xyz_to_linear_srgb(Vec3d(xyz.at(i, 0), xyz.at(i, 1), xyz.at(i, 2)));
        }
        return points_to_array(out);
      },
      py::arg("xyz"));
  m.def(
      "_spectrum_sample_wavelengths",
      [](const py::object& u_object, bool terminate) {
        const DoubleArray u = as_array(u_object, "u", 1);
        const py::ssize_t n = u.shape(0);
        DoubleArray lambda({n, py::ssize_t(4)}), pdf({n, py::ssize_t(4)});
        for (py::ssize_t i = 0; i < n; ++i) {
          if (!(u.at(i) >= 0.0 && u.at(i) < 1.0)) throw_invalid("u must be in [0, 1) (got ", u.at(i), ")");
          SampledWavelengths w = SampledWavelengths::sample_uniform(u.at(i));
          if (terminate) w.terminate_secondary();
          for (int j = 0; j < 4; ++j) lambda.mutable_at(i, j) = w.lambda[j], pdf.mutable_at(i, j) = w.pdf[j];
        }
        return py::make_tuple(lambda, pdf);
      },
      py::arg("u"), py::arg("terminate"));
  m.def(
      "_spectrum_to_linear_srgb",
      [](const py::object& radiance_object, const py::object& lambda_object, const py::object& pdf_object) {
        const DoubleArray radiance = as_array(radiance_object, "radiance", 2, 4);
        const DoubleArray lambda = as_array(lambda_object, "wavelengths", 2, 4);
        const DoubleArray pdf = as_array(pdf_object, "pdf", 2, 4);
        if (lambda.shape(0) != radiance.shape(0) || pdf.shape(0) != radiance.shape(0)) {
          throw_invalid("radiance, wavelengths and pdf must have the same shape (N, 4)");
        }
        std::vector<Vec3d> out(radiance.shape(0));
        for (size_t i = 0; i < out.size(); ++i) {
          SampledWavelengths w;
          w.spectral = true;
          Spectrum l;
          for (int j = 0; j < 4; ++j) w.lambda[j] = lambda.at(i, j), w.pdf[j] = pdf.at(i, j), l[j] = radiance.at(i, j);
          out[i] = to_linear_srgb(l, w);
        }
        return points_to_array(out);
      },
      py::arg("radiance"), py::arg("wavelengths"), py::arg("pdf"));
  m.def(
      "_spectrum_measure_table",
      [](int resolution, int quadrature_step_nm, int polish_steps, int samples, unsigned seed) {
        py::gil_scoped_release release;
        const spectral::RgbToSpectrumTable table(resolution, quadrature_step_nm, polish_steps);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        double worst = 0.0, sum = 0.0;
        std::vector<double> s(spectral::kTableSamples);
        std::vector<Vec3d> colours(samples);
        for (Vec3d& c : colours) c = Vec3d(uniform(rng), uniform(rng), uniform(rng));
        const auto start = std::chrono::steady_clock::now();
        double sink = 0.0;
        for (const Vec3d& c : colours) sink += table.coefficients(c)[2];
        const double lookup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        for (const Vec3d& rgb : colours) {
          const Coefficients c = table.coefficients(rgb);
          for (int i = 0; i < spectral::kTableSamples; ++i) s[i] = spectral::sigmoid_polynomial(c, spectral::kTableMin + i);
          const double e = (spectral::xyz_to_linear_srgb(spectral::xyz_of_reflectance(s)) - rgb).cwiseAbs().maxCoeff();
          worst = std::max(worst, e), sum += e;
        }
        py::gil_scoped_acquire acquire;
        py::dict out;
        out["build_seconds"] = table.build_seconds();
        out["max_error"] = worst;
        out["mean_error"] = sum / std::max(samples, 1);
        out["worst_fit_residual"] = table.worst_fit_residual();
        out["lookup_seconds"] = lookup / std::max(samples, 1) + 0.0 * sink;
        return out;
      },
      py::arg("resolution"), py::arg("quadrature_step_nm"), py::arg("polish_steps"), py::arg("samples"),
      py::arg("seed"));

  py::class_<PhysicalSkyLight, std::shared_ptr<PhysicalSkyLight>>(m, "PhysicalSky", R"doc(
A single-scattering physical sky (Nishita et al. 1993) through a spherical standard atmosphere:
Rayleigh (lambda^-4, 8 km, tau(550 nm) = 0.097), Mie (1.2 km, Cornette-Shanks g = 0.76, scaled by
`aerosol`), ozone absorption (`ozone_du` Dobson units), a 5778 K sun scaled to 1361 W/m^2.
sun_direction: unit, toward the sun, y up. Radiance in W/(m^2 sr nm); below the horizon, by
below_horizon: 'ground' (default) the ground's Lambertian radiance (ground_albedo), reached by
BSDF sampling only (pdf_li 0); 'horizon' the radiance at the horizon at the same azimuth
(ground_albedo must be 0), sample_li/pdf_li then cover the whole sphere (Scene.set_physical_sky's
default). See cpp/refracta/shading/physical_sky.h.)doc")
      .def(py::init([](const py::object& sun, double aerosol, double ozone_du, double ground_albedo, double altitude,
                       double rayleigh_scale, const std::string& below_horizon, const std::optional<double>& visibility) {
             PhysicalSkySettings s;
             s.sun_direction = to_point(sun, "sun_direction");
             s.aerosol = aerosol, s.ozone_du = ozone_du, s.ground_albedo = ground_albedo, s.altitude = altitude;
             s.rayleigh_scale = rayleigh_scale;
             s.below_horizon = below_horizon_from(below_horizon);
             if (visibility) set_visibility(&s, *visibility);
             py::gil_scoped_release release;
             return std::make_shared<PhysicalSkyLight>(s);
           }),
           py::arg("sun_direction"), py::arg("aerosol") = PhysicalSkySettings{}.aerosol,
           py::arg("ozone_du") = PhysicalSkySettings{}.ozone_du, py::arg("ground_albedo") = PhysicalSkySettings{}.ground_albedo,
           py::arg("altitude") = PhysicalSkySettings{}.altitude, py::arg("rayleigh_scale") = PhysicalSkySettings{}.rayleigh_scale,
           py::arg("below_horizon") = "ground", py::arg("visibility") = py::none())
      .def_property_readonly("aerosol", [](const PhysicalSkyLight& l) { return l.settings().aerosol; },
                             "The Mie density scale (set from `visibility` when that was given).")
      .def("radiance",
           [](const PhysicalSkyLight& l, const py::object& dirs, const py::object& lambda_object, bool direct) {
             const std::vector<Vec3d> d = unit_directions(dirs);
             const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
             const py::ssize_t n = py::ssize_t(d.size()), k = lambda.shape(0);
             DoubleArray out({n, k});
             double* o = out.mutable_data();
             for (py::ssize_t i = 0; i < n; ++i) {
               for (py::ssize_t j = 0; j < k; ++j) {
                 o[i * k + j] = direct ? l.sky().radiance_direct(d[i], lambda.at(j)) : l.sky().radiance(d[i], lambda.at(j));
               }
             }
             return out;
           },
           py::arg("dirs"), py::arg("wavelengths"), py::arg("direct") = false)
      .def("rgb_radiance",
           [](const PhysicalSkyLight& l, const py::object& dirs) {
             std::vector<Vec3d> d = unit_directions(dirs);
             for (Vec3d& v : d) v = l.sky().rgb_radiance(v);
             return points_to_array(d);
           },
           py::arg("dirs"))
      .def("sun_transmittance",
           [](const PhysicalSkyLight& l, const py::object& lambda_object) {
             const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
             std::vector<double> out(lambda.size());
             for (size_t i = 0; i < out.size(); ++i) out[i] = l.sky().sun_transmittance(lambda.at(i));
             return values_to_array(out);
           },
           py::arg("wavelengths"))
      .def("sun_radiance",
           [](const PhysicalSkyLight& l, const py::object& lambda_object, double diameter) {
             const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
             std::vector<double> out(lambda.size());
             for (size_t i = 0; i < out.size(); ++i) out[i] = l.sky().sun_radiance(lambda.at(i), diameter);
             return values_to_array(out);
           },
           py::arg("wavelengths"), py::arg("angular_diameter_deg") = 0.53)
      .def("sun_radiance_rgb",
           [](const PhysicalSkyLight& l, double diameter) {
             return points_to_array({l.sky().sun_radiance_rgb(diameter)}).reshape({py::ssize_t(3)});
           },
           py::arg("angular_diameter_deg") = 0.53)
      .def_static("solar_irradiance",
                  [](const py::object& lambda_object) {
                    const DoubleArray lambda = as_array(lambda_object, "wavelengths", 1);
                    std::vector<double> out(lambda.size());
                    for (size_t i = 0; i < out.size(); ++i) out[i] = PhysicalSky::solar_irradiance(lambda.at(i));
                    return values_to_array(out);
                  },
                  py::arg("wavelengths"))
      .def("rayleigh_optical_depth", [](const PhysicalSkyLight& l, double lambda) { return l.sky().rayleigh_optical_depth(lambda); },
           py::arg("wavelength"))
      .def("optical_depth", [](const PhysicalSkyLight& l, double lambda) { return l.sky().optical_depth(lambda); },
           py::arg("wavelength"))
      .def("sample_li",
           [](const PhysicalSkyLight& l, const py::object& u_object) {
             const DoubleArray u = as_array(u_object, "u", 2, 2);
             const py::ssize_t n = u.shape(0);
             std::vector<Vec3d> dirs(n, Vec3d::Zero()), rgb(n, Vec3d::Zero());
             std::vector<double> pdf(n, 0.0);
             for (py::ssize_t i = 0; i < n; ++i) {
               const auto s = l.sample_li({}, Vec2d(u.at(i, 0), u.at(i, 1)), SampledWavelengths::rgb());
               if (!s) continue;
               dirs[i] = s->wi, pdf[i] = s->pdf, rgb[i] = s->L.head<3>().matrix();
             }
             return py::make_tuple(points_to_array(dirs), values_to_array(pdf), points_to_array(rgb));
           },
           py::arg("u"))
      .def("pdf_li",
           [](const PhysicalSkyLight& l, const py::object& dirs) {
             const std::vector<Vec3d> d = unit_directions(dirs);
             std::vector<double> out(d.size());
             for (size_t i = 0; i < out.size(); ++i) out[i] = l.pdf_direction(d[i]);
             return values_to_array(out);
           },
           py::arg("dirs"))
      .def("power", &PhysicalSkyLight::power)
      .def("preprocess", [](PhysicalSkyLight& l, const py::object& c, double r) { l.preprocess(to_point(c, "centre"), r); },
           py::arg("centre"), py::arg("radius"))
      .def_property_readonly("build_seconds", [](const PhysicalSkyLight& l) { return l.sky().build_seconds(); })
      .def("__repr__", &PhysicalSkyLight::describe)
      // Pickled as its settings; unpickling rebuilds the sky's table (~0.5 s).
      .def(py::pickle([](const PhysicalSkyLight& l) { return sky_settings_state(l.settings()); },
                      [](const py::tuple& t) {
                        const PhysicalSkySettings s = sky_settings_from_state(t);
                        py::gil_scoped_release release;
                        return std::make_shared<PhysicalSkyLight>(s);
                      }));

  py::class_<AerialPerspective, std::shared_ptr<AerialPerspective>>(m, "AerialPerspective", R"doc(
Aerial perspective of a physical sky: along a segment of air from a viewer at `a` to a point `b`
[m] (scene coordinates; y = 0 lies the sky's `altitude` above sea level), the transmittance T and
the single-scattered sunlight S the air adds (the sky's coefficients, densities, phase functions,
ozone and sun; multiple scattering left out, as in the sky): what arrives at a is T L(b) + S. The
chord is integrated in pieces in closed form (cpp/refracta/shading/aerial_perspective.h).
earth_radius: a CurvedEarth's radius when the scene is its flat frame (y is then the height above
the curved ground), inf for a flat scene (the sky's planet touches y = 0 under the origin).
Scene.set_physical_sky(aerial_perspective=True) makes the renderers apply it to every segment.)doc")
      .def(py::init([](const std::shared_ptr<PhysicalSkyLight>& sky, double scale) {
             if (!sky) throw_invalid("sky must be a refracta.spectrum.PhysicalSky");
             return std::make_shared<AerialPerspective>(PhysicalSky::shared(sky->settings()), scale);
           }),
           py::arg("sky"), py::arg("scale") = 1.0)
      .def("along",
           [](const AerialPerspective& air, const py::object& a, const py::object& b, double wavelength, double earth_radius) {
             return air.along_at(to_point(a, "a"), to_point(b, "b"), AirFrame{earth_radius}, wavelength);
           },
           py::arg("a"), py::arg("b"), py::arg("wavelength"), py::arg("earth_radius") = AirFrame{}.earth_radius,
           "(transmittance, in-scatter [W/(m^2 sr nm)] x scale) at one wavelength [nm] in [360, 830].")
      .def("along_rgb",
           [](const AerialPerspective& air, const py::object& a, const py::object& b, double earth_radius) {
             const AirFrame frame{earth_radius};
             frame.validate();
             const auto seg = air.along(to_point(a, "a"), to_point(b, "b"), frame, SampledWavelengths::rgb());
             return py::make_tuple(points_to_array({Vec3d(seg.transmittance.head<3>().matrix())}).reshape({py::ssize_t(3)}),
                                   points_to_array({Vec3d(seg.inscatter.head<3>().matrix())}).reshape({py::ssize_t(3)}));
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
             return air.sun_transmittance(height, elevation_deg * kPi / 180.0, wavelength);
           },
           py::arg("height"), py::arg("elevation_deg"), py::arg("wavelength"),
           "The sun's transmittance to `height` [m] above sea level where it stands `elevation_deg` above the local horizon.")
      .def_property_readonly("scale", &AerialPerspective::scale)
      // Pickled as its sky's settings and scale; unpickling rebuilds the tables.
      .def(py::pickle(
          [](const AerialPerspective& air) { return py::make_tuple(sky_settings_state(air.sky().settings()), air.scale()); },
          [](const py::tuple& t) {
            if (t.size() != 2) throw_invalid("AerialPerspective: bad pickle state (", t.size(), " items)");
            const PhysicalSkySettings s = sky_settings_from_state(py::cast<py::tuple>(t[0]));
            const double scale = py::cast<double>(t[1]);
            py::gil_scoped_release release;
            return std::make_shared<AerialPerspective>(PhysicalSky::shared(s), scale);
          }));
}

}  // namespace refracta
