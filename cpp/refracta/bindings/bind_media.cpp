// Python bindings of the refractive-index fields (cpp/refracta/media) and CustomField.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/custom_field.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/media/curved_earth.h"
#include "refracta/media/fields.h"
#include "refracta/media/hot_spot.h"
#include "refracta/media/tabulated_height_field.h"

#include <optional>
#include <set>
#include <type_traits>
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

// The signature line of a model's __init__, which takes *args and **kwargs (its parameters come
// from the spec list): help() and the stubs show the real parameters instead.
std::string init_signature(const char* name, const std::vector<ParamSpec>& specs, bool hot_spots) {
  std::ostringstream out;
  out << "__init__(self: refracta._core." << name;
  for (const auto& s : specs) out << ", " << s.name << ": float = " << std::string(py::repr(py::float_(s.default_value)));
  if (hot_spots) {
    out << ", *, hot_spots: refracta._core.HotSpot | collections.abc.Sequence[refracta._core.HotSpot] | None = None"
        << ", turbulence: object = None";
  }
  out << ") -> None\n\nParameters in the order above (positional or by name); see the class for units and bounds.";
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
  const auto& specs = field.param_specs();
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

// Whether a model's Config carries hot spots.
template <class Config, class = void>
struct HasHotSpots : std::false_type {};
template <class Config>
struct HasHotSpots<Config, std::void_t<decltype(std::declval<Config&>().hot_spots)>> : std::true_type {};

// Whether a model's Config can switch its hot layer off (LogisticProfile's height-only part).
template <class Config, class = void>
struct HasHotLayerOff : std::false_type {};
template <class Config>
struct HasHotLayerOff<Config, std::void_t<decltype(std::declval<Config&>().hot_layer_off)>> : std::true_type {};

// The hot spots given to a field's constructor: a HotSpot or a sequence of them. PhysicalAtmosphere
// takes a spot without depth as deep as its surface layer; LogisticProfile's spots have no depth.
std::vector<HotSpot> hot_spots_from_python(const char* model, const py::handle& object, bool with_depth,
                                           double default_depth) {
  std::vector<HotSpot> spots;
  if (object.is_none()) return spots;
  if (py::isinstance<HotSpot>(object)) return hot_spots_from_python(model, py::make_tuple(object), with_depth, default_depth);
  if (!py::isinstance<py::sequence>(object) || py::isinstance<py::str>(object)) {
    throw_invalid(model, ": hot_spots must be a HotSpot or a list of them (got ", std::string(py::str(py::type::handle_of(object))), ")");
  }
  for (const py::handle& item : object) {
    if (!py::isinstance<HotSpot>(item)) {
      throw_invalid(model, ": hot_spots[", spots.size(), "] must be a refracta.HotSpot (got ",
                    std::string(py::str(py::type::handle_of(item))), ")");
    }
    HotSpot spot = py::cast<HotSpot>(item);
    if (!with_depth && !std::isnan(spot.depth)) {
      throw_invalid(model, ": hot_spots[", spots.size(), "] has depth ", spot.depth,
                    "; a LogisticProfile spot takes its vertical width from a_hot (leave depth None)");
    }
    if (with_depth && std::isnan(spot.depth)) spot.depth = default_depth;
    spots.push_back(spot);
  }
  return spots;
}

// turbulence=: a refracta.Turbulence (its `layer`), a TurbulenceLayer, or None.
std::shared_ptr<const Turbulence> turbulence_from_python(const char* model, py::object object) {
  if (object.is_none()) return nullptr;
  if (py::hasattr(object, "layer") && !py::isinstance<Turbulence>(object)) object = object.attr("layer");
  if (!py::isinstance<Turbulence>(object)) {
    throw_invalid(model, ": turbulence must be a refracta.Turbulence (got ", std::string(py::str(py::type::handle_of(object))), ")");
  }
  return py::cast<std::shared_ptr<Turbulence>>(object);
}

template <class Field>
py::class_<Field, IndexField, std::shared_ptr<Field>> bind_model(py::module_& m, const char* name,
                                                                 const std::string& doc) {
  using Config = typename Field::Config;
  const auto specs = Field::param_specs_for({});
  py::class_<Field, IndexField, std::shared_ptr<Field>> cls(m, name, (doc + param_table(specs)).c_str());
  py::options signature_by_hand;  // the generated one would read (*args, **kwargs)
  signature_by_hand.disable_function_signatures();
  cls.def(py::init([specs](const py::args& args, const py::kwargs& kwargs) {
    Config config{};
    std::vector<double> values = values_from(Field::model_name(), specs, default_values(specs), 0, args, [&] {
      py::kwargs rest;
      for (const auto& item : kwargs) {
        const std::string key = py::cast<std::string>(item.first);
        if (key != "hot_spots" && key != "turbulence") rest[item.first] = item.second;
      }
      return rest;
    }());
    if constexpr (HasHotSpots<Config>::value) {
      if (kwargs.contains("hot_spots")) {
        constexpr bool with_depth = Field::ModelType::kSpotsHaveDepth;
        double depth = 0.0;
        for (size_t i = 0; i < specs.size(); ++i) {
          if (specs[i].name == "surface_depth") depth = values[i];
        }
        config.hot_spots = hot_spots_from_python(Field::model_name(), kwargs["hot_spots"], with_depth, depth);
        for (const ParamSpec& spec : Field::param_specs_for(config)) {
          if (spec.name.rfind("hot_spot", 0) == 0) values.push_back(spec.default_value);
        }
      }
    } else if (kwargs.contains("hot_spots")) {
      throw_invalid(Field::model_name(), " takes no hot_spots");
    }
    if constexpr (HasHotSpots<Config>::value) {
      if (kwargs.contains("turbulence")) config.turbulence = turbulence_from_python(Field::model_name(), kwargs["turbulence"]);
    } else if (kwargs.contains("turbulence")) {
      throw_invalid(Field::model_name(), " takes no turbulence");
    }
    return std::make_shared<Field>(config, values);
  }), init_signature(name, specs, HasHotSpots<Config>::value).c_str());
  signature_by_hand.enable_function_signatures();
  if constexpr (HasHotSpots<Config>::value) {
    cls.def_property_readonly("hot_spots", [](const Field& f) {
      const size_t first = Field::param_specs_for(Config{}).size();
      constexpr bool with_depth = Field::ModelType::kSpotsHaveDepth;
      std::vector<HotSpot> spots = hot_spots_from(f.config().hot_spots, f.param_values(), first, with_depth);
      if (!with_depth) {
        for (HotSpot& spot : spots) spot.depth = std::nan("");
      }
      return spots;
    }, "The hot spots with their current parameter values (a list of HotSpot).");
    cls.def_property_readonly("turbulence", [](const Field& f) { return std::const_pointer_cast<Turbulence>(f.config().turbulence); },
                              "The TurbulenceLayer this air carries (None: calm).");
    // Pickled as its parameter values, hot spots as made and turbulence, rebuilt (and validated)
    // by the model.
    cls.def(py::pickle([](const Field& f) {
                         bool layer_off = false;
                         if constexpr (HasHotLayerOff<Config>::value) layer_off = f.config().hot_layer_off;
                         return py::make_tuple(f.param_values(), f.config().hot_spots,
                                               std::const_pointer_cast<Turbulence>(f.config().turbulence), layer_off);
                       },
                       [](const py::tuple& state) {
                         if (state.size() != 4) throw_invalid(Field::model_name(), ": bad pickle state");
                         Config config{};
                         config.hot_spots = py::cast<std::vector<HotSpot>>(state[1]);
                         if (!state[2].is_none()) config.turbulence = py::cast<std::shared_ptr<Turbulence>>(state[2]);
                         if constexpr (HasHotLayerOff<Config>::value) config.hot_layer_off = py::cast<bool>(state[3]);
                         return std::make_shared<Field>(config, py::cast<std::vector<double>>(state[0]));
                       }));
  } else {
    // Pickled as its parameter values, rebuilt (and validated) by the model's constructor.
    cls.def(py::pickle([](const Field& f) { return py::make_tuple(f.param_values()); },
                       [](const py::tuple& state) {
                         if (state.size() != 1) throw_invalid(Field::model_name(), ": bad pickle state");
                         return std::make_shared<Field>(Config{}, py::cast<std::vector<double>>(state[0]));
                       }));
  }
  return cls;
}

void bind_hot_spot(py::module_& m) {
  py::class_<HotSpot>(m, "HotSpot", R"doc(
An areal hot (dt > 0) or cold (dt < 0) patch of ground centred at (x, z) [m]: the air above it is
warmer by dt * exp(-h / depth) * F(r), r the horizontal distance from the centre, with footprint
'gaussian' F = exp(-r^2 / (2 radius^2)) or 'compact' F = (1 - r/R)^4 (4 r/R + 1) for r < R = radius
(Wendland's C2 function: exactly zero outside). Give it to PhysicalAtmosphere(hot_spots=[...])
(dt [K]; depth [m], None: the atmosphere's surface_depth) or LogisticProfile(hot_spots=[...])
(dt: strength of the profile's hot-spot term there, 1 = the whole term; depth must be None: the
term's width is a_hot). The fields expose each spot's numbers as parameters hot_spot<i>_x, _z,
_radius, _dt (, _depth), so refracta.edit.solve can move, resize and heat them.)doc")
      .def(py::init([](double x, double z, double radius, double dt, std::optional<double> depth,
                       const std::string& footprint) {
             HotSpot s;
             s.x = x, s.z = z, s.radius = radius, s.dt = dt, s.depth = depth.value_or(std::nan(""));
             s.footprint = parse_footprint(footprint);
             const std::pair<const char*, double> finite[] = {{"x", x}, {"z", z}, {"radius", radius}, {"dt", dt}};
             for (const auto& [what, value] : finite) {
               if (!std::isfinite(value)) throw_invalid("HotSpot: ", what, " must be finite (got ", value, ")");
             }
             if (!(radius > 0.0)) throw_invalid("HotSpot: radius must be > 0 m (got ", radius, ")");
             if (depth && !(*depth > 0.0 && std::isfinite(*depth))) {
               throw_invalid("HotSpot: depth must be > 0 m and finite (got ", *depth, ")");
             }
             return s;
           }),
           py::arg("x"), py::arg("z"), py::arg("radius"), py::arg("dt"), py::arg("depth") = py::none(),
           py::arg("footprint") = "gaussian")
      .def_readonly("x", &HotSpot::x)
      .def_readonly("z", &HotSpot::z)
      .def_readonly("radius", &HotSpot::radius)
      .def_readonly("dt", &HotSpot::dt)
      .def_property_readonly("depth", [](const HotSpot& s) -> std::optional<double> {
        return std::isnan(s.depth) ? std::nullopt : std::optional<double>(s.depth);
      })
      .def_property_readonly("footprint", [](const HotSpot& s) { return std::string(footprint_name(s.footprint)); })
      .def_property_readonly("reach", &HotSpot::reach,
                             "Distance [m] beyond which the footprint is below 1e-6 (compact: exactly 0).")
      .def("__eq__", [](const HotSpot& a, const HotSpot& b) {
        return a.x == b.x && a.z == b.z && a.radius == b.radius && a.dt == b.dt && a.footprint == b.footprint &&
               (a.depth == b.depth || (std::isnan(a.depth) && std::isnan(b.depth)));
      })
      .def("__repr__", [](const HotSpot& s) {
        return concat("HotSpot(x=", s.x, ", z=", s.z, ", radius=", s.radius, ", dt=", s.dt, ", depth=",
                      std::isnan(s.depth) ? std::string("None") : concat(s.depth), ", footprint='",
                      footprint_name(s.footprint), "')");
      })
      .def(py::pickle(
          [](const HotSpot& s) { return py::make_tuple(s.x, s.z, s.radius, s.dt, s.depth, int(s.footprint)); },
          [](const py::tuple& t) {
            if (t.size() != 6) throw_invalid("HotSpot: bad pickle state");
            HotSpot s;
            s.x = py::cast<double>(t[0]), s.z = py::cast<double>(t[1]), s.radius = py::cast<double>(t[2]);
            s.dt = py::cast<double>(t[3]), s.depth = py::cast<double>(t[4]);
            s.footprint = Footprint(py::cast<int>(t[5]));
            return s;
          }));
}

// The interface every field shares: n, its gradient, parameters, regions, turbulence.
void bind_index_field(py::module_& m) {
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
      .def_property_readonly("height_only_part",
                             [](const IndexField& f) { return std::const_pointer_cast<IndexField>(f.height_only_part()); },
                             "A field that depends on height alone except in local regions (hot spots): the height-only "
                             "field that holds outside them; None for other fields.")
      .def("with_turbulence",
           [](const IndexField& f, const py::object& turbulence) {
             return std::const_pointer_cast<IndexField>(f.with_turbulence(turbulence_from_python(f.type_name().c_str(), turbulence)));
           },
           py::arg("turbulence"),
           "The same air (parameters, hot spots) with `turbulence` (a refracta.Turbulence, a TurbulenceLayer, or None: "
           "calm) in place of its own; PhysicalAtmosphere and LogisticProfile (ValueError for other fields).")
      .def_property_readonly("local_regions", [](const IndexField& f) {
        py::list out;
        for (const LocalRegion& r : f.local_regions()) {
          out.append(py::dict(py::arg("x") = r.x, py::arg("z") = r.z, py::arg("radius") = r.radius, py::arg("top") = r.top,
                              py::arg("scale") = r.scale));
        }
        return out;
      }, "Where the field differs from height_only_part: vertical cylinders (x, z, radius [m]) below `top` [m]; `scale` [m]: the feature's horizontal size.")
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
}

}  // namespace

void bind_media(py::module_& m) {
  bind_hot_spot(m);
  bind_turbulence(m);
  bind_index_field(m);

  bind_model<LogisticProfile>(m, "LogisticProfile", R"doc(
The original mirage editor's height profile (Choi 2017), in scene units::

    n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
           + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|)
    f(L, w, x0, x) = L / (1 + e^((x0 - x) / w))

Scaling n_bg, n_inv, n_hot together changes nothing (gauge freedom): editing fixes n_bg by default.
hot_spots=[refracta.HotSpot(x, z, radius, strength), ...] localise the hot term: its deficit near
the ground, n_hot * sigma(-h / (0.3 a_hot)), is scaled by sum_i dt_i F_i(r_i), so the hot layer lies
only over the spots (parameters hot_spot<i>_x, _z, _radius, _dt).)doc");

  bind_model<LinearSquaredProfile>(m, "LinearSquaredProfile", R"doc(
n^2 = n0^2 + alpha y: rays are parabolas y = y0 + t0 x + alpha x^2 / (4 beta^2), beta = n(y0) cos(e0).)doc");

  auto physical = bind_model<PhysicalAtmosphere>(m, "PhysicalAtmosphere", R"doc(
Real air: U.S. Standard Atmosphere 1976 temperature (its seven layers to 86 km, geometric heights,
gravity falling with height) + a smooth inversion layer + a surface layer
surface_dt * exp(-h / surface_depth) (h >= 0) + areal hot spots (hot_spots=[refracta.HotSpot, ...]),
hydrostatic pressure, and the index of air from Edlen's formula revised by Birch & Downs (1993/94)
at `wavelength`, optional relative humidity. Defaults give n - 1 = 2.7784e-4 at the ground (15 C,
101325 Pa, 550 nm). Modelled for heights in [-1000, 86000] m (uniform above). With hot spots the
field is no longer height-only: its parameters gain hot_spot<i>_x, _z, _radius, _dt, _depth, and
height_only_part is the same air without them.)doc");
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
                 // Each level adds 16 hydrostatic nodes (~7 us): from ~10^5 levels on this takes
                 // seconds, so it runs like any long call (GIL released, Ctrl-C stops it).
                 std::shared_ptr<TemperatureProfile> field;
                 WorkControl control;
                 run_interruptible(control, py::none(),
                                   [&] { field = std::make_shared<TemperatureProfile>(config, values); });
                 return field;
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
