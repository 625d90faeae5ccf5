// solve_edit: validation, the insensitive-parameter check, the strategy (a local solve, or the
// default: local, then the global stage and local solves from its best points), the measured result.
#include "refracta/edit/solve.h"

#include "refracta/edit/global_stage.h"

#include <chrono>
#include <cmath>

namespace refracta {

void SolveSettings::validate() const {
  if (backend != "ceres" && backend.rfind("nlopt:", 0) != 0) {
    throw_invalid("backend must be 'ceres' or 'nlopt:<ALGORITHM>' (got '", backend, "')");
  }
  if (backend.rfind("nlopt:", 0) == 0) check_nlopt_algorithm(backend.substr(6));
  if (strategy != "auto" && strategy != "local") {
    throw_invalid("strategy must be 'auto' or 'local' (got '", strategy, "')");
  }
  if (max_iterations < 1) throw_invalid("max_iterations must be >= 1 (got ", max_iterations, ")");
  if (max_evaluations < 1) throw_invalid("max_evaluations must be >= 1 (got ", max_evaluations, ")");
  if (quick_iterations < 1) throw_invalid("quick_iterations must be >= 1 (got ", quick_iterations, ")");
  if (design_per_param < 1) throw_invalid("design_per_param must be >= 1 (got ", design_per_param, ")");
  if (local_starts < 1) throw_invalid("local_starts must be >= 1 (got ", local_starts, ")");
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

// auto: local solves start from design points at least this far apart (largest coordinate
// difference in the unit box): closer ones would end in the same basin.
constexpr double kStartSpacing = 0.05;

// auto: the global stage traces pairs to this fraction of the longest pair's range: it only ranks
// points whose costs differ by orders of magnitude (1e-7 of 50 m is 5 um).
constexpr double kDesignTolerance = 1e-7;

// auto: a quick Ceres solve that ran out of iterations while its cost still fell at least this
// many times over its last kRecentIterations goes on locally (up to kQuickExtensions more quick
// solves) before the global stage: LM closing in on a minimum needs a few more iterations, far
// cheaper than the global stage (bench_edit: LogisticProfile, 4 pairs, 18 iterations to the
// target). A trapped LM creeps or stalls instead.
constexpr double kStillFalling = 2.0;
constexpr int kRecentIterations = 3;
constexpr int kQuickExtensions = 3;

bool still_falling(const std::vector<double>& history) {
  if (int(history.size()) <= kRecentIterations) return false;
  const double before = history[history.size() - 1 - kRecentIterations], now = history.back();
  return now > 0.0 && before >= kStillFalling * now;
}

// nlopt counts evaluations, not iterations: its first local solve gets this many per iteration
// of quick_iterations (a derivative-free step costs about m + 1 evaluations).
constexpr int kNloptEvaluationsPerIteration = 20;

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

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point begin) {
  return std::chrono::duration<double>(Clock::now() - begin).count();
}

// One local solve and how it ended.
struct Attempt {
  BackendResult result;
  double cost = std::numeric_limits<double>::infinity();
  int met = 0;
  bool all_met = false;
};

class Strategy {
 public:
  Strategy(const EditProblem& problem, const SolveSettings& settings, WorkControl& control, SolveSummary* out)
      : problem_(problem), settings_(settings), control_(control), out_(out), begin_(Clock::now()) {}

  BackendResult run() {
    if (settings_.strategy == "local") return local(problem_.start(), settings_).result;
    const int pairs = int(problem_.pairs().size());

    // 1. A short local solve from the start: most edits end here.
    SolveSettings quick = settings_;
    quick.max_iterations = std::min(settings_.max_iterations, settings_.quick_iterations);
    quick.max_evaluations = std::min(settings_.max_evaluations, kNloptEvaluationsPerIteration * settings_.quick_iterations);
    Attempt best = local(problem_.start(), quick);
    stage("local from the start", best);
    for (int extension = 0; extension < kQuickExtensions && !best.all_met && !best.result.converged &&
                            settings_.backend == "ceres" && still_falling(best.result.history) &&
                            iterations_ + quick.max_iterations <= settings_.max_iterations && !out_of_time();
         ++extension) {
      Attempt more = local(best.result.x, continuing(quick, best.result));
      stage("local, continued (the cost still fell)", more);
      if (!(more.cost <= best.cost)) break;
      best = std::move(more);
    }
    if (best.all_met && !best.result.converged && !out_of_time()) {
      // Met but still converging (LM's last iterations gain digits quadratically): finish it.
      Attempt finished = local(best.result.x, continuing(remaining_settings(), best.result));
      stage("local, continued", finished);
      if (finished.all_met) best = std::move(finished);
    }
    if (best.all_met || out_of_time()) return best.result;

    // 2. The global stage.
    const auto design_begin = Clock::now();
    double longest = 0.0;
    for (const PointPair& pair : problem_.pairs()) longest = std::max(longest, pair.range());
    const auto coarse = problem_.with_tolerance(std::max(problem_.pair_options().tol, kDesignTolerance * longest));
    std::vector<DesignPoint> design = evaluate_design(*coarse, settings_.design_per_param, control_);
    evaluations_ += int64_t(design.size());
    traces_ += coarse->context().pair_evaluations.load();
    const int64_t failed = std::count_if(design.begin(), design.end(),
                                         [](const DesignPoint& p) { return !std::isfinite(p.cost); });
    std::string line = concat("global: ", design.size(), " design points (", settings_.design_per_param,
                              " on each free parameter's axis, the rest quasi-random over the box and near the start) in ",
                              seconds_since(design_begin), " s; lowest cost ", design.front().cost, " m^2 (",
                              design.front().label, ")");
    if (failed > 0) line += concat("; ", failed, " could not trace every pair");
    out_->stages.push_back(line);

    // 3. Local solves from the best points (the first solve's end competes with them), until one
    // meets every pair.
    design.push_back({best.result.x, best.cost, "the end of the first local solve"});
    std::stable_sort(design.begin(), design.end(),
                     [](const DesignPoint& a, const DesignPoint& b) { return a.cost < b.cost; });
    for (const DesignPoint& start : spread_best(problem_, design, settings_.local_starts, kStartSpacing)) {
      if (out_of_time()) break;
      Attempt attempt = local(start.x, remaining_settings());
      stage(concat("local from a design point (", start.label, ", cost ", start.cost, " m^2)"), attempt);
      if (std::make_pair(attempt.all_met, -attempt.cost) > std::make_pair(best.all_met, -best.cost)) {
        best = std::move(attempt);
      }
      if (best.all_met) break;
    }
    if (!best.all_met) {
      out_->stages.push_back(concat("no start met every pair; the best met ", best.met, " of ", pairs));
    }
    return best.result;
  }

