// Python bindings of the refractive-index fields (cpp/refracta/media) and CustomField.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/custom_field.h"
#include "refracta/media/curved_earth.h"
#include "refracta/media/fields.h"
#include "refracta/media/tabulated_height_field.h"

#include <set>
#include <sstream>

namespace refracta {

namespace {

std::string param_table(const std::vector<ParamSpec>& specs) {
  std::ostringstream out;
  out << "\n\nParameters (name [unit] default, optimiser bounds: meaning):\n";
  for (const auto& s : specs) {
    out << "    " << s.name << " [" << s.unit << "] " << s.default_value << ", [" << s.lower << ", "
        << s.upper << "]: " << s.doc << "\n";
  }
  return out.str();
}

// Parameter values from positional arguments (in order) and keywords (by name) over defaults.
std::vector<double> values_from(const std::string& type, const std::vector<ParamSpec>& specs,
                                std::vector<double> values, size_t first, const py::args& args,
                                const py::kwargs& kwargs) {
  if (args.size() > specs.size() - first) {
    throw_invalid(type, " takes at most ", specs.size() - first, " positional parameters (got ",
                  args.size(), ")");
  }
  std::set<std::string> given;
  for (size_t i = 0; i < args.size(); ++i) {
    values[first + i] = py::cast<double>(args[i]);
    given.insert(specs[first + i].name);
  }
  for (const auto& item : kwargs) {
    const std::string name = py::cast<std::string>(item.first);
    size_t index = specs.size();
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].name == name) index = i;
    }
    if (index == specs.size() || index < first) {
      std::string names;
      for (size_t i = first; i < specs.size(); ++i) names += (i > first ? ", " : "") + specs[i].name;
      throw_invalid(type, ": unknown parameter '", name, "' (parameters: ", names, ")");
    }
    if (given.count(name)) throw_invalid(type, ": parameter '", name, "' given twice");
    try {
      values[index] = py::cast<double>(item.second);
    } catch (const py::cast_error&) {
      throw_invalid(type, ": ", name, " must be a number");
    }
  }
  return values;
}

FieldPtr with_params(const IndexField& field, const py::kwargs& kwargs) {
  std::vector<double> values = field.param_values();
  for (const auto& item : kwargs) {
    const size_t index = field.param_index(py::cast<std::string>(item.first));
    try {
      values[index] = py::cast<double>(item.second);
    } catch (const py::cast_error&) {
      throw_invalid(field.type_name(), ": ", py::cast<std::string>(item.first), " must be a number");
    }
  }
  return field.with_param_values(values);
}

std::string field_repr(const IndexField& field) {
  std::ostringstream out;
  out.precision(8);
  out << field.type_name() << "(";
  const auto specs = field.param_specs();
  const auto values = field.param_values();
  for (size_t i = 0; i < specs.size(); ++i) out << (i ? ", " : "") << specs[i].name << "=" << values[i];
  out << ")";
  return out.str();
}

py::object ior_of(const IndexField& field, const py::object& points) {
  bool single = false;
  const std::vector<Vec3d> p = to_points(points, "points", &single);
  if (auto custom = dynamic_cast<const CustomField*>(&field)) {
    const DoubleArray values = custom->call_ior(points_to_array(p));
    return single ? py::object(py::float_(values.at(0))) : py::object(values);
  }
  std::vector<double> n(p.size());
  Vec3d grad;
  for (size_t i = 0; i < p.size(); ++i) field.evaluate_checked(p[i], &n[i], &grad);
  return single ? py::object(py::float_(n[0])) : py::object(values_to_array(n));
}

py::object grad_of(const IndexField& field, const py::object& points) {
  bool single = false;
  const std::vector<Vec3d> p = to_points(points, "points", &single);
  DoubleArray out;
  if (auto custom = dynamic_cast<const CustomField*>(&field)) {
    out = custom->call_grad(points_to_array(p));
  } else {
    std::vector<Vec3d> grad(p.size());
    double n;
    for (size_t i = 0; i < p.size(); ++i) field.evaluate_checked(p[i], &n, &grad[i]);
    out = points_to_array(grad);
  }
  return single ? py::object(out.reshape({py::ssize_t(3)})) : py::object(out);
}

