// solve_edit: validation, the insensitive-parameter check, the back-end, and the measured result.
#include "refracta/edit/solve.h"


#include <chrono>
#include <cmath>

namespace refracta {

void SolveSettings::validate() const {
  if (backend != "ceres" && backend.rfind("nlopt:", 0) != 0) {
    throw_invalid("backend must be 'ceres' or 'nlopt:<ALGORITHM>' (got '", backend, "')");
  }
  if (backend.rfind("nlopt:", 0) == 0) check_nlopt_algorithm(backend.substr(6));
  if (max_iterations < 1) throw_invalid("max_iterations must be >= 1 (got ", max_iterations, ")");
  if (max_evaluations < 1) throw_invalid("max_evaluations must be >= 1 (got ", max_evaluations, ")");
  const std::pair<const char*, double> non_negative[] = {
      {"max_time", max_time}, {"function_tolerance", function_tolerance},
      {"parameter_tolerance", parameter_tolerance}, {"gradient_tolerance", gradient_tolerance},
      {"target_cost", target_cost}, {"accept_angle", accept_angle}};
  if (!(trust_region > 0.0) || !std::isfinite(trust_region)) {
    throw_invalid("trust_region must be > 0 (got ", trust_region, ")");
  }
  for (const auto& [name, value] : non_negative) {
    if (!(value >= 0.0) || !std::isfinite(value)) throw_invalid(name, " must be >= 0 (got ", value, ")");
  }
  if (loss != "none" && loss != "huber" && loss != "soft_l1" && loss != "cauchy" && loss != "arctan") {
    throw_invalid("loss must be 'none', 'huber', 'soft_l1', 'cauchy' or 'arctan' (got '", loss, "')");
  }
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) {
    throw_invalid("loss_scale must be > 0 (got ", loss_scale, ")");
  }
  if (loss != "none" && backend != "ceres") throw_invalid("a robust loss needs backend 'ceres'");
}

namespace {

// Requested free parameters on which no pair depends at the start: a column of the Jacobian
// that, over the parameter's whole bound range, moves no miss by more than this fraction of
// the most influential parameter's effect (or exactly zero). They are held fixed, not left to
// wander in the null space.
constexpr double kInsensitive = 1e-10;

std::vector<std::string> insensitive_params(const EditProblem& problem) {
  std::vector<double> r, jacobian;
  if (!problem.evaluate(problem.start(), &r, &jacobian)) return {};
  const int m = problem.num_free();
  std::vector<double> effect(m, 0.0);
  double largest = 0.0;
  for (int j = 0; j < m; ++j) {
    double norm2 = 0.0;
    for (int k = 0; k < problem.num_residuals(); ++k) norm2 += std::pow(jacobian[size_t(k) * m + j], 2);
    effect[j] = std::sqrt(norm2) * (problem.upper()[j] - problem.lower()[j]);
    largest = std::max(largest, effect[j]);
  }
  std::vector<std::string> out;
  const auto names = problem.free_names();
  for (int j = 0; j < m; ++j) {
    if (effect[j] == 0.0 || effect[j] <= kInsensitive * largest) out.push_back(names[j]);
  }
  return out;
}

}  // namespace

SolveSummary solve_edit(const FieldPtr& field, const std::vector<PointPair>& pairs,
                        const ProblemSpec& spec, const SolveSettings& settings, WorkControl& control) {
  settings.validate();
  auto problem = std::make_unique<EditProblem>(field, pairs, spec, &control.cancel);
  SolveSummary out;
  out.insensitive = insensitive_params(*problem);
  if (!out.insensitive.empty() && out.insensitive.size() < size_t(problem->num_free())) {
    ProblemSpec reduced = spec;
    reduced.free.clear();
    for (const auto& name : problem->free_names()) {
      if (std::find(out.insensitive.begin(), out.insensitive.end(), name) == out.insensitive.end()) {
        reduced.free.push_back(name);
      }
    }
    for (const auto& name : out.insensitive) reduced.bounds.erase(name);
    problem = std::make_unique<EditProblem>(field, pairs, reduced, &control.cancel);
  } else if (!out.insensitive.empty()) {
    out.insensitive.clear();  // nothing depends on anything (e.g. all free params irrelevant):
                              // let the solver report it rather than remove every parameter
  }
  out.free = problem->free_names();
  out.derivatives = derivatives_name(problem->derivatives());
  out.backend = settings.backend;
  out.initial_cost = problem->cost(problem->start());
  if (!std::isfinite(out.initial_cost)) {
    const std::string why = problem->context().first_failure();
    throw_numerical("the start field cannot trace every pair: ", why.empty() ? "evaluation failed" : why);
  }

  const auto begin = std::chrono::steady_clock::now();
  const BackendResult result = settings.backend == "ceres"
                                   ? solve_with_ceres(*problem, settings, control)
                                   : solve_with_nlopt(*problem, settings.backend.substr(6), settings, control);
  out.time = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

  out.values = problem->full_values(result.x);
  out.history = result.history;
  out.iterations = result.iterations;
  out.evaluations = result.evaluations;
  out.pair_traces = problem->context().pair_evaluations.load();
  out.converged = result.converged;
  out.cost = problem->cost(result.x);
  out.distances = problem->distances(result.x);

  // Success: the back-end ended normally and every pair is met.
  std::string unmet;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double allowed = settings.accept_angle * pairs[i].range();
    if (!(out.distances[i] <= allowed)) {
      unmet += concat(unmet.empty() ? "" : "; ", "pair ", i, " misses its source by ", out.distances[i],
                      " m (allowed ", allowed, " m)");
    }
  }
  out.success = result.converged && unmet.empty();
  out.message = result.message;
  while (!out.message.empty() && out.message.back() == '.') out.message.pop_back();
  if (!unmet.empty()) {
    out.message += concat(". Not every pair is met: ", unmet,
                          ". No atmosphere with these free parameters within their bounds puts every "
                          "image where asked, or the solve stopped early");
  }
  const std::string failure = problem->context().first_failure();
  if (!failure.empty()) out.message += concat(". Some trial parameters failed to trace: ", failure);
  return out;
}


}  // namespace refracta
