// Python bindings of editing (cpp/refracta/edit): the option structs, the solve and the pair
// measures. refracta.edit (Python) builds pairs from cameras and wraps the result.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/edit/solve.h"

#include <optional>

namespace refracta {

namespace {

std::vector<PointPair> make_pairs(const py::object& origins, const py::object& directions,
                                  const py::object& sources, const py::object& weights,
                                  const py::object& margins = py::none(), const py::object& tolerances = py::none()) {
  const std::vector<Vec3d> o = to_points(origins, "eye positions");
  const std::vector<Vec3d> d = to_points(directions, "destination directions");
  const std::vector<Vec3d> s = to_points(sources, "sources");
  const std::vector<double> w =
      weights.is_none() ? std::vector<double>(o.size(), 1.0) : to_values(weights, "weights");
  const std::vector<double> margin =
      margins.is_none() ? std::vector<double>(o.size(), 0.0) : to_values(margins, "margins");
  const std::vector<double> tolerance =
      tolerances.is_none() ? std::vector<double>(o.size(), 0.0) : to_values(tolerances, "tolerances");
  if (o.size() != d.size() || o.size() != s.size() || o.size() != w.size() || o.size() != margin.size() ||
      o.size() != tolerance.size()) {
    throw_invalid("one eye, direction, source, weight, margin and tolerance per pair (got ", o.size(), ", ",
                  d.size(), ", ", s.size(), ", ", w.size(), ", ", margin.size(), ", ", tolerance.size(), ")");
  }
  std::vector<PointPair> pairs(o.size());
  for (size_t i = 0; i < o.size(); ++i) pairs[i] = {o[i], d[i], s[i], w[i], margin[i], tolerance[i]};
  return pairs;
}

FieldPtr checked(const std::shared_ptr<IndexField>& field) {
  if (!field) throw_invalid("field must be an IndexField (got None)");
  return field;
}

Derivatives parse_derivatives(const std::string& name, const IndexField& field) {
  if (name == "automatic") return Derivatives::kAutomatic;
  if (name == "numeric") return Derivatives::kNumeric;
  if (name == "auto") return has_templated_model(field) ? Derivatives::kAutomatic : Derivatives::kNumeric;
  throw_invalid("derivatives must be 'auto', 'automatic' or 'numeric' (got '", name, "')");
}

}  // namespace

void bind_edit(py::module_& m) {
  py::class_<PairOptions>(m, "_PairOptions")
      .def(py::init([](const std::string& method, double tol, std::optional<double> step,
                       std::optional<double> ground, const std::string& distance, double reach) {
             PairOptions o;
             o.method = parse_trace_method(method);
             o.tol = tol;
             o.step = step.value_or(0.0);
             if (step && !(*step > 0.0)) throw_invalid("step must be > 0 (got ", *step, ")");
             o.ground = ground;
             o.distance = parse_pair_distance(distance);
             o.reach = reach;
             o.validate();
             return o;
           }),
           py::arg("method"), py::arg("tol"), py::arg("step"), py::arg("ground"), py::arg("distance"),
           py::arg("reach"));

  py::class_<SolveSettings>(m, "_SolveSettings")
      .def(py::init<>())
      .def_readwrite("backend", &SolveSettings::backend)
      .def_readwrite("strategy", &SolveSettings::strategy)
      .def_readwrite("quick_iterations", &SolveSettings::quick_iterations)
      .def_readwrite("design_per_param", &SolveSettings::design_per_param)
      .def_readwrite("local_starts", &SolveSettings::local_starts)
      .def_readwrite("max_iterations", &SolveSettings::max_iterations)
      .def_readwrite("max_evaluations", &SolveSettings::max_evaluations)
      .def_readwrite("time_limit", &SolveSettings::time_limit)
      .def_readwrite("function_tolerance", &SolveSettings::function_tolerance)
      .def_readwrite("parameter_tolerance", &SolveSettings::parameter_tolerance)
      .def_readwrite("gradient_tolerance", &SolveSettings::gradient_tolerance)
      .def_readwrite("target_cost", &SolveSettings::target_cost)
      .def_readwrite("trust_region", &SolveSettings::trust_region)
      .def_readwrite("loss", &SolveSettings::loss)
      .def_readwrite("loss_scale", &SolveSettings::loss_scale)
      .def_readwrite("accept_angle", &SolveSettings::accept_angle)
      .def_readwrite("pixel_tolerance", &SolveSettings::pixel_tolerance)
      .def("validate", &SolveSettings::validate);

  m.def("_solve_edit",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const py::object& weights, const py::object& margins,
           const py::object& tolerances, const std::vector<std::string>& free,
           const std::map<std::string, std::pair<double, double>>& bounds,
           const std::string& derivatives, const PairOptions& pair_options, const SolveSettings& settings,
           const py::object& progress) {
          ProblemSpec spec;
          spec.free = free;
          spec.bounds = bounds;
          spec.derivatives = parse_derivatives(derivatives, *checked(field));
          spec.pair = pair_options;
          const std::vector<PointPair> pairs = make_pairs(origins, directions, sources, weights, margins, tolerances);
          settings.validate();
          WorkControl control;
          SolveSummary s;
          // Ceres' messages reach Python's logging however the solve ends (a logging error is
          // dropped rather than thrown from a destructor).
          struct EmitLibraryLog {
            ~EmitLibraryLog() {
              try {
                emit_library_log();
              } catch (...) {
              }
            }
          } emit_log;
          run_interruptible(control, progress, [&] { s = solve_edit(field, pairs, spec, settings, control); });
          py::dict out;
          out["values"] = values_to_array(s.values);
          out["free"] = s.free;
          out["insensitive"] = s.insensitive;
          out["backend"] = s.backend;
          out["derivatives"] = s.derivatives;
          out["initial_cost"] = s.initial_cost;
          out["cost"] = s.cost;
          out["distances"] = values_to_array(s.distances);
          out["history"] = values_to_array(s.history);
          out["iterations"] = s.iterations;
          out["evaluations"] = s.evaluations;
          out["pair_traces"] = s.pair_traces;
          out["time"] = s.time;
          out["converged"] = s.converged;
          out["success"] = s.success;
          out["message"] = s.message;
          out["met"] = std::vector<bool>(s.met.begin(), s.met.end());
          out["strategy"] = s.strategy;
          out["stages"] = s.stages;
          out["stopped_by"] = s.stopped_by;
          out["condition"] = s.condition;
          out["rank"] = s.rank;
          out["solver_report"] = s.solver_report;
          return out;
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"),
        py::arg("weights"), py::arg("margins"), py::arg("tolerances"), py::arg("free"), py::arg("bounds"),
        py::arg("derivatives"), py::arg("pair_options"), py::arg("settings"), py::arg("progress"));

  m.def("_pair_distances",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const PairOptions& options) {
          const FieldPtr f = checked(field);
          const auto pairs = make_pairs(origins, directions, sources, py::none());
          std::vector<double> d;
          {
            py::gil_scoped_release release;
            d = pair_distances(*f, pairs, options);
          }
          return values_to_array(d);
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"), py::arg("options"));

  m.def("_pair_jacobian",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const py::object& weights, const py::object& margins,
           const std::vector<std::string>& free, const std::string& derivatives, const PairOptions& options) {
          ProblemSpec spec;
          spec.free = free;
          spec.derivatives = parse_derivatives(derivatives, *checked(field));
          spec.pair = options;
          // Bounds are irrelevant here: open them so any start is accepted.
          for (const auto& name : free) spec.bounds[name] = {-1e300, 1e300};
          EditProblem problem(field, make_pairs(origins, directions, sources, weights, margins), spec, nullptr);
          std::vector<double> r, jacobian;
          bool ok;
          {
            py::gil_scoped_release release;
            ok = problem.evaluate(problem.start(), &r, &jacobian);
          }
          if (!ok) throw_numerical("evaluation failed: ", problem.context().first_failure());
          const py::ssize_t rows = problem.num_residuals(), cols = problem.num_free();
          DoubleArray residuals(rows), jac({rows, cols});
          std::copy(r.begin(), r.end(), residuals.mutable_data());
          std::copy(jacobian.begin(), jacobian.end(), jac.mutable_data());
          return py::make_tuple(residuals, jac, problem.free_names());
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"),
        py::arg("weights"), py::arg("margins"), py::arg("free"), py::arg("derivatives"), py::arg("options"));
}

}  // namespace refracta
