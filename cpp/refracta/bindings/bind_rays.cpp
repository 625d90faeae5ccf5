// Python bindings of the ray integrators (cpp/refracta/rays): trace_ray, the batch tracer, RayPath.
#include "generated/docstrings.h"
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/core/memory.h"
#include "refracta/rays/astronomical_refraction.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/trace.h"

#include <pybind11/eigen.h>

#include <optional>

namespace refracta {

namespace {

// `method` was the integrator's name before `trace` (README, notebooks): still accepted for one
// release, with a DeprecationWarning (refracta._warn: attributed to the user's line).
py::dict trace_fields(const py::kwargs& fields, const char* owner) {
  py::dict out;
  for (const auto& item : fields) out[item.first] = item.second;
  if (out.contains("method")) {
    if (out.contains("trace")) throw_invalid(owner, ": give trace, not both trace and its old name method");
    py::module_::import("refracta._warn")
        .attr("deprecated")(
            concat(owner, ": method= is deprecated; the integrator is called trace= (TraceOptions.trace)"));
    out["trace"] = out.attr("pop")("method");
  }
  return out;
}

TraceOptions trace_options_from(const py::object& options, const py::kwargs& fields, const char* owner) {
  return options_from<TraceOptions>(options, trace_fields(fields, owner), owner);
}

// progress: True for a bar on stderr, else None / False or a callable progress(done, total).
// The package's one rule (refracta._progress.progress_callback: anything else is a ValueError
// naming progress; a string reached the work and failed as "'str' object is not callable").
py::object progress_callback(const py::object& progress, const char* label) {
  return py::module_::import("refracta._progress").attr("progress_callback")(progress, label);
}

const IndexField& checked_field(const std::shared_ptr<IndexField>& field) {
  if (!field) throw_invalid("field must be an IndexField (got None)");
  return *field;
}

// A batch's ends as numpy arrays (points, directions, lengths, stops, evaluations); _rays.py
// makes the RayBatch.
py::tuple ends_tuple(const RayBatchEnds& ends) {
  return py::make_tuple(points_to_array(ends.points), points_to_array(ends.directions), values_to_array(ends.lengths),
                        py::array(py::cast(ends.stops)), py::array(py::cast(ends.evaluations)));
}

void bind_ray_path(py::module_& m) {
  py::class_<RayPath, std::shared_ptr<RayPath>>(m, "RayPath", DOC(refracta, RayPath))
      .def_property_readonly("points", [](const RayPath& p) { return points_to_array(p.points()); })
      .def_property_readonly("directions", [](const RayPath& p) { return points_to_array(p.directions()); })
      .def_property_readonly("ray_vectors", [](const RayPath& p) { return points_to_array(p.ray_vectors()); })
      .def_property_readonly("arc_length", [](const RayPath& p) { return values_to_array(p.arc_lengths()); })
      .def_property_readonly("ior", [](const RayPath& p) { return values_to_array(p.iors()); })
      .def_property_readonly("length", &RayPath::length, "Arc length of the whole path [m].")
      .def_property_readonly("stop", [](const RayPath& p) { return std::string(trace_stop_name(p.stop())); })
      .def_property_readonly("evaluations", &RayPath::evaluations)
      .def("__len__", [](const RayPath& p) { return p.nodes().size(); })
      // Pickled as its nodes (s, x, v, n, grad n: (N, 11) float64), stop and evaluation count; the
      // copy answers every query exactly as the original.
      .def(py::pickle([](const RayPath& p) { return std::make_tuple(p.packed(), int(p.stop()), p.evaluations()); },
                      [](const std::tuple<RayPath::PackedNodes, int, int64_t>& state) {
                        const auto& [nodes, stop, evaluations] = state;
                        return std::make_shared<RayPath>(RayPath::unpacked(nodes, stop, evaluations));
                      }))
      .def(
          "point_at",
          [](const RayPath& p, double s) {
            Vec3d direction;
            const Vec3d x = p.point_at(s, &direction);
            return std::make_tuple(x, direction);
          },
          py::arg("s"), "(point, unit tangent) at arc length s [m] on the continuous path.")
      .def("sample", [](const RayPath& p, int count) { return points_to_array(p.sample(count)); }, py::arg("count") = 200,
           "count points (count, 3) evenly spaced in arc length on the continuous path.")
      .def(
          "closest_point",
          [](const RayPath& p, const py::object& q) {
            const ClosestPoint c = p.closest_point(to_point(q, "q"));
            return std::make_tuple(c.point, c.distance, c.s);
          },
          py::arg("q"),
          "(point, distance, s): the point of the continuous path closest to q (within 1e7 m of the origin), "
          "its distance [m] and its arc length [m].")
      .def("at_height", [](const RayPath& p, double y) { return points_to_array(p.at_height(y)); }, py::arg("y"),
           "Every point where the path crosses height y [m], in path order, (K, 3).")
      .def(
          "crossings",
          [](const RayPath& p, const py::object& normal, double offset) {
            std::vector<std::tuple<Vec3d, double, Vec3d>> out;
            for (const auto& c : p.crossings(to_point(normal, "normal"), offset)) out.emplace_back(c.point, c.s, c.direction);
            return out;
          },
          py::arg("normal"), py::arg("offset"),
          "Crossings of the plane normal . x = offset: a list of (point, s, unit direction).")
      .def("__repr__", [](const RayPath& p) {
        return concat("RayPath(nodes=", p.nodes().size(), ", length=", p.length(), " m, stop='",
                      trace_stop_name(p.stop()), "')");
      });

}

void bind_trace_options(py::module_& m) {
  py::class_<TraceOptions> options(m, "TraceOptions", DOC(refracta, TraceOptions));
  def_enum_property(def_options_common<TraceOptions>(options, "TraceOptions"), "trace", &TraceOptions::trace, &trace_method_name, &parse_trace_method,
                    "the integrator: 'rk45' (adaptive Dormand-Prince; tol is the target position error [m] over the "
                    "path), 'rk4' (fixed step `step`), or 'stratified' (height-only fields: exact paths from "
                    "n(h) cos(e) = const by quadrature to tol; `step` is the largest node spacing)")
      .def_readwrite("tol", &TraceOptions::tol, DOC(refracta, TraceOptions, tol))
      .def_readwrite("step", &TraceOptions::step,
                     concat("[m] rk4: the fixed step (0: ", kRk4DefaultStep, " m, the original editor's); rk45: the "
                            "largest step (0: none); stratified: the largest node spacing (0: ",
                            kStratifiedDefaultSpacing, " m)")
                         .c_str())
      .def_readwrite("max_length", &TraceOptions::max_length, DOC(refracta, TraceOptions, max_length))
      .def_readwrite("stop_height", &TraceOptions::stop_height, DOC(refracta, TraceOptions, stop_height))
      .def_readwrite("max_steps", &TraceOptions::max_steps, DOC(refracta, TraceOptions, max_steps))
      .def_readwrite("ior_floor", &TraceOptions::ior_floor, DOC(refracta, TraceOptions, ior_floor));

  using E = ElevationTableOptions;
  py::class_<E> table(m, "ElevationTableOptions", DOC(refracta, ElevationTableOptions));
  def_options_common<E>(table, "ElevationTableOptions")
      .def_readwrite("tol", &E::tol, DOC(refracta, ElevationTableOptions, tol))
      .def_readwrite("trace_tol", &E::trace_tol, DOC(refracta, ElevationTableOptions, trace_tol))
      .def_readwrite("initial_rays", &E::initial_rays, DOC(refracta, ElevationTableOptions, initial_rays))
      .def_readwrite("max_rays", &E::max_rays, DOC(refracta, ElevationTableOptions, max_rays))
      .def_readwrite("trace", &E::trace, DOC(refracta, ElevationTableOptions, trace));
}

void bind_tracing(py::module_& m) {
  m.def("trace_ray",
        [](const std::shared_ptr<IndexField>& field, const py::object& origin, const py::object& direction,
           const py::object& options, const py::kwargs& fields) {
          const IndexField& f = checked_field(field);
          TraceOptions cancellable = trace_options_from(options, fields, "trace_ray");
          const Vec3d o = to_point(origin, "origin"), d = to_point(direction, "direction");
          // On a worker thread with the GIL released, like the batch: Ctrl-C stops a long path.
          return interruptible_result(py::none(), [&](WorkControl& control) {
            cancellable.cancel = &control.cancel;
            return std::make_shared<RayPath>(trace_path(f, o, d, cancellable));
          });
        },
        py::arg("field"), py::arg("origin"), py::arg("direction"), py::arg("options") = py::none(), DOC(refracta, trace_path));

  m.def(
      "_astronomical_refraction",
      [](const std::shared_ptr<IndexField>& field, const py::object& elevations, std::optional<double> eye_height,
         std::optional<double> top, std::optional<double> earth_radius, std::optional<double> tol) {
        AstronomicalRefractionOptions options;  // its defaults where None
        options.eye_height = eye_height.value_or(options.eye_height);
        options.top = top;
        options.earth_radius = earth_radius.value_or(options.earth_radius);
        options.tol = tol.value_or(options.tol);
        const std::vector<double> e = to_values(elevations, "apparent elevations");
        return values_to_array(interruptible_result(
            py::none(), [&](WorkControl& control) { return astronomical_refraction(field, e, options, control); }));
      },
      py::arg("field"), py::arg("elevations"), py::arg("eye_height"), py::arg("top"), py::arg("earth_radius"),
      py::arg("tol"), "Refraction [rad] at apparent elevations [rad] (refracta.astronomical_refraction).");

  m.def("_trace_batch",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& options, const py::object& progress, const py::kwargs& fields) {
          const IndexField& f = checked_field(field);
          const TraceOptions checked = trace_options_from(options, fields, "trace_rays");
          // At its peak a ray holds its origin and direction twice (arrays, vectors), its ends and
          // their arrays: 252-284 bytes measured.
          constexpr double kPeakBytesPerRay = 300.0;
          check_work_memory(double(py::len(origins)), kPeakBytesPerRay, "trace_rays", "rays");
          const std::vector<Vec3d> o = to_points(origins, "origins");
          const std::vector<Vec3d> d = to_points(directions, "directions");
          return ends_tuple(interruptible_result(
              progress_callback(progress, "tracing rays"),
              [&](WorkControl& control) { return trace_batch(f, o, d, checked, control); }, int64_t(o.size())));
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("options"), py::arg("progress"));
  m.attr("_stop_names") = py::make_tuple(trace_stop_name(TraceStop::kMaxLength),
                                         trace_stop_name(TraceStop::kStopHeight),
                                         trace_stop_name(TraceStop::kVisitor));
}

std::vector<double> radians(std::vector<double> values) {
  for (double& value : values) value = degrees_to_radians(value);
  return values;
}

std::vector<double> degrees(std::vector<double> values) {
  for (double& value : values) value = radians_to_degrees(value);
  return values;
}

// The Python class ElevationTable (python/refracta/_rays.py) derives from this one: its unit for
// elevations and azimuths is the degree, converted here, the library's being the radian.
void bind_elevation_table(py::module_& m) {
  py::class_<ElevationTable, std::shared_ptr<ElevationTable>>(m, "_ElevationTable")
      .def(py::init([](const std::shared_ptr<IndexField>& field, double eye_height, double min_elevation,
                       double max_elevation, const py::object& options, const py::object& progress,
                       const py::kwargs& fields) {
             checked_field(field);
             ElevationTableOptions checked = options_from<ElevationTableOptions>(options, fields, "ElevationTable", "trace");
             checked.eye_height = eye_height;
             checked.min_elevation = degrees_to_radians(min_elevation);
             checked.max_elevation = degrees_to_radians(max_elevation);
             return interruptible_result(progress_callback(progress, "elevation table"), [&](WorkControl& control) {
               return std::make_shared<ElevationTable>(field, checked, control);
             });
           }),
           py::arg("field"), py::arg("eye_height"), py::arg("min_elevation"), py::arg("max_elevation"),
           py::arg("options"), py::arg("progress"))
      .def(
          "_ends",
          [](const ElevationTable& table, const py::object& elevations, const py::object& azimuths) {
            const std::vector<double> e = radians(to_values(elevations, "elevations"));
            const std::vector<double> a = radians(to_values(azimuths, "azimuths"));
            return ends_tuple(
                interruptible_result(py::none(), [&](WorkControl& control) { return table.ends(e, a, control); }));
          },
          py::arg("elevations"), py::arg("azimuths"), "(points, directions, lengths, stops, evaluations) [deg].")
      .def_property_readonly("options", &ElevationTable::built_options, DOC(refracta, ElevationTable, built_options))
      .def_property_readonly("tol", [](const ElevationTable& t) { return t.options().tol; }, "The interpolation tolerance [m].")
      .def_property_readonly("eye_height", [](const ElevationTable& t) { return t.options().eye_height; }, "[m]")
      .def_property_readonly("size", &ElevationTable::size, "Number of exactly traced elevations.")
      .def_property_readonly("evaluations", &ElevationTable::evaluations, "Field evaluations spent building the table.")
      .def_property_readonly("exact_intervals", &ElevationTable::exact_intervals,
                             "Elevation intervals where queries are traced exactly (unresolved kind changes).")
      .def_property_readonly(
          "elevations", [](const ElevationTable& t) { return values_to_array(degrees(t.elevations())); },
          "The traced elevations [deg].");
}

}  // namespace

void bind_rays(py::module_& m) {
  bind_ray_path(m);
  bind_trace_options(m);
  bind_tracing(m);
  bind_elevation_table(m);
}

}  // namespace refracta