template <class Getter>
py::object per_height(const py::object& heights, Getter get) {
  bool single = false;
  const std::vector<double> h = to_values(heights, "heights", &single);
  std::vector<double> out(h.size());
  for (size_t i = 0; i < h.size(); ++i) out[i] = get(h[i]);
  return single ? py::object(py::float_(out[0])) : py::object(values_to_array(out));
}

template <class Field, class Class>
void add_air_column(Class& cls) {
  cls.def("temperature",
          [](const Field& f, const py::object& h) {
            return per_height(h, [&](double x) { return f.temperature(x); });
          },
          py::arg("heights"), "Air temperature [K] at the given heights [m] (scalar or 1-D array).")
      .def("pressure",
           [](const Field& f, const py::object& h) {
             return per_height(h, [&](double x) { return f.pressure(x); });
           },
           py::arg("heights"), "Hydrostatic pressure [Pa] at the given heights [m].");
}

template <class Field>
py::class_<Field, IndexField, std::shared_ptr<Field>> bind_model(py::module_& m, const char* name,
                                                                 const std::string& doc) {
  const auto specs = Field::param_specs_for({});
  py::class_<Field, IndexField, std::shared_ptr<Field>> cls(m, name, (doc + param_table(specs)).c_str());
  cls.def(py::init([specs](const py::args& args, const py::kwargs& kwargs) {
    return std::make_shared<Field>(typename Field::Config{},
                                   values_from(Field::model_name(), specs, default_values(specs), 0, args, kwargs));
  }));
  // Pickled as its parameter values, rebuilt (and validated) by the model's constructor.
  cls.def(py::pickle([](const Field& f) { return py::make_tuple(f.param_values()); },
                     [](const py::tuple& state) {
                       if (state.size() != 1) throw_invalid(Field::model_name(), ": bad pickle state");
                       return std::make_shared<Field>(typename Field::Config{}, py::cast<std::vector<double>>(state[0]));
                     }));
  return cls;
}

}  // namespace

