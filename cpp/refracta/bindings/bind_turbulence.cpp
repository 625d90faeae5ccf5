// Python bindings of optical turbulence (media/turbulence.h): the grid refracta.Turbulence builds
// and the layer the fields add. The spectrum and its synthesis live in python/refracta/turbulence.py.
#include "refracta/bindings/bindings.h"
#include "refracta/media/turbulence.h"

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

}  // namespace

void bind_turbulence(py::module_& m) {
  py::class_<TurbulenceGrid, std::shared_ptr<TurbulenceGrid>>(m, "TurbulenceGrid", R"doc(
A periodic uniform cubic B-spline over a 3-D grid: TurbulenceGrid(coefficients (nx, ny, nz) float32,
spacing [m]); axis 0 is x, 1 is y (up), 2 is z. Built by refracta.Turbulence; evaluate(points) gives
the spline's values and gradients (for tests and plots).)doc")
      .def(py::init(&grid_from), py::arg("coefficients"), py::arg("spacing"))
      .def_property_readonly("shape", [](const TurbulenceGrid& g) { return py::make_tuple(g.shape()[0], g.shape()[1], g.shape()[2]); })
      .def_property_readonly("spacing", &TurbulenceGrid::spacing)
      .def_property_readonly("bound", &TurbulenceGrid::bound, "max |coefficient|: a bound of |values|.")
      .def_property_readonly("coefficients", &coefficients_of)
      .def("evaluate",
           [](const TurbulenceGrid& g, const py::object& points) {
             const std::vector<Vec3d> p = to_points(points, "points");
             std::vector<double> values(p.size());
             std::vector<Vec3d> grads(p.size());
             {
               py::gil_scoped_release release;
               for (size_t i = 0; i < p.size(); ++i) g.evaluate(p[i], &values[i], &grads[i]);
             }
             return py::make_tuple(values_to_array(values), points_to_array(grads));
           },
           py::arg("points"), "(values (N,), gradients (N, 3) [1/m]) at points (N, 3) [m].")
      .def(py::pickle([](const TurbulenceGrid& g) { return py::make_tuple(coefficients_of(g), g.spacing()); },
                      [](const py::tuple& t) {
                        if (t.size() != 2) throw_invalid("TurbulenceGrid: bad pickle state");
                        return grid_from(t[0], py::cast<double>(t[1]));
                      }));

  py::class_<Turbulence, std::shared_ptr<Turbulence>>(m, "TurbulenceLayer", R"doc(
A TurbulenceGrid placed in the air: delta_n = scale * E(h) * grid(R_yaw (p - offset)), E(h) =
e^(-h/depth) above the ground (none for depth = inf), the lattice turned by yaw [rad] about the
vertical. Made by refracta.Turbulence (its `layer`).)doc")
      .def(py::init([](std::shared_ptr<TurbulenceGrid> grid, double scale, const py::object& offset, double depth,
                       double yaw) {
             if (!grid) throw_invalid("TurbulenceLayer: grid must be a TurbulenceGrid (got None)");
             if (!std::isfinite(scale)) throw_invalid("TurbulenceLayer: scale must be finite (got ", scale, ")");
             if (!(depth > 0.0)) throw_invalid("TurbulenceLayer: depth must be > 0 m (got ", depth, ")");
             if (!std::isfinite(yaw)) throw_invalid("TurbulenceLayer: yaw must be finite (got ", yaw, ")");
             Turbulence layer;
             layer.grid = std::move(grid);
             layer.scale = scale;
             layer.offset = to_point(offset, "offset");
             layer.depth = depth;
             layer.set_yaw(yaw);
             return layer;
           }),
           py::arg("grid"), py::arg("scale"), py::arg("offset"), py::arg("depth"), py::arg("yaw") = 0.0)
      .def_readonly("yaw", &Turbulence::yaw, "The lattice's turn about the vertical [rad].")
      .def_property_readonly("grid", [](const Turbulence& t) { return std::const_pointer_cast<TurbulenceGrid>(t.grid); })
      .def_readonly("scale", &Turbulence::scale)
      .def_property_readonly("offset", [](const Turbulence& t) { return points_to_array({t.offset}).reshape({py::ssize_t(3)}); })
      .def_readonly("depth", &Turbulence::depth)
      .def("evaluate",
           [](const Turbulence& t, const py::object& points) {
             const std::vector<Vec3d> p = to_points(points, "points");
             std::vector<double> values(p.size());
             std::vector<Vec3d> grads(p.size());
             for (size_t i = 0; i < p.size(); ++i) t.evaluate(p[i], &values[i], &grads[i]);
             return py::make_tuple(values_to_array(values), points_to_array(grads));
           },
           py::arg("points"), "(delta_n (N,), its gradient (N, 3) [1/m]) at points (N, 3) [m].")
      .def(py::pickle(
          [](const Turbulence& t) {
            return py::make_tuple(std::const_pointer_cast<TurbulenceGrid>(t.grid), t.scale,
                                  py::make_tuple(t.offset.x(), t.offset.y(), t.offset.z()), t.depth, t.yaw);
          },
          [](const py::tuple& s) {
            if (s.size() != 5) throw_invalid("TurbulenceLayer: bad pickle state");
            Turbulence layer;
            layer.grid = py::cast<std::shared_ptr<TurbulenceGrid>>(s[0]);
            layer.scale = py::cast<double>(s[1]);
            layer.offset = to_point(s[2], "offset");
            layer.depth = py::cast<double>(s[3]);
            layer.set_yaw(py::cast<double>(s[4]));
            return layer;
          }));
}

}  // namespace refracta
