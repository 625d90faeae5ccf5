// Python bindings of the refractive-index fields (cpp/refracta/media) and CustomField.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_media.h"
#include "refracta/bindings/custom_field.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/media/curved_earth.h"
#include "refracta/media/dispersed_field.h"
#include "refracta/media/model_args.h"
#include "refracta/media/tabulated_height_field.h"

#include <pybind11/operators.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <tuple>

namespace refracta {

namespace {

// A parameter's value as a number (convert.h's number_of; nullopt where it is not one: the library
// names it).
ParamInput param_input(const py::handle& value) { return {number_of(value), py::repr(value).cast<std::string>()}; }

NamedValues named_values(const py::kwargs& kwargs) {
  NamedValues out;
  for (const auto& [key, value] : kwargs) out.emplace_back(py::cast<std::string>(key), param_input(value));
  return out;
}

std::string type_name_of(const py::handle& object) { return py::str(py::type::handle_of(object)); }

// turbulence=: a refracta.Turbulence (its `layer`), a TurbulenceLayer, or None.
std::shared_ptr<const Turbulence> turbulence_from_python(const char* model, py::object object) {
  if (object.is_none()) return nullptr;
  if (py::hasattr(object, "layer") && !py::isinstance<Turbulence>(object)) object = object.attr("layer");
  if (!py::isinstance<Turbulence>(object)) {
    throw_invalid(model, ": turbulence must be a refracta.Turbulence (got ", type_name_of(object), ")");
  }
  return py::cast<std::shared_ptr<Turbulence>>(object);
}

// hot_spots=: a HotSpot or a sequence of them.
std::vector<HotSpot> hot_spots_from_python(const char* model, const py::handle& object) {
  if (object.is_none()) return {};
  if (py::isinstance<HotSpot>(object)) return {py::cast<HotSpot>(object)};
  if (!py::isinstance<py::sequence>(object) || py::isinstance<py::str>(object)) {
    throw_invalid(model, ": hot_spots must be a HotSpot or a list of them (got ", type_name_of(object), ")");
  }
  std::vector<HotSpot> spots;
  for (const py::handle& item : object) {
    if (!py::isinstance<HotSpot>(item)) {
      throw_invalid(model, ": hot_spots[", spots.size(), "] must be a refracta.HotSpot (got ", type_name_of(item), ")");
    }
    spots.push_back(py::cast<HotSpot>(item));
  }
  return spots;
}

// Parameters a model takes by position; the rest by name (the house rule for every bound function).
constexpr size_t kMaxPositional = 6;

// A model's constructor arguments: parameters by position or name, hot_spots= and turbulence=.
template <class Field>
std::shared_ptr<Field> model_from_python(const py::args& args, const py::kwargs& kwargs) {
  ModelArgs model;
  for (size_t i = 0; i < args.size(); ++i) {
    const ParamInput value = param_input(args[i]);
    if (!value.number) {
      throw_invalid(Field::model_name(), ": positional parameter ", i + 1, " must be a number (got ", value.given, ")");
    }
    model.positional.push_back(*value.number);
  }
  constexpr bool spots = HasHotSpots<typename Field::Config>::value;  // else the library refuses them
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    if (name == "hot_spots") {
      model.hot_spots = spots ? hot_spots_from_python(Field::model_name(), value) : std::vector<HotSpot>();
    } else if (name == "turbulence") {
      const auto object = py::reinterpret_borrow<py::object>(value);
      model.turbulence = spots ? turbulence_from_python(Field::model_name(), object) : nullptr;
    } else {
      model.named.emplace_back(name, param_input(value));
    }
  }
  auto field = make_model<Field>(model);  // first: too many or bad parameters raise ValueError
  if (args.size() > kMaxPositional) {     // accepted for one release, as the earlier API took them
    const std::string message = std::string(Field::model_name()) + ": parameters after the " +
                                std::to_string(kMaxPositional) + "th by position are deprecated; pass them by name";
    if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0) throw py::error_already_set();
  }
  return field;
}

// The signature line of a model's __init__, which takes *args and **kwargs (its parameters come
// from the spec list): help() and the stubs show the real parameters instead.
std::string init_signature(const char* name, const std::vector<ParamSpec>& specs, bool hot_spots) {
  std::ostringstream out;
  out << "__init__(self: refracta._core." << name;
  for (size_t i = 0; i < specs.size(); ++i) {
    if (i == kMaxPositional) out << ", *";
    out << ", " << specs[i].name << ": float = " << std::string(py::repr(py::float_(specs[i].default_value)));
  }
  if (hot_spots) {
    out << (specs.size() > kMaxPositional ? "" : ", *") << ", hot_spots: refracta._core.HotSpot | collections.abc.Sequence[refracta._core.HotSpot] | None = None"
        << ", turbulence: object = None";
  }
  out << ") -> None\n\n";
  if (specs.size() > kMaxPositional) {
    out << "The first " << kMaxPositional << " parameters by position or name, the rest by name";
  } else {
    out << "Parameters in the order above (positional or by name)";
  }
  out << "; see the class for units and bounds.";
  return out.str();
}

