// Python bindings of optical turbulence (media/turbulence.h, media/turbulence_synthesis.h): the
// settings, the synthesis, the grid and the layer the fields add. refracta.Turbulence
// (python/refracta/turbulence.py) holds them with the ensemble statistics of the pattern.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_media.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/media/turbulence.h"
#include "refracta/media/turbulence_synthesis.h"

#include <pybind11/eigen.h>

#include <cmath>

namespace refracta {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

std::shared_ptr<TurbulenceGrid> grid_from(const py::object& coefficients, double spacing) {
  const FloatArray array = py::cast<FloatArray>(coefficients);
  if (array.ndim() != 3) throw_invalid("TurbulenceGrid: coefficients must be a 3-D array (got ", array.ndim(), " dimensions)");
  std::vector<float> values(array.data(), array.data() + array.size());
  return std::make_shared<TurbulenceGrid>(std::move(values),
                                          std::array<int, 3>{int(array.shape(0)), int(array.shape(1)), int(array.shape(2))},
                                          spacing);
}

py::array coefficients_of(const TurbulenceGrid& grid) {
  const auto& n = grid.shape();
  FloatArray out({py::ssize_t(n[0]), py::ssize_t(n[1]), py::ssize_t(n[2])});
  std::copy(grid.coefficients().begin(), grid.coefficients().end(), out.mutable_data());
  return out;
}

// A function of one real array, element by element, as an array of the same shape.
template <class F>
py::array elementwise(const py::object& x, const char* what, F f) {
  const DoubleArray in = real_array(x, what);
  DoubleArray out(std::vector<py::ssize_t>(in.shape(), in.shape() + in.ndim()));
  std::transform(in.data(), in.data() + in.size(), out.mutable_data(), f);
  return std::move(out);
}

// evaluate(points) of a grid or a layer: (values (N,), gradients (N, 3)).
template <class Source>
std::tuple<DoubleArray, DoubleArray> evaluate_points(const Source& source, const py::object& points) {
  const std::vector<Vec3d> p = to_points(points, "points");
  for (size_t i = 0; i < p.size(); ++i) {  // the pattern's cells are counted in integers
    if (!within_reach(p[i])) check_within_reach(p[i], concat("evaluate: points[", i, "]").c_str());
  }
  PointValues out;
  {
    py::gil_scoped_release release;
    out = evaluate_at(source, p);
  }
  return {values_to_array(out.values), points_to_array(out.gradients)};
}

void bind_settings(py::module_& m) {
  using S = TurbulenceSettings;
  py::class_<S> settings(m, "TurbulenceSettings", DOC(refracta, TurbulenceSettings));
  def_options_common<S>(settings, "TurbulenceSettings")
      .def_readwrite("cn2", &S::cn2, DOC(refracta, TurbulenceSettings, cn2))
      .def_readwrite("outer_scale", &S::outer_scale, DOC(refracta, TurbulenceSettings, outer_scale))
      .def_readwrite("inner_scale", &S::inner_scale, DOC(refracta, TurbulenceSettings, inner_scale))
      .def_readwrite("seed", &S::seed, DOC(refracta, TurbulenceSettings, seed))
      .def_property(
          "wind", [](const S& s) { return py::make_tuple(s.wind[0], s.wind[1]); },
          [](S& s, const py::object& v) {
            const Vec2d wind = to_vec2(v, "Turbulence: wind");
            s.wind = {wind.x(), wind.y()};
          },
          DOC(refracta, TurbulenceSettings, wind))
      .def_readwrite("spacing", &S::spacing, DOC(refracta, TurbulenceSettings, spacing))
      .def_readwrite("cells", &S::cells, DOC(refracta, TurbulenceSettings, cells))
      .def_readwrite("size", &S::size, DOC(refracta, TurbulenceSettings, size))
      .def_readwrite("depth", &S::depth, DOC(refracta, TurbulenceSettings, depth))
      .def_readwrite("max_bytes", &S::max_bytes, DOC(refracta, TurbulenceSettings, max_bytes))
      .def_readwrite("yaw_deg", &S::yaw_deg, DOC(refracta, TurbulenceSettings, yaw_deg))
      .def("cell_count", &S::cell_count, DOC(refracta, TurbulenceSettings, cell_count))
      .def_static(
          "from_fields", [](const py::kwargs& fields) { return options_from<TurbulenceSettings>(py::none(), fields, "Turbulence"); },
          "Settings with the given fields set (the rest at their defaults), validated.");
}

void bind_synthesis(py::module_& m) {
  m.def("synthesise_turbulence",
        [](const TurbulenceSettings& settings, const py::object& progress) {
          return interruptible_result(progress, [&](WorkControl& control) { return synthesise_turbulence(settings, control); });
        },
        py::arg("settings"), py::arg("progress") = py::none(),
        "The spline coefficients of the pattern for C_n^2 = 1 (a TurbulenceGrid); GIL released, Ctrl-C stops it.");
  m.def("turbulence_memory_needed", &turbulence_memory_needed, py::arg("cells"),
        "Bytes the synthesis of a cells^3 grid holds at its peak (a bound).");
  m.def("von_karman_spectrum",
        [](const py::object& kappa, double cn2, double inner_scale, double outer_scale) {
          return elementwise(kappa, "kappa",
                             [&](double k) { return checked_von_karman_spectrum(k, cn2, inner_scale, outer_scale); });
        },
        py::arg("kappa"), py::arg("cn2") = 1.0, py::arg("inner_scale") = 0.0,
        py::arg("outer_scale") = std::numeric_limits<double>::infinity(), DOC(refracta, von_karman_spectrum));
  m.def("bessel_j1",
        [](const py::object& x) { return elementwise(x, "x", [](double v) { return std::cyl_bessel_j(1.0, std::abs(v)) * (v < 0 ? -1.0 : 1.0); }); },
        py::arg("x"), "The Bessel function J1 (std::cyl_bessel_j), element by element.");
  m.attr("SPECTRUM_CONSTANT") = von_karman_constant();
  m.attr("INNER_SCALE_FACTOR") = kInnerScaleFactor;
  m.attr("DEFAULT_TURBULENCE_YAW_DEG") = default_turbulence_yaw_deg();

  py::class_<TurbulenceSpectrum>(m, "_TurbulenceSpectrum")
      .def(py::init<int64_t, double, double, double>(), py::arg("cells"), py::arg("spacing"), py::arg("inner_scale"),
           py::arg("outer_scale"))
      .def("variances", &TurbulenceSpectrum::mode_variances, py::arg("i"), py::arg("j"), py::arg("k"),
           "sigma^2 at lattice indices (i, j[a], k[b]) as a (len(j), len(k)) array (C_n^2 = 1).");
}

}  // namespace