void bind_media(py::module_& m) {
  py::class_<IndexField, std::shared_ptr<IndexField>>(m, "IndexField", R"doc(
A refractive-index field n(x). Points are (N, 3) or (3,) float arrays in metres, y up.

ior(points) -> n, shape (N,) (float for one point); grad_ior(points) -> grad n [1/m], (N, 3).
params: dict of parameter values; param_names; bounds: dict name -> (lower, upper), the box an
optimiser searches; ``with_params(**values)`` -> a new field; height_only: n depends on y alone;
gauge_params: parameters an optimiser holds fixed by default (a joint scaling leaves rays unchanged).
Raises refracta.NumericalError where n <= 0 or is not finite.)doc")
      .def("ior", &ior_of, py::arg("points"), "Refractive index at points (N, 3) -> (N,).")
      .def("grad_ior", &grad_of, py::arg("points"), "Gradient of n [1/m] at points (N, 3) -> (N, 3).")
      .def_property_readonly("type_name", &IndexField::type_name)
      .def_property_readonly("height_only", &IndexField::height_only)
      .def_property_readonly("param_names", [](const IndexField& f) {
        std::vector<std::string> names;
        for (const auto& s : f.param_specs()) names.push_back(s.name);
        return names;
      })
      .def_property_readonly("params", [](const IndexField& f) {
        py::dict out;
        const auto values = f.param_values();
        const auto& specs = f.param_specs();
        for (size_t i = 0; i < specs.size(); ++i) out[py::str(specs[i].name)] = values[i];
        return out;
      })
      .def_property_readonly("bounds", [](const IndexField& f) {
        py::dict out;
        for (const auto& s : f.param_specs()) out[py::str(s.name)] = py::make_tuple(s.lower, s.upper);
        return out;
      })
      .def_property_readonly("param_info", [](const IndexField& f) {
        py::list out;
        for (const auto& s : f.param_specs()) {
          out.append(py::dict(py::arg("name") = s.name, py::arg("default") = s.default_value,
                              py::arg("lower") = s.lower, py::arg("upper") = s.upper,
                              py::arg("unit") = s.unit, py::arg("doc") = s.doc));
        }
        return out;
      }, "One dict per parameter: name, default, lower, upper, unit, doc.")
      .def_property_readonly("gauge_params", &IndexField::gauge_params)
      .def("with_params",
           [](const IndexField& f, const py::kwargs& kw) {
             return std::const_pointer_cast<IndexField>(with_params(f, kw));
           },
           "A new field of the same model with the given parameters changed.")
      .def("__repr__", &field_repr);

  bind_model<LogisticProfile>(m, "LogisticProfile", R"doc(
The original mirage editor's height profile (Choi 2017), in scene units::

    n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
           + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|)
    f(L, w, x0, x) = L / (1 + e^((x0 - x) / w))

Scaling n_bg, n_inv, n_hot together changes nothing (gauge freedom): editing fixes n_bg by default.)doc");

  bind_model<LinearSquaredProfile>(m, "LinearSquaredProfile", R"doc(
n^2 = n0^2 + alpha y: rays are parabolas y = y0 + t0 x + alpha x^2 / (4 beta^2), beta = n(y0) cos(e0).)doc");

  auto physical = bind_model<PhysicalAtmosphere>(m, "PhysicalAtmosphere", R"doc(
Real air: U.S. Standard Atmosphere 1976 temperature + a smooth inversion layer + a surface layer
surface_dt * exp(-h / surface_depth) (h >= 0), hydrostatic pressure, and the index of air from
Edlen's formula revised by Birch & Downs (1993/94) at `wavelength`, optional relative humidity.
Defaults give n - 1 = 2.7784e-4 at the ground (15 C, 101325 Pa, 550 nm). Modelled for heights in
[-1000, 32000] m.)doc");
  add_air_column<PhysicalAtmosphere>(physical);

  py::class_<TemperatureProfile, IndexField, std::shared_ptr<TemperatureProfile>> sounding(
      m, "TemperatureProfile", R"doc(
A measured sounding: temperatures [K] at strictly increasing heights [m], joined by a monotone C1
cubic (pchip) and levelling off smoothly beyond the ends; hydrostatic pressure from `pressure` [Pa]
at the lowest height; n from the same air formula as PhysicalAtmosphere. The temperatures are the
parameters t0, t1, ... (with pressure, humidity, wavelength).)doc");
  sounding.def(py::init([](const py::object& heights, const py::object& temperatures, double pressure,
                           double humidity, double wavelength) {
                 TemperatureProfile::Config config{to_values(heights, "heights")};
                 std::vector<double> values = to_values(temperatures, "temperatures");
                 if (values.size() != config.heights.size()) {
                   throw_invalid("TemperatureProfile: heights and temperatures must have the same "
                                 "length (", config.heights.size(), " vs ", values.size(), ")");
                 }
                 values.insert(values.end(), {pressure, humidity, wavelength});
                 return std::make_shared<TemperatureProfile>(config, values);
               }),
               py::arg("heights"), py::arg("temperatures"), py::arg("pressure") = kStandardPressure,
               py::arg("humidity") = 0.0, py::arg("wavelength") = 550.0)
      .def_property_readonly("heights", [](const TemperatureProfile& f) { return values_to_array(f.config().heights); })
      .def(py::pickle(
          [](const TemperatureProfile& f) { return py::make_tuple(f.config().heights, f.param_values()); },
          [](const py::tuple& state) {
            if (state.size() != 2) throw_invalid("TemperatureProfile: bad pickle state");
            return std::make_shared<TemperatureProfile>(TemperatureProfile::Config{py::cast<std::vector<double>>(state[0])},
                                                        py::cast<std::vector<double>>(state[1]));
          }));
  add_air_column<TemperatureProfile>(sounding);

  py::class_<CurvedEarth, IndexField, std::shared_ptr<CurvedEarth>>(m, "CurvedEarth", R"doc(
A height-only atmosphere over a spherical Earth, in flat coordinates (conformal Earth-flattening
transform): x' = distance along the surface, y' = R ln(r/R), n' = n(h) e^(y'/R). Exact for rays in
their vertical plane; scene heights y' differ from true heights by h^2/(2R) (0.8 mm at 100 m):
true_height(y') and flat_height(h) convert. Use it for anything seen over kilometres (horizons,
looming, Fata Morgana).)doc")
      .def(py::init([](const std::shared_ptr<IndexField>& base, double radius) {
             return std::make_shared<CurvedEarth>(base, radius);
           }),
           py::arg("base"), py::arg("radius") = kEarthRadius)
      .def_property_readonly("base", [](const CurvedEarth& f) { return std::const_pointer_cast<IndexField>(f.base()); })
      .def_property_readonly("radius", &CurvedEarth::radius)
      .def("true_height", [](const CurvedEarth& f, const py::object& y) {
             return per_height(y, [&](double v) { return f.true_height(v); });
           }, py::arg("y"), "True height h [m] of flat-frame heights y'.")
      .def("flat_height", [](const CurvedEarth& f, const py::object& h) {
             return per_height(h, [&](double v) { return f.flat_height(v); });
           }, py::arg("h"), "Flat-frame height y' of true heights h [m].")
      .def(py::pickle(
          [](const CurvedEarth& f) { return py::make_tuple(std::const_pointer_cast<IndexField>(f.base()), f.radius()); },
          [](const py::tuple& state) {
            if (state.size() != 2) throw_invalid("CurvedEarth: bad pickle state");
            return std::make_shared<CurvedEarth>(py::cast<std::shared_ptr<IndexField>>(state[0]), py::cast<double>(state[1]));
          }));

  py::class_<CustomField, IndexField, std::shared_ptr<CustomField>>(m, "CustomField", R"doc(
A field written in Python: ior(points (N,3)) -> (N,) and grad_ior(points (N,3)) -> (N,3), both
vectorised. height_only=True promises n depends on y alone (enables method='stratified').
Slow: the integrators call back into Python at every evaluation.)doc")
      .def(py::init<py::object, py::object, bool>(), py::arg("ior"), py::arg("grad_ior"),
           py::arg("height_only") = false)
      .def_property_readonly("ior_function", &CustomField::ior_function)
      .def_property_readonly("grad_function", &CustomField::grad_function)
      // Pickled as its callables: this works when they pickle (module-level functions with
      // pickle; lambdas and closures with cloudpickle, as dask uses), else the pickler's error.
      .def(py::pickle(
          [](const CustomField& f) { return py::make_tuple(f.ior_function(), f.grad_function(), f.height_only()); },
          [](const py::tuple& state) {
            if (state.size() != 3) throw_invalid("CustomField: bad pickle state");
            return std::make_shared<CustomField>(state[0], state[1], py::cast<bool>(state[2]));
          }));
  // Tests: the tabulation renders and ElevationTables trace through (media/tabulated_height_field.h).
  m.def(
      "_tabulate_heights",
      [](const std::shared_ptr<IndexField>& field, double lo, double hi) {
        if (!field) throw_invalid("_tabulate_heights: field must be a field (got None)");
        return std::const_pointer_cast<IndexField>(tabulate_heights(field, lo, hi));
      },
      py::arg("field"), py::arg("lo"), py::arg("hi"),
      "A height-only field tabulated over [lo, hi] m (cubic Hermite to 1e-12 in n); other fields unchanged.");
}

}  // namespace refracta