template <class Field>
py::class_<Field, IndexField, std::shared_ptr<Field>> bind_model(py::module_& m, const char* name, const char* doc) {
  using Config = typename Field::Config;
  const auto specs = Field::param_specs_for({});
  py::class_<Field, IndexField, std::shared_ptr<Field>> cls(m, name, (doc + param_table(specs)).c_str());
  py::options signature_by_hand;  // the generated one would read (*args, **kwargs)
  signature_by_hand.disable_function_signatures();
  cls.def(py::init(&model_from_python<Field>), init_signature(name, specs, HasHotSpots<Config>()).c_str());
  signature_by_hand.enable_function_signatures();
  if constexpr (HasHotSpots<Config>::value) {
    cls.def_property_readonly("hot_spots", &model_hot_spots<Field>,
                              "The hot spots with their current parameter values (a list of HotSpot).");
    cls.def_property_readonly("turbulence", [](const Field& f) { return unconst(f.config().turbulence); },
                              "The TurbulenceLayer this air carries (None: calm).");
    // Pickled as its parameter values, hot spots as made and turbulence, rebuilt (and validated)
    // by the model.
    using State = std::tuple<std::vector<double>, std::vector<HotSpot>, std::shared_ptr<Turbulence>, bool>;
    def_tuple_pickle<State>(
        cls, Field::model_name(),
        [](const Field& f) {
          const ModelState s = model_state(f);
          return State(s.values, s.hot_spots, unconst(s.turbulence), s.hot_layer_off);
        },
        [](std::vector<double> values, std::vector<HotSpot> spots, std::shared_ptr<Turbulence> turbulence, bool off) {
          return model_from_state<Field>({std::move(values), std::move(spots), std::move(turbulence), off});
        });
  } else {
    // Pickled as its parameter values, rebuilt (and validated) by the model's constructor.
    def_tuple_pickle<std::tuple<std::vector<double>>>(
        cls, Field::model_name(), [](const Field& f) { return std::make_tuple(f.param_values()); },
        [](std::vector<double> values) { return std::make_shared<Field>(Config{}, std::move(values)); });
  }
  return cls;
}

// A method of one height [m] over a scalar (-> float) or an (N,) array (-> array) of them.
template <class T, double (T::*method)(double) const>
py::object per_height(const T& self, const py::object& heights) {
  bool single = false;
  std::vector<double> h = to_values(heights, "heights", &single);
  for (double& value : h) value = (self.*method)(value);
  return single ? py::object(py::float_(h[0])) : py::object(values_to_array(h));
}

template <class Field, class Class>
void add_air_column(Class& cls) {
  cls.def("temperature", &per_height<Field, &Field::temperature>, py::arg("heights"),
          "Air temperature [K] at the given heights [m] (scalar or 1-D array).");
  cls.def("pressure", &per_height<Field, &Field::pressure>, py::arg("heights"),
          "Hydrostatic pressure [Pa] at the given heights [m].");
}

// ior and grad_ior: n (float) and grad n (3,) for one point, (N,) and (N, 3) for (N, 3).
py::object ior_of(const IndexField& field, const py::object& points) {
  bool single = false;
  const std::vector<double> n = field.ior_at(to_points(points, "points", &single));
  return single ? py::object(py::float_(n[0])) : py::object(values_to_array(n));
}

py::object grad_of(const IndexField& field, const py::object& points) {
  bool single = false;
  DoubleArray out = points_to_array(field.grad_ior_at(to_points(points, "points", &single)));
  return single ? py::object(out.reshape({py::ssize_t(3)})) : py::object(out);
}