void bind_turbulence(py::module_& m) {
  bind_settings(m);

  py::class_<TurbulenceGrid, std::shared_ptr<TurbulenceGrid>> grid(m, "TurbulenceGrid", DOC(refracta, TurbulenceGrid));
  grid.def(py::init(&grid_from), py::arg("coefficients"), py::arg("spacing"))
      .def_property_readonly("shape", [](const TurbulenceGrid& g) { return py::make_tuple(g.shape()[0], g.shape()[1], g.shape()[2]); })
      .def_property_readonly("spacing", &TurbulenceGrid::spacing)
      .def_property_readonly("bound", &TurbulenceGrid::bound, "max |coefficient|: a bound of |values|.")
      .def_property_readonly("coefficients", &coefficients_of)
      .def("__repr__",
           [](const TurbulenceGrid& g) {
             return concat("TurbulenceGrid(", g.shape()[0], " x ", g.shape()[1], " x ", g.shape()[2],
                           " coefficients, spacing ", g.spacing(), " m, bound ", g.bound(), ")");
           })
      .def("evaluate", &evaluate_points<TurbulenceGrid>, py::arg("points"),
           "(values (N,), gradients (N, 3) [1/m]) at points (N, 3) [m].");
  def_tuple_pickle<std::tuple<py::array, double>>(
      grid, "TurbulenceGrid", [](const TurbulenceGrid& g) { return std::make_tuple(coefficients_of(g), g.spacing()); },
      &grid_from);

  py::class_<Turbulence, std::shared_ptr<Turbulence>> layer(m, "TurbulenceLayer", DOC(refracta, Turbulence));
  auto make_layer = [](std::shared_ptr<TurbulenceGrid> grid, double scale, const py::object& offset, double depth,
                       double yaw) {
    return make_turbulence_layer(grid, scale, to_point(offset, "offset"), depth, yaw);
  };
  layer
      .def(py::init(make_layer), py::arg("grid"), py::arg("scale"), py::arg("offset"), py::arg("depth"),
           py::arg("yaw") = 0.0)
      .def_static(
          "of",
          [](const TurbulenceSettings& settings, std::shared_ptr<TurbulenceGrid> grid, double time) {
            return turbulence_layer(settings, std::move(grid), time);
          },
          py::arg("settings"), py::arg("grid"), py::arg("time"),
          "The layer of `settings` over `grid`: scaled by sqrt(cn2), carried by the wind to time [s].")
      .def_readonly("yaw", &Turbulence::yaw, "The lattice's turn about the vertical [rad].")
      .def_property_readonly("grid", [](const Turbulence& t) { return unconst(t.grid); })
      .def_readonly("scale", &Turbulence::scale)
      .def_property_readonly("offset", [](const Turbulence& t) { return vector_to_array(t.offset); })
      .def_readonly("depth", &Turbulence::depth)
      .def("__repr__",
           [](const Turbulence& t) {
             return concat("TurbulenceLayer(scale=", t.scale, ", offset=(", t.offset.x(), ", ", t.offset.y(), ", ",
                           t.offset.z(), ") m, depth=", t.depth, " m, yaw=", t.yaw, " rad)");
           })
      .def("evaluate", &evaluate_points<Turbulence>, py::arg("points"),
           "(delta_n (N,), its gradient (N, 3) [1/m]) at points (N, 3) [m].");
  using Offset = std::tuple<double, double, double>;
  using State = std::tuple<std::shared_ptr<TurbulenceGrid>, double, Offset, double, double>;
  def_tuple_pickle<State>(
      layer, "TurbulenceLayer",
      [](const Turbulence& t) {
        return State(unconst(t.grid), t.scale, Offset(t.offset.x(), t.offset.y(), t.offset.z()), t.depth, t.yaw);
      },
      [make_layer](std::shared_ptr<TurbulenceGrid> grid, double scale, Offset offset, double depth, double yaw) {
        return make_layer(std::move(grid), scale, py::cast(offset), depth, yaw);
      });
  bind_synthesis(m);
}

}  // namespace refracta
