// Python bindings of editing (cpp/refracta/edit): SolveSettings and PairOptions (options, pickled
// through their fields), SolveSummary (a read-only result), the solve, the pair measures and the
// pairs' paths. refracta.edit (Python) builds pairs from cameras and wraps the result.
#include "generated/docstrings.h"
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/edit/solve.h"

#include <pybind11/eigen.h>

#include <functional>
#include <optional>

namespace refracta {

namespace {

using Values = std::optional<std::vector<double>>;  // per pair (None: the library's default)

std::vector<PointPair> make_pairs(const py::object& origins, const py::object& directions, const py::object& sources,
                                  const Values& weights = {}, const Values& margins = {},
                                  const Values& tolerances = {}, const std::optional<PixelRows>& pixels = {}) {
  return make_point_pairs(to_points(origins, "eye positions"), to_points(directions, "destination directions"),
                          to_points(sources, "sources"), weights.value_or(std::vector<double>()),
                          margins.value_or(std::vector<double>()), tolerances.value_or(std::vector<double>()),
                          pixels.value_or(PixelRows()));
}

FieldPtr checked(const std::shared_ptr<IndexField>& field) {
  if (!field) throw_invalid("field must be an IndexField (got None)");
  return field;
}

ProblemSpec make_spec(const std::shared_ptr<IndexField>& field, const std::vector<std::string>& free,
                      const std::string& derivatives, const PairOptions& options,
                      const std::optional<Camera>& camera) {
  ProblemSpec spec;
  spec.free = free;
  spec.camera = camera;
  spec.derivatives = parse_derivatives(derivatives, *checked(field));
  spec.pair = options;
  return spec;
}

void bind_solve_settings(py::module_& m) {
  using S = SolveSettings;
  py::class_<S> cls(m, "SolveSettings", DOC(refracta, SolveSettings));
  def_options_common<S>(cls, "SolveSettings")
      .def_property("backend", &backend_name, [](S& s, const std::string& v) { parse_backend(v, &s); },
                    "'ceres' (Levenberg-Marquardt, automatic derivatives) or 'nlopt:<ALGORITHM>' (any nlopt name)")
      .def_readwrite("quick_iterations", &S::quick_iterations, DOC(refracta, SolveSettings, quick_iterations))
      .def_readwrite("design_per_param", &S::design_per_param, DOC(refracta, SolveSettings, design_per_param))
      .def_readwrite("local_starts", &S::local_starts, DOC(refracta, SolveSettings, local_starts))
      .def_readwrite("max_iterations", &S::max_iterations, DOC(refracta, SolveSettings, max_iterations))
      .def_readwrite("max_evaluations", &S::max_evaluations, DOC(refracta, SolveSettings, max_evaluations))
      .def_readwrite("time_limit", &S::time_limit, DOC(refracta, SolveSettings, time_limit))
      .def_readwrite("function_tolerance", &S::function_tolerance, DOC(refracta, SolveSettings, function_tolerance))
      .def_readwrite("parameter_tolerance", &S::parameter_tolerance, DOC(refracta, SolveSettings, parameter_tolerance))
      .def_readwrite("gradient_tolerance", &S::gradient_tolerance, DOC(refracta, SolveSettings, gradient_tolerance))
      .def_readwrite("target_cost", &S::target_cost, DOC(refracta, SolveSettings, target_cost))
      .def_readwrite("trust_region", &S::trust_region, DOC(refracta, SolveSettings, trust_region))
      .def_readwrite("loss_scale", &S::loss_scale, DOC(refracta, SolveSettings, loss_scale))
      .def_readwrite("accept_angle", &S::accept_angle, DOC(refracta, SolveSettings, accept_angle))
      .def_readwrite("pixel_tolerance", &S::pixel_tolerance, DOC(refracta, SolveSettings, pixel_tolerance))
      .def_readwrite("starts", &S::starts, DOC(refracta, SolveSettings, starts))
      .def_readwrite("seed", &S::seed, DOC(refracta, SolveSettings, seed));
  def_enum_property(cls, "strategy", &S::strategy, &strategy_name, &parse_strategy,
                    "'auto' (a short local solve; if not every pair is met, the global stage and local solves from "
                    "its best points) or 'local' (the back-end from the start only)");
  def_enum_property(cls, "loss", &S::loss, &loss_name, &parse_loss,
                    "ceres robust loss on each pair's squared miss: 'none', 'huber', 'soft_l1', 'cauchy', 'arctan'");
}

void bind_pair_options(py::module_& m) {
  using P = PairOptions;
  py::class_<P> cls(m, "PairOptions", DOC(refracta, PairOptions));
  def_options_common<P>(cls, "PairOptions")
      .def_readwrite("tol", &P::tol, DOC(refracta, PairOptions, tol))
      .def_readwrite("step", &P::step, DOC(refracta, PairOptions, step))
      .def_readwrite("stop_height", &P::stop_height, DOC(refracta, PairOptions, stop_height))
      .def_readwrite("reach", &P::reach, DOC(refracta, PairOptions, reach))
      .def_readwrite("max_steps", &P::max_steps, DOC(refracta, PairOptions, max_steps));
  def_enum_property(cls, "trace", &P::trace, &trace_method_name, &parse_trace_method,
                    "the ray integrator: 'rk45' (to tol) or 'rk4' (fixed step); 'stratified' has no derivatives");
  def_enum_property(cls, "distance", &P::distance, &pair_distance_name, &parse_pair_distance,
                    "'continuous' (closest approach of the continuous path) or 'vertex' (nearest integrator node)");
}

// SolveSummary's fields: each bound read-only (typed, for the stubs), read as Python sees it and
// set from that (unpickling).
struct SummaryField {
  const char* name;
  std::function<void(py::class_<SolveSummary>&)> bind;
  std::function<py::object(const SolveSummary&)> get;
  std::function<void(SolveSummary&, const py::handle&)> set;
};

template <class T>
SummaryField plain(const char* name, T SolveSummary::*member, const char* doc) {
  return {name, [=](py::class_<SolveSummary>& cls) { cls.def_readonly(name, member, doc); },
          [member](const SolveSummary& s) { return py::cast(s.*member); },
          [member](SolveSummary& s, const py::handle& v) { s.*member = py::cast<T>(v); }};
}

SummaryField array(const char* name, std::vector<double> SolveSummary::*member, const char* doc) {
  auto get = [member](const SolveSummary& s) { return values_to_array(s.*member); };
  return {name, [=](py::class_<SolveSummary>& cls) { cls.def_property_readonly(name, get, doc); },
          [get](const SolveSummary& s) -> py::object { return get(s); },
          [member](SolveSummary& s, const py::handle& v) { s.*member = py::cast<std::vector<double>>(v); }};
}

py::array_t<bool> met_array(const SolveSummary& s) {
  py::array_t<bool> out(py::ssize_t(s.met.size()));
  std::copy(s.met.begin(), s.met.end(), out.mutable_data());
  return out;
}

const std::vector<SummaryField>& summary_fields() {
  using S = SolveSummary;
  static const std::vector<SummaryField> fields = {
      array("values", &S::values, "every parameter of the solved field, in param_names order"),
      array("camera_values", &S::camera_values,
            "with camera parameters free: camera_yaw, camera_pitch, camera_roll (offsets from the start camera) "
            "and camera_vfov [deg] at the result; else empty"),
      plain("camera", &S::camera, "with camera parameters free: the solved Camera; else None"),
      plain("free", &S::free, "the parameters that were optimised"),
      plain("insensitive", &S::insensitive, "requested free, but no pair depends on them: held fixed"),
      plain("at_bounds", &S::at_bounds,
            "free parameters the result left on a bound of the search (the message says which bound): the best "
            "fit may lie beyond it"),
      plain("backend", &S::backend, "'ceres' or 'nlopt:<ALGORITHM>'"),
      plain("derivatives", &S::derivatives, "'automatic' or 'numeric'"),
      plain("initial_cost", &S::initial_cost, "[m^2] 1/2 sum weight * (miss - margin)^2 at the start"),
      plain("cost", &S::cost, "[m^2] the same at the result"),
      array("distances", &S::distances, "[m] each pair's miss at the result"),
      array("history", &S::history, "cost per iteration (ceres) or best cost per evaluation (nlopt)"),
      plain("iterations", &S::iterations, "iterations of the start that gave the result"),
      plain("evaluations", &S::evaluations, "cost evaluations of the whole solve"),
      plain("pair_traces", &S::pair_traces, "traced pairs, derivative passes included"),
      plain("time", &S::time, "[s] solving, set-up excluded"),
      plain("converged", &S::converged, "the back-end ended normally"),
      plain("success", &S::success, "every pair met (strategy 'local': and converged)"),
      {"met",
       [](py::class_<S>& cls) {
         cls.def_property_readonly("met", &met_array, "per pair: its miss is within its margin plus its met tolerance");
       },
       [](const S& s) -> py::object { return met_array(s); },
       [](S& s, const py::handle& v) {
         const auto met = py::cast<std::vector<bool>>(v);
         s.met.assign(met.begin(), met.end());
       }},
      plain("message", &S::message, "what happened, and why a pair is not met"),
      plain("strategy", &S::strategy, "'auto' or 'local'"),
      plain("starts", &S::starts, "starts asked for"),
      plain("stages", &S::stages, "what the strategy did, one line per stage"),
      plain("stopped_by", &S::stopped_by, "'iteration limit', 'evaluation limit', 'time limit' or ''"),
      plain("condition", &S::condition, "the Jacobian's condition number at a result meeting every pair (else 0)"),
      plain("rank", &S::rank, "its numerical rank (else 0)"),
      plain("unique", &S::unique, "every pair met, and the pairs fix every free parameter (condition <= 1e6, and a quarter of the search box along the least-determined combination meets them no longer)"),
      plain("solver_report", &S::solver_report, "the back-end's own report of the run that gave the result"),
  };
  return fields;
}

void bind_solve_summary(py::module_& m) {
  py::class_<SolveSummary> cls(m, "SolveSummary", DOC(refracta, SolveSummary));
  for (const SummaryField& field : summary_fields()) field.bind(cls);
  cls.def("__repr__", [](const py::object& self) {
    return py::str("SolveSummary(success={}, met={}, cost={:.6g}, initial_cost={:.6g}, backend='{}', "
                   "iterations={}, evaluations={}, stopped_by='{}')")
        .format(self.attr("success"), self.attr("met"), self.attr("cost"), self.attr("initial_cost"),
                self.attr("backend"), self.attr("iterations"), self.attr("evaluations"), self.attr("stopped_by"));
  });
  cls.def(py::pickle(
      [](const SolveSummary& s) {
        py::dict state;
        for (const SummaryField& field : summary_fields()) state[field.name] = field.get(s);
        return state;
      },
      [](const py::dict& state) {
        SolveSummary s;
        for (const SummaryField& field : summary_fields()) {
          if (state.contains(field.name)) field.set(s, state[field.name]);
        }
        return s;
      }));
}

}  // namespace

void bind_edit(py::module_& m) {
  bind_solve_settings(m);
  bind_pair_options(m);
  bind_solve_summary(m);

  py::tuple camera_names(CameraRig::kCount);
  for (int k = 0; k < CameraRig::kCount; ++k) camera_names[k] = CameraRig::names()[k];
  m.attr("EDIT_CAMERA_PARAMETERS") = camera_names;

  m.def("_solve_edit",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const Values& weights, const Values& margins, const Values& tolerances,
           const std::vector<std::string>& free, const std::map<std::string, std::pair<double, double>>& bounds,
           const std::string& derivatives, const PairOptions& pair_options, const SolveSettings& settings,
           const py::object& progress, const std::optional<Camera>& camera, const std::optional<PixelRows>& pixels) {
          ProblemSpec spec = make_spec(field, free, derivatives, pair_options, camera);
          spec.bounds = bounds;
          const std::vector<PointPair> pairs =
              make_pairs(origins, directions, sources, weights, margins, tolerances, pixels);
          settings.validate();
          WorkControl control;
          SolveSummary summary;
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
          run_interruptible(control, progress, [&] { summary = solve_edit(field, pairs, spec, settings, control); });
          return summary;
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"), py::kw_only(),
        py::arg("weights"), py::arg("margins"), py::arg("tolerances"), py::arg("free"), py::arg("bounds"),
        py::arg("derivatives"), py::arg("pair_options"), py::arg("settings"), py::arg("progress"),
        py::arg("camera") = py::none(), py::arg("pixels") = py::none());

  m.def(
      "_check_derivatives",
      [](const std::string& derivatives, const std::shared_ptr<IndexField>& field) {
        parse_derivatives(derivatives, *checked(field));
      },
      py::arg("derivatives"), py::arg("field"), DOC(refracta, parse_derivatives));
  m.def("_pair_distances",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const PairOptions& options) {
          const FieldPtr f = checked(field);
          const auto pairs = make_pairs(origins, directions, sources);
          // Ctrl-C stops it: a ducting atmosphere's pairs take seconds each (a code review).
          const std::vector<double> d =
              interruptible_result(py::none(), [&](WorkControl& control) { return pair_distances(*f, pairs, options, control); });
          return values_to_array(d);
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"), py::arg("options"));

  m.def("_pair_paths",
        [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
           const py::object& sources, const PairOptions& options) {
          const FieldPtr f = checked(field);
          const auto pairs = make_pairs(origins, directions, sources);
          std::vector<RayPath> paths =
              interruptible_result(py::none(), [&](WorkControl& control) { return pair_paths(*f, pairs, options, control); });
          std::vector<std::shared_ptr<RayPath>> out;
          for (RayPath& path : paths) out.push_back(std::make_shared<RayPath>(std::move(path)));
          return out;
        },
        py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"), py::arg("options"),
        "Each pair's path, traced by PairOptions' rule for it (what its miss is measured on).");

  m.def(
      "_pair_jacobian",
      [](const std::shared_ptr<IndexField>& field, const py::object& origins, const py::object& directions,
         const py::object& sources, const Values& weights, const Values& margins, const std::vector<std::string>& free,
         const std::string& derivatives, const PairOptions& options, const std::optional<Camera>& camera,
         const std::optional<PixelRows>& pixels) {
        const ProblemSpec spec = make_spec(field, free, derivatives, options, camera);
        std::vector<PointPair> pairs = make_pairs(origins, directions, sources, weights, margins, {}, pixels);
        py::gil_scoped_release release;  // the tuple below holds C++ values: converted after the GIL is back
        const PairJacobian out = pair_jacobian(field, std::move(pairs), spec);
        return std::make_tuple(out.residuals, out.jacobian, out.free);
      },
      py::arg("field"), py::arg("origins"), py::arg("directions"), py::arg("sources"), py::kw_only(),
      py::arg("weights"), py::arg("margins"), py::arg("free"), py::arg("derivatives"), py::arg("options"),
      py::arg("camera") = py::none(), py::arg("pixels") = py::none());
}

}  // namespace refracta
