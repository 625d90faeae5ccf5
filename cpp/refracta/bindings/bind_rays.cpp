// Python bindings of the ray integrators (cpp/refracta/rays): trace_ray, the batch tracer, RayPath.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/rays/astronomical_refraction.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/trace.h"

#include <optional>

namespace refracta {

namespace {

TraceOptions make_options(const std::string& method, double tol, std::optional<double> step,
                          double max_length, std::optional<double> stop_height) {
  TraceOptions options;
  options.method = parse_trace_method(method);
  options.tol = tol;
  if (step) {
    if (!(*step > 0.0) || !std::isfinite(*step)) throw_invalid("step must be > 0 (got ", *step, ")");
    options.step = *step;
  }
  options.max_length = max_length;
  options.stop_height = stop_height;
  options.validate();
  return options;
}

const IndexField& checked_field(const std::shared_ptr<IndexField>& field) {
  if (!field) throw_invalid("field must be an IndexField (got None)");
  return *field;
}

template <class Get>
DoubleArray node_vectors(const RayPath& path, Get get) {
  std::vector<Vec3d> out;
  for (const auto& node : path.nodes()) out.push_back(get(node));
  return points_to_array(out);
}

template <class Get>
DoubleArray node_values(const RayPath& path, Get get) {
  std::vector<double> out;
  for (const auto& node : path.nodes()) out.push_back(get(node));
  return values_to_array(out);
}

}  // namespace

void bind_rays(py::module_& m) {
  py::class_<RayPath, std::shared_ptr<RayPath>>(m, "RayPath", R"doc(
A traced light path. Arrays are per node (the integrator's steps; the path between nodes is the
quintic Hermite interpolant of positions, tangents and curvatures, accurate to O(step^6)).

points (N,3) [m]; directions (N,3) unit tangents; arc_length (N,) [m]; ior (N,) n at each node;
ray_vectors (N,3) the integrated v (``|v| = n``); stop: why the path ended ('max_length',
'stop_height'); evaluations: field evaluations used.)doc")
      .def_property_readonly("points", [](const RayPath& p) { return node_vectors(p, [](const RayNode<double>& n) { return n.x; }); })
      .def_property_readonly("directions", [](const RayPath& p) {
        return node_vectors(p, [](const RayNode<double>& n) { return Vec3d(n.v.normalized()); });
      })
      .def_property_readonly("ray_vectors", [](const RayPath& p) { return node_vectors(p, [](const RayNode<double>& n) { return n.v; }); })
      .def_property_readonly("arc_length", [](const RayPath& p) { return node_values(p, [](const RayNode<double>& n) { return n.s; }); })
      .def_property_readonly("ior", [](const RayPath& p) { return node_values(p, [](const RayNode<double>& n) { return n.n; }); })
      .def_property_readonly("length", &RayPath::length, "Arc length of the whole path [m].")
      .def_property_readonly("stop", [](const RayPath& p) { return std::string(trace_stop_name(p.stop())); })
      .def_property_readonly("evaluations", &RayPath::evaluations)
      .def("__len__", [](const RayPath& p) { return p.nodes().size(); })
      // Pickled as its nodes (s, x, v, n, grad n: 11 numbers each, (N, 11) float64), stop and
      // evaluation count; the copy answers every query exactly as the original.
      .def(py::pickle(
          [](const RayPath& p) {
            DoubleArray nodes({py::ssize_t(p.nodes().size()), py::ssize_t(11)});
            double* d = nodes.mutable_data();
            for (const auto& n : p.nodes()) {
              const double row[11] = {n.s, n.x.x(), n.x.y(), n.x.z(), n.v.x(), n.v.y(), n.v.z(), n.n, n.grad.x(), n.grad.y(), n.grad.z()};
              d = std::copy(row, row + 11, d);
            }
            return py::make_tuple(nodes, int(p.stop()), p.evaluations());
          },
          [](const py::tuple& state) {
            if (state.size() != 3) throw_invalid("RayPath: bad pickle state");
            const DoubleArray nodes = py::cast<DoubleArray>(state[0]);
            if (nodes.ndim() != 2 || nodes.shape(1) != 11 || nodes.shape(0) < 1) throw_invalid("RayPath: bad pickle state (nodes)");
            const int stop = py::cast<int>(state[1]);
            if (stop < 0 || stop > int(TraceStop::kVisitor)) throw_invalid("RayPath: bad pickle state (stop ", stop, ")");
            std::vector<RayNode<double>> out(size_t(nodes.shape(0)));
            for (size_t i = 0; i < out.size(); ++i) {
              const double* r = nodes.data() + 11 * i;
              out[i] = RayNode<double>{r[0], Vec3d(r[1], r[2], r[3]), Vec3d(r[4], r[5], r[6]), r[7], Vec3d(r[8], r[9], r[10])};
            }
            return std::make_shared<RayPath>(std::move(out), TraceStop(stop), py::cast<int64_t>(state[2]));
          }))
      .def("point_at",
           [](const RayPath& p, double s) {
             Vec3d direction;
             const Vec3d x = p.point_at(s, &direction);
             return py::make_tuple(points_to_array({x}).reshape({py::ssize_t(3)}),
                                   points_to_array({direction}).reshape({py::ssize_t(3)}));
           },
           py::arg("s"), "(point, unit tangent) at arc length s [m] on the continuous path.")
      .def("sample",
           [](const RayPath& p, int count) {
             if (count < 2) throw_invalid("count must be >= 2 (got ", count, ")");
             std::vector<Vec3d> points(count);
             for (int i = 0; i < count; ++i) points[i] = p.point_at(p.length() * i / (count - 1));
             return points_to_array(points);
           },
           py::arg("count") = 200, "count points (count, 3) evenly spaced in arc length on the continuous path.")
      .def("closest_point",
           [](const RayPath& p, const py::object& q) {
             const ClosestPoint c = p.closest_point(to_point(q, "q"));
             return py::make_tuple(points_to_array({c.point}).reshape({py::ssize_t(3)}), c.distance, c.s);
           },
           py::arg("q"),
           "(point, distance, s): the point of the continuous path closest to q, its distance [m] "
           "and its arc length [m].")
      .def("at_height",
           [](const RayPath& p, double y) {
             std::vector<Vec3d> points;
             for (const auto& c : p.crossings(Vec3d(0, 1, 0), y)) points.push_back(c.point);
             return points_to_array(points);
           },
           py::arg("y"), "Every point where the path crosses height y [m], in path order, (K, 3).")
      .def("crossings",
           [](const RayPath& p, const py::object& normal, double offset) {
             py::list out;
             for (const auto& c : p.crossings(to_point(normal, "normal"), offset)) {
               out.append(py::make_tuple(points_to_array({c.point}).reshape({py::ssize_t(3)}), c.s,
                                         points_to_array({c.direction}).reshape({py::ssize_t(3)})));
             }
             return out;
           },
           py::arg("normal"), py::arg("offset"),
           "Crossings of the plane normal . x = offset: a list of (point, s, unit direction).")
      .def("__repr__", [](const RayPath& p) {
        return concat("RayPath(nodes=", p.nodes().size(), ", length=", p.length(), " m, stop='",
                      trace_stop_name(p.stop()), "')");
      });

  m.def("trace_ray",
        [](const std::shared_ptr<IndexField>& field, const py::object& origin, const py::object& direction,
           const std::string& method, double tol, std::optional<double> step, double max_length,
           std::optional<double> stop_height) {
          const IndexField& f = checked_field(field);
          const TraceOptions options = make_options(method, tol, step, max_length, stop_height);
          const Vec3d o = to_point(origin, "origin"), d = to_point(direction, "direction");
          // On a worker thread with the GIL released, like the batch: Ctrl-C stops a long path.
          WorkControl control;
          TraceOptions cancellable = options;
          cancellable.cancel = &control.cancel;
          std::shared_ptr<RayPath> path;
          run_interruptible(control, py::none(), [&] { path = std::make_shared<RayPath>(trace_path(f, o, d, cancellable)); });
          return path;
        },
        py::arg("field"), py::arg("origin"), py::arg("direction"), py::arg("method") = "rk45",
        py::arg("tol") = 1e-6, py::arg("step") = py::none(), py::arg("max_length") = 1000.0,
        py::arg("stop_height") = py::none(), R"doc(
Trace one curved ray through `field` and return its RayPath.

The ray equations dx/ds = v/n, dv/ds = grad n are launched with ``v0 = n(origin) * direction / |direction|``.
method: 'rk45' (adaptive Dormand-Prince; tol is the target position error [m] over the path),
'rk4' (fixed step `step`, default 0.3 m, the original editor's), or 'stratified' (height-only
fields: exact paths from n(h) cos(e) = const by quadrature to `tol`; `step` is the largest node
spacing, default 100 m). max_length [m]: arc length at which the path ends. stop_height [m]: the
path ends where it descends through this height (a ground). Raises ValueError for bad arguments
(a path needing more than 10 million nodes is refused up front), refracta.NumericalError where n
<= 0 or is not finite; Ctrl-C (KeyboardInterrupt) stops it.)doc");

  m.def("_astronomical_refraction",
        [](const std::shared_ptr<IndexField>& field, const py::object& elevations, double eye_height, double top,
           double earth_radius, double tol) {
          const FieldPtr f = field;
          AstronomicalRefractionOptions options;
          options.eye_height = eye_height;
          options.top = top;
          options.earth_radius = earth_radius;
          options.tol = tol;
          options.validate();
          const std::vector<double> e = to_values(elevations, "apparent elevations");
          std::vector<double> out(e.size());
          WorkControl control;
          run_interruptible(control, py::none(), [&] {
            parallel_for_each(int64_t(e.size()), 1, control,
                              [&](int64_t i) { out[i] = astronomical_refraction(f, e[i], options); });
          });
          return values_to_array(out);
        },
        py::arg("field"), py::arg("elevations"), py::arg("eye_height"), py::arg("top"), py::arg("earth_radius"),
        py::arg("tol"), "Refraction [rad] at apparent elevations [rad] (refracta.astronomical_refraction).");

  m.def("_trace_batch",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const std::string& method, double tol, std::optional<double> step, double max_length,
           std::optional<double> stop_height, const py::object& progress) {
          const IndexField& f = checked_field(field);
          const TraceOptions options = make_options(method, tol, step, max_length, stop_height);
          const std::vector<Vec3d> o = to_points(origins, "origins");
          const std::vector<Vec3d> d = to_points(directions, "directions");
          WorkControl control;
          control.total = int64_t(o.size());
          RayBatchEnds ends;
          run_interruptible(control, progress, [&] { ends = trace_batch(f, o, d, options, control); });
          std::vector<double> stops(ends.stops.begin(), ends.stops.end());
          std::vector<double> evaluations(ends.evaluations.begin(), ends.evaluations.end());
          return py::make_tuple(points_to_array(ends.points), points_to_array(ends.directions),
                                values_to_array(ends.lengths), values_to_array(stops),
                                values_to_array(evaluations));
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("method"),
        py::arg("tol"), py::arg("step"), py::arg("max_length"), py::arg("stop_height"),
        py::arg("progress"));
  py::class_<ElevationTable, std::shared_ptr<ElevationTable>>(m, "_ElevationTable")
      .def(py::init([](const std::shared_ptr<IndexField>& field, double eye_height, double min_deg,
                       double max_deg, double tol, double max_length, std::optional<double> stop_height,
                       std::optional<double> step, std::optional<double> trace_tol, const py::object& progress) {
             checked_field(field);
             ElevationTableOptions options;
             options.eye_height = eye_height;
             options.min_elevation = degrees_to_radians(min_deg);
             options.max_elevation = degrees_to_radians(max_deg);
             options.tol = tol;
             options.trace = make_options("stratified", trace_tol ? *trace_tol : tol, step,
                                          max_length, stop_height);
             options.validate();
             WorkControl control;
             std::shared_ptr<ElevationTable> table;
             run_interruptible(control, progress, [&] {
               table = std::make_shared<ElevationTable>(field, options, control);
             });
             return table;
           }),
           py::arg("field"), py::arg("eye_height"), py::arg("min_elevation"), py::arg("max_elevation"),
           py::arg("tol"), py::arg("max_length"), py::arg("stop_height"), py::arg("step"),
           py::arg("trace_tol"), py::arg("progress"))
      .def("ends",
           [](const ElevationTable& table, const py::object& elevations, const py::object& azimuths) {
             const std::vector<double> e = to_values(elevations, "elevations");
             std::vector<double> a = to_values(azimuths, "azimuths");
             if (a.size() == 1 && e.size() != 1) a.assign(e.size(), a[0]);
             if (a.size() != e.size()) {
               throw_invalid("azimuths must be one value or one per elevation (", a.size(), " vs ", e.size(), ")");
             }
             std::vector<Vec3d> points(e.size()), directions(e.size());
             std::vector<double> lengths(e.size()), stops(e.size());
             {
               py::gil_scoped_release release;
               WorkControl control;
               parallel_for_each(int64_t(e.size()), 64, control, [&](int64_t i) {
                 const PlaneState p = table.end(degrees_to_radians(e[i]));
                 const double ca = std::cos(degrees_to_radians(a[i])), sa = std::sin(degrees_to_radians(a[i]));
                 points[i] = Vec3d(p.r * ca, p.h, p.r * sa);
                 directions[i] = Vec3d(p.cos_e * ca, p.sin_e, p.cos_e * sa);
                 lengths[i] = p.s;
                 stops[i] = double(int(p.stop));
               });
             }
             return py::make_tuple(points_to_array(points), points_to_array(directions),
                                   values_to_array(lengths), values_to_array(stops));
           },
           py::arg("elevations"), py::arg("azimuths"))
      .def_property_readonly("size", &ElevationTable::size)
      .def_property_readonly("evaluations", &ElevationTable::evaluations)
      .def_property_readonly("exact_intervals", &ElevationTable::exact_intervals)
      .def_property_readonly("elevations", [](const ElevationTable& t) {
        std::vector<double> deg;
        for (double e : t.elevations()) deg.push_back(e * 180.0 / kPi);
        return values_to_array(deg);
      });

  m.attr("_stop_names") = py::make_tuple(trace_stop_name(TraceStop::kMaxLength),
                                         trace_stop_name(TraceStop::kStopHeight),
                                         trace_stop_name(TraceStop::kVisitor));
}

}  // namespace refracta