void bind_hot_spot(py::module_& m) {
  py::class_<HotSpot> cls(m, "HotSpot", DOC(refracta, HotSpot));
  cls.def(py::init(&make_hot_spot), py::arg("x"), py::arg("z"), py::arg("radius"), py::arg("dt"),
          py::arg("depth") = py::none(), py::arg("footprint") = "gaussian")
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
      .def(py::self == py::self)  // NOLINT(misc-redundant-expression): pybind11's operator binding
      .def("__hash__",  // immutable, so a set member or dict key; a NaN depth ("none") hashes as one value
           [](const HotSpot& s) {
             const py::object depth = std::isnan(s.depth) ? py::object(py::none()) : py::float_(s.depth);
             return py::hash(py::make_tuple(s.x, s.z, s.radius, s.dt, depth, int(s.footprint)));
           })
      .def("__repr__", &hot_spot_repr);
  using State = std::tuple<double, double, double, double, double, int>;
  def_tuple_pickle<State>(
      cls, "HotSpot", [](const HotSpot& s) { return State(s.x, s.z, s.radius, s.dt, s.depth, int(s.footprint)); },
      [](double x, double z, double radius, double dt, double depth, int footprint) {
        if (footprint != int(Footprint::kGaussian) && footprint != int(Footprint::kCompact)) {
          throw_invalid("HotSpot: bad pickle state (footprint ", footprint, ")");
        }
        // Through the constructor's checks, as HotSpot(...) would be.
        return make_hot_spot(x, z, radius, dt, std::isnan(depth) ? std::nullopt : std::optional<double>(depth),
                             footprint_name(Footprint(footprint)));
      });
}

// The interface every field shares: n, its gradient, parameters, regions, turbulence.
void bind_index_field(py::module_& m) {
  py::class_<IndexField, std::shared_ptr<IndexField>>(m, "IndexField", DOC(refracta, IndexField))
      .def("ior", &ior_of, py::arg("points"), "Refractive index at points (N, 3) -> (N,).")
      .def("grad_ior", &grad_of, py::arg("points"), "Gradient of n [1/m] at points (N, 3) -> (N, 3).")
      .def_property_readonly("type_name", &IndexField::type_name)
      .def_property_readonly("height_only", &IndexField::height_only)
      .def_property_readonly("earth_radius", &IndexField::earth_radius,
                             "The radius [m] of the spherical Earth whose coordinates this field flattens (CurvedEarth's "
                             "radius; inf: a flat-Earth field).")
      .def_property_readonly("height_only_part", [](const IndexField& f) { return unconst(f.height_only_part()); },
                             "A field that depends on height alone except in local regions (hot spots): the height-only "
                             "field that holds outside them; None for other fields.")
      .def("with_turbulence",
           [](const IndexField& f, const py::object& turbulence) {
             return unconst(f.with_turbulence(turbulence_from_python(f.type_name().c_str(), turbulence)));
           },
           py::arg("turbulence"),
           "The same air (parameters, hot spots) with `turbulence` (a refracta.Turbulence, a TurbulenceLayer, or None: "
           "calm) in place of its own; PhysicalAtmosphere and LogisticProfile (ValueError for other fields).")
      .def_property_readonly("local_regions", [](const IndexField& f) {
        py::list out;
        for (const LocalRegion& r : f.local_regions()) {
          out.append(py::dict(py::arg("x") = r.x, py::arg("z") = r.z, py::arg("radius") = r.radius,
                              py::arg("top") = r.top, py::arg("scale") = r.scale));
        }
        return out;
      }, "Where the field differs from height_only_part: vertical cylinders (x, z, radius [m]) below `top` [m]; `scale` [m]: the feature's horizontal size.")
      .def_property_readonly("param_names", &param_names)
      .def_property_readonly(
          "params", [](const IndexField& f) { return py::dict(py::cast(named_param_values(f))); },
          "The parameters' values by name: a new dict at each access, so changing it changes no field;\n"
          "field.with_params(name=value) makes a field with new values.")
      .def_property_readonly(
          "bounds", [](const IndexField& f) { return py::dict(py::cast(param_bounds(f))); },
          "Each parameter's (low, high) bounds by name, as edit.solve keeps them (a new dict at each access).")
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
           [](const IndexField& f, const py::args& args, const py::kwargs& kw) {
             if (!args.empty()) {
               throw_invalid("with_params takes the parameters by name: with_params(surface_dt=3.0) (a dict d: "
                             "with_params(**d))");
             }
             return unconst(with_params(f, named_values(kw)));
           },
           "A new field of the same model with the given parameters changed.")
      .def("__repr__", &field_repr);
}

}  // namespace