  int iterations() const { return iterations_; }
  int64_t evaluations() const { return evaluations_; }
  int64_t design_traces() const { return traces_; }

 private:
  // Settings that carry on from where `from` ended: LM's trust region as it had adapted it (a
  // fresh radius would cost its first iterations again).
  static SolveSettings continuing(SolveSettings settings, const BackendResult& from) {
    if (from.trust_region > 0.0) settings.trust_region = from.trust_region;
    return settings;
  }

  Attempt local(const std::vector<double>& x0, const SolveSettings& settings) {
    Attempt out;
    out.result = settings.backend == "ceres"
                     ? solve_with_ceres(problem_, x0, settings, control_)
                     : solve_with_nlopt(problem_, settings.backend.substr(6), x0, settings, control_);
    iterations_ += out.result.iterations;
    evaluations_ += out.result.evaluations;
    std::vector<double> r;
    if (problem_.evaluate(out.result.x, &r)) {
      out.cost = 0.0;
      for (double v : r) out.cost += 0.5 * v * v;
      out.met = problem_.count_met(r, settings_.accept_angle);
      out.all_met = out.met == int(problem_.pairs().size());
    }
    return out;
  }

  void stage(const std::string& what, const Attempt& attempt) {
    out_->stages.push_back(concat(what, ": ", attempt.result.iterations, " iterations, cost ", attempt.cost,
                                  " m^2, ", attempt.met, " of ", problem_.pairs().size(), " pairs met"));
  }

  bool out_of_time() const { return settings_.max_time > 0.0 && seconds_since(begin_) >= settings_.max_time; }

  SolveSettings remaining_settings() const {
    SolveSettings s = settings_;
    if (s.max_time > 0.0) s.max_time = std::max(1e-3, s.max_time - seconds_since(begin_));
    return s;
  }

  const EditProblem& problem_;
  const SolveSettings& settings_;
  WorkControl& control_;
  SolveSummary* out_;
  Clock::time_point begin_;
  int iterations_ = 0;
  int64_t evaluations_ = 0, traces_ = 0;
};

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
  out.strategy = settings.strategy;
  out.initial_cost = problem->cost(problem->start());
  if (!std::isfinite(out.initial_cost)) {
    const std::string why = problem->context().first_failure();
    throw_numerical("the start field cannot trace every pair: ", why.empty() ? "evaluation failed" : why);
  }

  const auto begin = Clock::now();
  Strategy strategy(*problem, settings, control, &out);
  const BackendResult result = strategy.run();
  out.time = seconds_since(begin);

  out.values = problem->full_values(result.x);
  out.history = result.history;
  out.iterations = strategy.iterations();
  out.evaluations = strategy.evaluations();
  out.pair_traces = problem->context().pair_evaluations.load() + strategy.design_traces();
  out.converged = result.converged;
  out.solver_report = result.report;
  out.cost = problem->cost(result.x);
  out.distances = problem->distances(result.x);

  // Met: within the margin plus accept_angle times the range.
  std::string unmet;
  out.met.assign(pairs.size(), 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double allowed = pairs[i].allowed_miss(settings.accept_angle);
    out.met[i] = out.distances[i] <= allowed;
    if (!out.met[i]) {
      unmet += concat(unmet.empty() ? "" : "; ", "pair ", i, " misses its source by ", out.distances[i],
                      " m (allowed ", allowed, " m)");
    }
  }
  // The default strategy succeeds when every pair is met, whatever stopped its last local solve;
  // a lone local solve must also have ended normally.
  out.success = unmet.empty() && (settings.strategy == "auto" || result.converged);
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