void bind_media(py::module_& m) {
  bind_hot_spot(m);
  bind_turbulence(m);
  bind_index_field(m);

  bind_model<LogisticProfile>(m, "LogisticProfile", DOC(refracta, LogisticModel));

  bind_model<LinearSquaredProfile>(m, "LinearSquaredProfile", DOC(refracta, LinearSquaredModel));

  auto physical = bind_model<PhysicalAtmosphere>(m, "PhysicalAtmosphere", DOC(refracta, PhysicalAtmosphereModel));
  add_air_column<PhysicalAtmosphere>(physical);

  py::class_<TemperatureProfile, IndexField, std::shared_ptr<TemperatureProfile>> sounding(
      m, "TemperatureProfile", DOC(refracta, TemperatureProfileModel));
  sounding.def(py::init([](const py::object& heights, const py::object& temperatures, double pressure,
                           double humidity, double wavelength) {
                 const std::vector<double> h = to_values(heights, "heights");
                 const std::vector<double> t = to_values(temperatures, "temperatures");
                 // Each level adds 16 hydrostatic nodes (~7 us): from ~10^5 levels on this takes
                 // seconds, so it runs like any long call (GIL released, Ctrl-C stops it).
                 return interruptible_result(
                     py::none(), [&](WorkControl&) { return make_temperature_profile(h, t, pressure, humidity, wavelength); });
               }),
               py::arg("heights"), py::arg("temperatures"), py::arg("pressure") = kStandardPressure,
               py::arg("humidity") = 0.0, py::arg("wavelength") = kDefaultFieldWavelength)
      .def_property_readonly("heights",
                             [](const TemperatureProfile& f) { return values_to_array(f.config().heights); });
  using Sounding = std::tuple<std::vector<double>, std::vector<double>>;
  def_tuple_pickle<Sounding>(
      sounding, "TemperatureProfile",
      [](const TemperatureProfile& f) { return Sounding(f.config().heights, f.param_values()); },
      [](std::vector<double> heights, std::vector<double> values) {
        return std::make_shared<TemperatureProfile>(TemperatureProfile::Config{std::move(heights)}, std::move(values));
      });
  add_air_column<TemperatureProfile>(sounding);

  py::class_<CurvedEarth, IndexField, std::shared_ptr<CurvedEarth>> curved(m, "CurvedEarth", DOC(refracta, CurvedEarth));
  auto make_curved = [](std::shared_ptr<IndexField> base, double radius) {
    return std::make_shared<CurvedEarth>(base, radius);
  };
  curved.def(py::init(make_curved), py::arg("base"), py::arg("radius") = kEarthRadius)
      .def_property_readonly("base", [](const CurvedEarth& f) { return unconst(f.base()); })
      .def_property_readonly("radius", &CurvedEarth::radius)
      .def("true_height", &per_height<CurvedEarth, &CurvedEarth::true_height>, py::arg("y"), DOC(refracta, CurvedEarth, true_height))
      .def("flat_height", &per_height<CurvedEarth, &CurvedEarth::flat_height>, py::arg("h"), DOC(refracta, CurvedEarth, flat_height));
  using Decorated = std::tuple<std::shared_ptr<IndexField>, double>;
  def_tuple_pickle<Decorated>(
      curved, "CurvedEarth", [](const CurvedEarth& f) { return Decorated(unconst(f.base()), f.radius()); },
      make_curved);

  py::class_<CustomField, IndexField, std::shared_ptr<CustomField>> custom(m, "CustomField", R"doc(
A field written in Python: ior(points (N,3)) -> (N,) and grad_ior(points (N,3)) -> (N,3), both
vectorised. height_only=True promises n depends on y alone (enables method='stratified').
Slow: the integrators call back into Python at every evaluation. Its first evaluation checks it
there: height_only=True against n and grad_ior 1 m aside (ValueError if either changes), and
grad_ior against ior's central differences 1 mm apart (a RuntimeWarning beyond 1e-3 of it).
A field whose callables refer back to it (methods of an object holding it) is garbage-collected
while Python alone holds it; one a CurvedEarth, scene or other field also holds stays alive with
its callables, so a cycle through that holder too is kept until the holder is dropped.)doc",
                                                                     py::custom_type_setup(&CustomField::setup_type));
  custom
      .def(py::init<py::object, py::object, bool>(), py::arg("ior"), py::arg("grad_ior"),
           py::arg("height_only").noconvert() = false)
      .def_property_readonly("ior_function", &CustomField::ior_function)
      .def_property_readonly("grad_function", &CustomField::grad_function);
  // Pickled as its callables: this works when they pickle (module-level functions with
  // pickle; lambdas and closures with cloudpickle, as dask uses), else the pickler's error.
  using Callables = std::tuple<py::object, py::object, bool>;
  def_tuple_pickle<Callables>(
      custom, "CustomField",
      [](const CustomField& f) { return Callables(f.ior_function(), f.grad_function(), f.height_only()); },
      [](py::object ior, py::object grad, bool height_only) {
        return std::make_shared<CustomField>(ior, grad, height_only);
      });
  // Tests: the tabulation renders and ElevationTables trace through (media/tabulated_height_field.h).
  m.def(
      "_tabulate_heights",
      [](const std::shared_ptr<IndexField>& field, double lo, double hi) {
        if (!field) throw_invalid("_tabulate_heights: field must be a field (got None)");
        return unconst(tabulate_heights(field, lo, hi));
      },
      py::arg("field"), py::arg("lo"), py::arg("hi"),
      "A height-only field tabulated over [lo, hi] m (cubic Hermite to 1e-12 in n); other fields unchanged.");
}

}  // namespace refracta
