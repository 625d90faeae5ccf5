// solve_edit: validation, the insensitive-parameter check, the strategy (a local solve, or the
// default: local, then the global stage and local solves from its best points), the measured
// result; with several starts, the strategy from each, the best result kept.
#include "refracta/edit/solve.h"

#include "refracta/core/rng.h"
#include "refracta/edit/global_stage.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace refracta {

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

// auto: the global stage's traces take at most this many steps; a design point needing more for
// some pair ranks last (cost +inf). Only trial atmospheres that duct a ray over its whole range need
// that many (issue 23: a 1 km pair at k_s = -300, 315 000; a 1e7 m pair, 10 million, 10 s a trace,
// which made the design take minutes); ordinary pairs need hundreds to thousands (1e7 m of
// straight-ish air: 12 000 at the solve's tolerance, fewer at the design's).
constexpr int64_t kDesignMaxSteps = 100'000;

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

// Each free parameter's effect at x: its Jacobian column's norm times its bounds' width (empty
// where the pairs cannot be traced there).
std::vector<double> effects_at(const EditProblem& problem, const std::vector<double>& x) {
  std::vector<double> r, jacobian;
  if (!problem.evaluate(x, &r, &jacobian)) return {};
  const int m = problem.num_free();
  std::vector<double> effect(m, 0.0);
  for (int j = 0; j < m; ++j) {
    double norm2 = 0.0;
    for (int k = 0; k < problem.num_residuals(); ++k) norm2 += std::pow(jacobian[size_t(k) * m + j], 2);
    effect[j] = std::sqrt(norm2) * (problem.upper()[j] - problem.lower()[j]);
  }
  return effect;
}

bool negligible(const std::vector<double>& effect, int j) {
  const double largest = *std::max_element(effect.begin(), effect.end());
  return effect[j] == 0.0 || effect[j] <= kInsensitive * largest;
}

// The free parameters no pair depends on: negligible at the start and at every probe -- the
// centre of the bounds, then each free parameter alone moved to a quarter and three quarters of
// its search box (the unit box: geometric for log-searched ones) -- probes evaluated only while a
// parameter is still negligible at every one before them. At the start alone a parameter can be
// idle only there -- the default air's surface_depth while its surface_dt is 0, a hot spot's x
// and z while its dt is 0 -- and was held fixed, so that the solve then reported no answer where
// one lay inside the bounds (a trial); at the centre too where that is the same idle value (an
// inversion_dt bounded by [-30, 30] K idles inversion_base and inversion_thickness at both:
// another trial), and moving every parameter at once put the layer kilometres above the paths.
std::vector<std::string> insensitive_params(const EditProblem& problem) {
  const std::vector<double> at_start = effects_at(problem, problem.start());
  if (at_start.empty()) return {};
  const int m = problem.num_free();
  std::vector<bool> idle(size_t(m), false);
  for (int j = 0; j < m; ++j) idle[size_t(j)] = negligible(at_start, j);
  std::vector<std::vector<double>> probes;
  std::vector<double> centre = problem.start();
  for (int j = 0; j < m; ++j) {
    const double mid = 0.5 * (problem.lower()[j] + problem.upper()[j]);
    if (std::isfinite(mid)) centre[size_t(j)] = mid;
  }
  probes.push_back(centre);
  for (int k = 0; k < m; ++k) {
    for (const double u : {0.25, 0.75}) {
      std::vector<double> probe = problem.start();
      probe[size_t(k)] = problem.from_unit(k, u);
      probes.push_back(probe);
    }
  }
  for (const std::vector<double>& probe : probes) {
    if (std::none_of(idle.begin(), idle.end(), [](bool b) { return b; })) break;
    const std::vector<double> effect = effects_at(problem, probe);
    if (effect.empty()) continue;  // the pairs cannot be traced there
    for (int j = 0; j < m; ++j) idle[size_t(j)] = idle[size_t(j)] && negligible(effect, j);
  }
  std::vector<std::string> out;
  const auto names = problem.free_names();
  for (int j = 0; j < m; ++j) {
    if (idle[size_t(j)]) out.push_back(names[j]);
  }
  return out;
}

std::string concat_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
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
  Strategy(const EditProblem& problem, const SolveSettings& settings, SolveBudget& budget, SolveSummary* out)
      : problem_(problem), settings_(settings), budget_(budget), out_(out) {}

  BackendResult run() {
    if (budget_.exhausted() == StopReason::kTimeLimit) {
      // The time ran out while the start was measured: the result is the start, with no stage
      // begun (a local solve's first evaluation, no longer interrupted, ran to its end).
      stopped("the first stage");
      BackendResult start;
      start.x = problem_.start();
      start.stopped = StopReason::kTimeLimit;
      start.message = "the start, measured; stopped by the time limit";
      return start;
    }
    if (settings_.strategy == SolveStrategy::kLocal) {
      Attempt attempt = local(problem_.start(), remaining_settings());
      if (attempt.result.stopped != StopReason::kNone) stage("local from the start", attempt);
      return attempt.result;
    }
    const int pairs = int(problem_.pairs().size());

    // 1. A short local solve from the start: most edits end here.
    SolveSettings quick = remaining_settings();
    quick.max_iterations = std::min(quick.max_iterations, settings_.quick_iterations);
    quick.max_evaluations = std::min(quick.max_evaluations, kNloptEvaluationsPerIteration * settings_.quick_iterations);
    Attempt best = local(problem_.start(), quick);
    stage("local from the start", best);
    for (int extension = 0; extension < kQuickExtensions && !best.all_met && !best.result.converged &&
                            settings_.backend == SolveBackend::kCeres && still_falling(best.result.history) &&
                            budget_.iterations_left() >= quick.max_iterations && !stopped("going on locally");
         ++extension) {
      Attempt more = local(best.result.x, continuing(quick, best.result));
      stage("local, continued (the cost still fell)", more);
      if (!(more.cost <= best.cost)) break;
      best = std::move(more);
    }
    if (best.all_met && !best.result.converged && !stopped("finishing the local solve")) {
      // Met but still converging (LM's last iterations gain digits quadratically): finish it.
      Attempt finished = local(best.result.x, continuing(remaining_settings(), best.result));
      stage("local, continued", finished);
      if (finished.all_met) best = std::move(finished);
    }
    if (best.all_met || stopped("the global stage")) return best.result;

    // 2. The global stage.
    const double design_begin = budget_.seconds();
    double longest = 0.0;
    for (const PointPair& pair : problem_.pairs()) longest = std::max(longest, pair.range());
    const auto coarse = problem_.with_tolerance(std::max(problem_.pair_options().tol, kDesignTolerance * longest),
                                                kDesignMaxSteps);
    Design design = evaluate_design(*coarse, settings_.design_per_param, budget_);
    traces_ += coarse->context().pair_evaluations.load();
    const int64_t failed = std::count_if(design.points.begin(), design.points.end(), [](const DesignPoint& p) {
      return !std::isfinite(p.cost);
    }) - (int64_t(design.points.size()) - design.evaluated);
    std::string line = concat("global: ", design.evaluated, " of ", design.points.size(), " design points (",
                              settings_.design_per_param,
                              " on each free parameter's axis, the rest quasi-random over the box and near the start) in ",
                              budget_.seconds() - design_begin, " s; lowest cost ", design.points.front().cost, " m^2 (",
                              design.points.front().label, ")");
    if (failed > 0) line += concat("; ", failed, " could not trace every pair");
    if (design.stopped != StopReason::kNone) {
      line += concat("; stopped by the ", stop_reason_name(design.stopped));
      note_stop(design.stopped);
    }
    out_->stages.push_back(line);
    for (const DesignPoint& p : design.points) {
      if (!p.vertical.empty()) sampled_.push_back(p.vertical);
    }

    // 3. Local solves from the best points (the first solve's end competes with them), until one
    // meets every pair.
    design.points.push_back({best.result.x, best.cost, "the end of the first local solve", {}});
    std::stable_sort(design.points.begin(), design.points.end(),
                     [](const DesignPoint& a, const DesignPoint& b) { return a.cost < b.cost; });
    const std::vector<DesignPoint> starts = spread_best(problem_, design.points, settings_.local_starts, kStartSpacing);
    for (size_t k = 0; k < starts.size(); ++k) {
      const DesignPoint& start = starts[k];
      if (stopped("the local solves from the design")) break;
      // nlopt: an equal share of the evaluations left for each start still to come. A derivative-free
      // solve creeping through a basin of ducting trial atmospheres (100 ms an evaluation for a 1 km
      // pair at k_s = -193) took the whole budget from the first start (a trial: 2 597 evaluations,
      // 300 s, the other starts never tried). LM ends such a basin itself (its trust region shrinks).
      SolveSettings settings = remaining_settings();
      if (settings_.backend != SolveBackend::kCeres) {
        settings.max_evaluations = std::max(1, settings.max_evaluations / int(starts.size() - k));
      }
      Attempt attempt = local(start.x, settings);
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
  int64_t design_traces() const { return traces_; }
  StopReason stopped_by() const { return stopped_by_; }
  // Per sampled atmosphere of the global stage, each pair's vertical residual (global_stage.h).
  const std::vector<std::vector<double>>& sampled() const { return sampled_; }

 private:
  // Settings that carry on from where `from` ended: LM's trust region as it had adapted it (a
  // fresh radius would cost its first iterations again).
  static SolveSettings continuing(SolveSettings settings, const BackendResult& from) {
    if (from.trust_region > 0.0) settings.trust_region = from.trust_region;
    return settings;
  }

  // The settings with the limits of a call: what is left of the budget.
  SolveSettings remaining_settings() const {
    SolveSettings s = settings_;
    s.max_iterations = std::max(1, budget_.iterations_left());
    s.max_evaluations = int(std::max<int64_t>(1, std::min<int64_t>(settings_.max_evaluations, budget_.evaluations_left())));
    return s;
  }

  void note_stop(StopReason reason) {
    if (stopped_by_ == StopReason::kNone) stopped_by_ = reason;
  }

  // The limit of the budget that has run out, if any (nlopt counts evaluations only).
  StopReason budget_stop() const {
    const StopReason reason = budget_.exhausted();
    return reason == StopReason::kIterations && settings_.backend != SolveBackend::kCeres ? StopReason::kNone : reason;
  }

  // True (and said in the stages, once) when a limit of the budget leaves nothing for `next`.
  bool stopped(const char* next) {
    const StopReason reason = budget_stop();
    if (reason == StopReason::kNone) return false;
    if (!said_stop_) {
      out_->stages.push_back(concat("stopped by the ", stop_reason_name(reason), " (", budget_.iterations_used(),
                                    " iterations, ", budget_.evaluations_used(), " evaluations, ", budget_.seconds(),
                                    " s) before ", next));
      said_stop_ = true;
    }
    note_stop(reason);
    return true;
  }

  Attempt local(const std::vector<double>& x0, const SolveSettings& settings) {
    Attempt out;
    out.result = settings.backend == SolveBackend::kCeres
                     ? solve_with_ceres(problem_, x0, settings, budget_)
                     : solve_with_nlopt(problem_, settings.nlopt_algorithm, x0, settings, budget_);
    iterations_ += out.result.iterations;
    // A stage's own cap is not a limit of the solve: the solve's stopped_by names only a budget
    // that ran out, and the stage's message its cap (a trial: "nlopt LN_BOBYQA: stopped by the
    // evaluation limit" after 1 150 of 3 000 evaluations).
    if (budget_.exhausted() != StopReason::kNone) note_stop(out.result.stopped);
    if (stopped_at_own_cap(out.result)) {
      const std::string limit = concat("stopped by the ", stop_reason_name(out.result.stopped));
      const std::string cap = concat("stopped at its stage's own cap of ", own_cap(out.result.stopped));
      const size_t at = out.result.message.find(limit);
      out.result.message = at == std::string::npos ? concat(out.result.message, "; ", cap)
                                                   : out.result.message.replace(at, limit.size(), cap);
    }
    // The time limit interrupted the traces: measure this result all the same (later stages see
    // the limit and do not start).
    if (budget_.exhausted() == StopReason::kTimeLimit) budget_.resume_for_measurement();
    std::vector<double> r;
    if (problem_.evaluate(out.result.x, &r)) {
      out.cost = 0.0;
      for (double v : r) out.cost += 0.5 * v * v;
      out.met = problem_.count_met(r, settings_.accept_angle);
      out.all_met = out.met == int(problem_.pairs().size());
      out.result.residuals = std::move(r);  // the summary's cost: not traced again
    }
    return out;
  }

  // Stopped by a cap of its own (the quick start's quick_iterations, an nlopt start's share of the
  // evaluations), not by the solve's budget.
  bool stopped_at_own_cap(const BackendResult& result) const {
    return (result.stopped == StopReason::kIterations || result.stopped == StopReason::kEvaluations) &&
           budget_stop() == StopReason::kNone;
  }
  static const char* own_cap(StopReason reason) {
    return reason == StopReason::kIterations ? "iterations (quick_iterations)"
                                             : "evaluations (the quick start's, or a start's share of max_evaluations)";
  }

  void stage(const std::string& what, const Attempt& attempt) {
    std::string line = concat(what, ": ", attempt.result.iterations, " iterations, cost ", attempt.cost, " m^2, ",
                              attempt.met, " of ", problem_.pairs().size(), " pairs met");
    if (stopped_at_own_cap(attempt.result)) {
      line += concat("; stopped at the stage's own cap of ", own_cap(attempt.result.stopped));
    } else if (attempt.result.stopped != StopReason::kNone) {
      line += concat("; stopped by the ", stop_reason_name(attempt.result.stopped));
    }
    out_->stages.push_back(line);
  }

  const EditProblem& problem_;
  const SolveSettings& settings_;
  SolveBudget& budget_;
  SolveSummary* out_;
  int iterations_ = 0;
  int64_t traces_ = 0;
  StopReason stopped_by_ = StopReason::kNone;
  bool said_stop_ = false;
  std::vector<std::vector<double>> sampled_;
};

// The message explains this many unmet pairs at most.
constexpr int kListedUnmet = 5;

// Singular values of the Jacobian in the unit box below this fraction of the largest count as
// zero for the rank: far below the derivatives' accuracy (automatic derivatives of traces to
// 1e-9 m agree with central differences to ~1e-6, tests/edit/test_03) yet above round-off.
constexpr double kRankTolerance = 1e-8;
// A condition number above this flags the solution as not unique (other parameters meet the
// pairs as well): a unit step along the weakest direction moves the misses by less than 1e-6 of
// the strongest direction's effect, beneath the misses accept_angle allows.
constexpr double kNonUniqueCondition = 1e6;

// Condition number and rank of the Jacobian (unit box) at free values x, and its weakest
// direction (unit box): the right singular vector of its smallest singular value, the combination
// of the free parameters the pairs determine least. False if it failed.
bool jacobian_condition(const EditProblem& problem, const std::vector<double>& x, double* condition, int* rank,
                        Eigen::VectorXd* weakest) {
  std::vector<double> r, jacobian;
  if (!problem.evaluate(x, &r, &jacobian)) return false;
  const int rows = problem.num_residuals(), m = problem.num_free();
  Eigen::MatrixXd J(rows, m);
  for (int k = 0; k < rows; ++k) {
    for (int j = 0; j < m; ++j) J(k, j) = jacobian[size_t(k) * m + j] * problem.dx_du(j, problem.to_unit(j, x[j]));
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double largest = sigma.size() > 0 ? sigma(0) : 0.0;
  *rank = 0;
  for (int i = 0; i < sigma.size(); ++i) *rank += sigma(i) > kRankTolerance * largest;
  *condition = *rank < m || largest == 0.0 ? std::numeric_limits<double>::infinity() : largest / sigma(m - 1);
  *weakest = svd.matrixV().col(svd.matrixV().cols() - 1);
  return true;
}

// A move of this fraction of the search box (unit box) along the weakest direction that still
// meets every pair makes a result not unique, however well conditioned: a trial's 3 pairs were
// met by every surface_dt from 0 to 60 K at condition 2e3. A quarter of the box is far beyond
// what a determined parameter may move (its pairs then miss by metres), and a move this long
// tells a flat valley from a narrow one where the Jacobian alone cannot (the README's two-pair
// edit, firm at a quarter of the box, moves its misses by 8.6 mm to first order across all of it).
constexpr double kUniquenessProbe = 0.25;
// A probe clamped by the box to less than this is not made (a result on a bound, moving out).
constexpr double kShortestProbe = 0.1;

// Whether a move of kUniquenessProbe of the box along `direction` (unit box), either way, still
// meets every pair; sets *met_at to the free values there.
bool met_along(const EditProblem& problem, const std::vector<double>& x, const Eigen::VectorXd& direction,
               double accept_angle, std::vector<double>* met_at) {
  for (const double sign : {1.0, -1.0}) {
    std::vector<double> moved = x;
    double length2 = 0.0;
    for (int j = 0; j < problem.num_free(); ++j) {
      const double u = problem.to_unit(j, x[size_t(j)]);
      const double to = std::clamp(u + sign * kUniquenessProbe * direction(j), 0.0, 1.0);
      length2 += (to - u) * (to - u);
      moved[size_t(j)] = problem.from_unit(j, to);
    }
    if (std::sqrt(length2) < kShortestProbe) continue;
    std::vector<double> r;
    if (problem.evaluate(moved, &r) && problem.all_met(r, accept_angle)) {
      *met_at = moved;
      return true;
    }
  }
  return false;
}

// Why pair i is not met, from the side of its source its path passes at the result and at every
// atmosphere the global stage sampled within the bounds.
std::string why_unmet(const EditProblem& problem, const std::vector<double>& residuals,
                      const std::vector<std::vector<double>>& sampled, size_t i) {
  // A path toward the destination starts at the eye: a source behind it is nearest the eye itself,
  // whose height difference the side below would report (a trial's "passes 1 m above" a source 400 m back).
  const PointPair& pair = problem.pairs()[i];
  if ((pair.source - pair.origin).dot(pair.direction) <= 0.0) {
    return concat("its source lies ", (pair.source - pair.origin).norm(),
                  " m from the eye, behind it as seen toward its destination: no path toward the destination "
                  "comes near it (a source in front of the camera, or another destination)");
  }
  const double vertical = residuals[3 * i + 1] / std::sqrt(problem.pairs()[i].weight);
  const char* side = vertical > 0.0 ? "above" : "below";
  // The miss across the destination's vertical plane: air that varies with height alone bends a
  // path within that plane, so that part stays whatever the solve tries (a trial's source 5 m to
  // the side was called "within reach").
  const Vec3d across(-pair.direction.z(), 0.0, pair.direction.x());  // horizontal, across the plane
  const Vec3d miss(residuals[3 * i], residuals[3 * i + 1], residuals[3 * i + 2]);
  const double sideways = across.norm() > 1e-9 ? std::abs(across.normalized().dot(miss)) / std::sqrt(pair.weight) : 0.0;
  // A path that ends short of the source (on the ground, or turned back) is nearest it at its end:
  // the miss then lies along the way to the source (a trial's path ended on the sea 1.3 km out, and
  // "passes 12.08 m below" a source 20 km away).
  const Vec3d ahead = Vec3d(pair.direction.x(), 0.0, pair.direction.z()).normalized();
  const double short_by = ahead.allFinite() ? -ahead.dot(miss) / std::sqrt(pair.weight) : 0.0;
  if (short_by > std::max(sideways, std::abs(vertical))) {
    return concat("its path ends ", short_by, " m short of the source, ", std::abs(vertical), " m ", side, " it",
                  problem.pair_options().stop_height ? " (on the ground, stop_height: it descends before the source)"
                                                     : " (it ends before the source's range)");
  }
  if (sideways > std::abs(vertical)) {
    return concat("its path passes ", sideways, " m to the side of the source (", std::abs(vertical), " m ", side,
                  " it): air that varies only with height bends a path within its vertical plane, so this miss "
                  "stays; aim the destination toward the source as seen from the eye",
                  pair.pixel ? " (or free the camera's yaw)" : " (a 3D destination does not turn with the camera)");
  }
  std::string out = concat("its path passes ", std::abs(vertical), " m ", side, " the source");
  if (sampled.empty()) return out;
  int above = 0, below = 0;
  for (const auto& point : sampled) {
    above += point[i] > 0.0;
    below += point[i] < 0.0;
  }
  if (above == int(sampled.size()) || below == int(sampled.size())) {
    // "May": the samples can miss a narrow basin (a trial's inversion 60 m up, 20 m thick, in
    // bounds of 5 km and 2 km, was met by none of 208 samples but by a second random start).
    out += concat(", and ", side, " it in all ", sampled.size(),
                  " atmospheres the global stage sampled within the bounds: the destination may lie ",
                  vertical > 0.0 ? "above" : "below", " every image of the source such atmospheres make (",
                  vertical > 0.0 ? "lower" : "raise",
                  " the destination, free another parameter or widen the bounds; or narrow the bounds or add "
                  "starts, as the samples can miss a narrow basin)");
  } else {
    out += concat(" (the sampled atmospheres sent it ", above, " times above and ", below,
                  " times below the source: the destination is within reach, ",
                  problem.pairs().size() > 1 ? "but perhaps not together with the other pairs, or " : "but ",
                  "the solve stopped before it found the atmosphere)");
  }
  return out;
}

// A success from a start that already met every pair says so: the pairs then do not tell the
// start's values from the result's apart (a trial's 38 pairs, met by the start to 8.1 mm of 9.5,
// moved surface_dt from 14 K to 17.4 K chasing sub-millimetre misses, and reported success alone).
void already_met(const EditProblem& problem, double accept_angle, SolveSummary* out) {
  const std::vector<double> start = problem.distances(problem.start());
  for (size_t i = 0; i < start.size(); ++i) {
    if (!(start[i] <= problem.pairs()[i].allowed_miss(accept_angle))) return;
  }
  out->message += ". The start already met every pair: these pairs do not tell its values from the result's (or any "
                  "between) apart; more pairs, or smaller margins and tolerances, pin the parameters down";
}

// Where every pair has a pixel destination and the converged result misses each by at most a
// pixel beyond its margin: the misses in pixels and what to do. Destinations read off a photograph
// are rarely better than half a pixel, which no fit meets at a tenth of one (pixel_tolerance): a
// trial's least-squares optimum, near the truth, was reported as a failure of the atmosphere.
std::string near_miss(const std::vector<PointPair>& pairs, const std::vector<double>& distances,
                      const SolveSettings& settings, bool converged) {
  if (!converged || !(settings.pixel_tolerance > 0.0) || distances.size() != pairs.size()) return "";
  double largest = 0.0, squares = 0.0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (!pairs[i].pixel || !(pairs[i].tolerance > 0.0)) return "";
    const double footprint = pairs[i].tolerance / settings.pixel_tolerance;  // [m] a pixel at the source
    const double pixels = std::max(0.0, distances[i] - pairs[i].margin) / footprint;
    largest = std::max(largest, pixels);
    squares += pixels * pixels;
  }
  constexpr double kNearMiss = 1.0;  // [pixels]
  if (!(largest <= kNearMiss)) return "";
  return concat(". The fit converged with every pair within a pixel of its place beyond its margin (rms ",
                std::sqrt(squares / double(pairs.size())), " px, largest ", largest,
                " px); a pair counts as met within pixel_tolerance = ", settings.pixel_tolerance,
                " px. Destinations read off a photograph are rarely that exact: solve(..., pixel_tolerance=) "
                "of your reading error in pixels counts pairs met within it, and EditResult.uncertainty(pixel_sigma) "
                "says how far that error moves the result (a margin, PointPair(..., margin=), is a dead zone for "
                "less important pairs: the fit stops at its edge nearest the start)");
}

// The free parameters that x leaves on a bound of the search box, into out->at_bounds and its
// message: a fit that stops there may have wanted to go on (a trial's marine layer, 60 m deep,
// fitted 10 m, the default upper bound of surface_depth, with a surface_dt to match).
void on_bounds(const EditProblem& problem, const std::vector<double>& x, SolveSummary* out) {
  constexpr double kOnBound = 1e-6;  // of the parameter's unit width: well below any step a solver takes
  const std::vector<std::string> names = problem.free_names();
  std::string which;
  for (int j = 0; j < problem.num_free(); ++j) {
    const double u = problem.to_unit(j, x[j]);
    if (u > kOnBound && u < 1.0 - kOnBound) continue;
    out->at_bounds.push_back(names[j]);
    const bool upper = u >= 1.0 - kOnBound;
    which += concat(which.empty() ? "" : ", ", names[j], " = ", x[j], " (its ", upper ? "upper" : "lower", " bound ",
                    upper ? problem.upper()[j] : problem.lower()[j], ")");
  }
  if (which.empty()) return;
  out->message += concat(". The result lies on a bound of the search: ", which,
                         "; the best fit may lie beyond it: widen it with bounds={'", out->at_bounds.front(),
                         "': (lower, upper)}");
}

// The strategy from one start (`field`'s values), drawing on the solve's budget: the
// insensitive-parameter check, the strategy, the measured result. Throws NumericalError when the
// start cannot trace every pair.
SolveSummary solve_from(const FieldPtr& field, const std::vector<PointPair>& pairs, const ProblemSpec& spec,
                        const SolveSettings& settings, SolveBudget& budget) {
  auto problem = std::make_unique<EditProblem>(field, pairs, spec, budget.interrupt());
  SolveSummary out;
  out.insensitive = insensitive_params(*problem);
  budget.check_cancelled();
  if (!out.insensitive.empty() && out.insensitive.size() < size_t(problem->num_free())) {
    ProblemSpec reduced = spec;
    reduced.free.clear();
    for (const auto& name : problem->free_names()) {
      if (std::find(out.insensitive.begin(), out.insensitive.end(), name) == out.insensitive.end()) {
        reduced.free.push_back(name);
      }
    }
    for (const auto& name : out.insensitive) reduced.bounds.erase(name);
    problem = std::make_unique<EditProblem>(field, pairs, reduced, budget.interrupt());
  }
  // No pair depends on any free parameter: none is removed (the solver then stays at the start),
  // and the message says why (a trial: camera_yaw with 3D destinations, which do not follow the
  // camera, was advised to "free the camera's yaw").
  const bool all_idle = !out.insensitive.empty() && out.insensitive.size() == size_t(problem->num_free());
  out.free = problem->free_names();
  out.derivatives = derivatives_name(problem->derivatives());
  out.backend = backend_name(settings);
  out.strategy = strategy_name(settings.strategy);
  out.starts = settings.starts;
  std::vector<double> start_residuals;  // kept: the result when the time runs out before any stage
  const auto measure_start = [&] {
    if (!problem->evaluate(problem->start(), &start_residuals)) return std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (double v : start_residuals) sum += v * v;
    return 0.5 * sum;  // EditProblem::cost's
  };
  out.initial_cost = measure_start();
  budget.check_cancelled();
  if (!std::isfinite(out.initial_cost) && budget.exhausted() == StopReason::kTimeLimit) {
    budget.resume_for_measurement();  // the time limit ran out while measuring the start
    out.initial_cost = measure_start();
  }
  if (!std::isfinite(out.initial_cost)) {
    const std::string why = problem->context().first_failure();
    throw_numerical("the start field cannot trace every pair: ", why.empty() ? "evaluation failed" : why);
  }

  const double begin = budget.seconds();
  Strategy strategy(*problem, settings, budget, &out);
  const BackendResult result = strategy.run();
  if (budget.exhausted() == StopReason::kTimeLimit) budget.resume_for_measurement();
  out.time = budget.seconds() - begin;
  out.stopped_by = stop_reason_name(strategy.stopped_by());

  out.values = problem->full_values(result.x);
  out.camera_values = problem->camera_values(result.x);
  out.camera = problem->camera_at(result.x);
  out.history = result.history;
  out.iterations = strategy.iterations();
  out.evaluations = budget.evaluations_used();
  out.pair_traces = problem->context().pair_evaluations.load() + strategy.design_traces();
  out.converged = result.converged;
  out.solver_report = result.report;
  std::vector<double> residuals = result.residuals.empty() && result.x == problem->start() ? start_residuals : result.residuals;
  out.cost = std::numeric_limits<double>::infinity();
  if (residuals.size() == size_t(problem->num_residuals()) || problem->evaluate(result.x, &residuals)) {
    out.cost = 0.0;
    for (double v : residuals) out.cost += 0.5 * v * v;
  }
  out.distances = problem->distances(result.x);

  // Met: within the margin plus accept_angle times the range; why not, where not (the first
  // kListedUnmet pairs: the report's table has every one).
  std::string unmet;
  int unlisted = 0;
  out.met.assign(pairs.size(), 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double allowed = pairs[i].allowed_miss(settings.accept_angle);
    out.met[i] = out.distances[i] <= allowed;
    if (out.met[i]) continue;
    if (std::count(out.met.begin(), out.met.begin() + i, 0) >= kListedUnmet) {
      ++unlisted;
      continue;
    }
    unmet += concat(unmet.empty() ? "" : "; ", "pair ", i, " misses its source by ", out.distances[i],
                    " m (allowed ", allowed, " m)");
    if (residuals.size() == 3 * pairs.size()) unmet += ": " + why_unmet(*problem, residuals, strategy.sampled(), i);
  }
  if (unlisted > 0) unmet += concat("; and ", unlisted, " more pairs");
  // The default strategy succeeds when every pair is met, whatever stopped its last local solve;
  // a lone local solve must also have ended normally.
  out.success = unmet.empty() && (settings.strategy == SolveStrategy::kAuto || result.converged);
  out.message = result.message;
  while (!out.message.empty() && out.message.back() == '.') out.message.pop_back();
  // (Unless the back-end's own message says so already: "stopped by the time limit" twice.)
  const std::string stop = concat("stopped by the ", out.stopped_by);
  const bool said = out.message.size() >= stop.size() && out.message.compare(out.message.size() - stop.size(), stop.size(), stop) == 0;
  // A local solve that converged was not what the budget stopped: the stages after it were.
  if (!out.stopped_by.empty() && !said) {
    out.message += result.converged ? concat(". That local solve converged; the solve as a whole was ", stop,
                                             " before its later stages (see stages)")
                                    : concat(". The solve was ", stop);
  }
  if (!unmet.empty() && all_idle) {
    const bool camera = std::any_of(out.insensitive.begin(), out.insensitive.end(),
                                    [](const std::string& name) { return name.rfind("camera_", 0) == 0; });
    out.message += concat(". Not every pair is met: ", unmet, ". No pair depends on ", concat_names(out.insensitive),
                          camera ? " (camera parameters move only pairs whose destination is a pixel of the camera: "
                                   "PointPair((u, v), source))"
                                 : ": the pairs' paths do not change with them anywhere in their bounds");
  } else if (!unmet.empty()) {
    out.message += concat(". Not every pair is met: ", unmet);
    const std::string near = near_miss(pairs, out.distances, settings, result.converged);
    out.message += near.empty() ? ". None of the atmospheres the solve tried within these free parameters' bounds puts "
                                  "every image where asked: there may be none, or one in a basin the global stage's "
                                  "samples missed (try other starts, or starting values nearer the answer)"
                                : near;
  }
  // At a solution the misses vanish and the Jacobian says which parameter combinations they fix
  // (elsewhere it also carries the turning of the miss vectors, which says nothing about that).
  Eigen::VectorXd weakest;
  const bool conditioned =
      unmet.empty() && jacobian_condition(*problem, result.x, &out.condition, &out.rank, &weakest);
  std::vector<double> also_met;
  const bool flat = conditioned && out.condition <= kNonUniqueCondition &&
                    met_along(*problem, result.x, weakest, settings.accept_angle, &also_met);
  out.unique = conditioned && out.condition <= kNonUniqueCondition && !flat;
  if (conditioned && out.condition > kNonUniqueCondition) {
    out.message += concat(". The solution is not unique: the pairs fix ", out.rank, " of the ", problem->num_free(),
                          " free parameters' combinations (Jacobian rank ", out.rank, ", condition ", out.condition,
                          "); other values of ", concat_names(out.free), " meet them as well");
  } else if (flat) {
    std::string values;
    const std::vector<std::string> names = problem->free_names();
    for (size_t j = 0; j < names.size(); ++j) values += concat(j ? ", " : "", names[j], " = ", also_met[j]);
    out.message += concat(". The solution is not unique: ", values, " (a quarter of the search box along the "
                          "combination the pairs determine least) meets every pair as well (more pairs, or smaller "
                          "tolerances, pin it down)");
  }
  if (out.success) already_met(*problem, settings.accept_angle, &out);
  on_bounds(*problem, result.x, &out);
  const std::string failure = problem->context().first_failure();
  if (!failure.empty()) out.message += concat(". Some trial parameters failed to trace: ", failure);
  return out;
}

// Start k (>= 1) of a multi-start solve: `field` with each of `free`'s parameters drawn uniformly
// within its bounds (spec.bounds, else the model's), from the seed's stream k. Camera parameters
// start at the camera given (a photograph's camera is known to a few degrees; the field is not).
FieldPtr random_start(const FieldPtr& field, const std::vector<std::string>& free, const ProblemSpec& spec,
                      uint64_t seed, int k) {
  Rng rng(seed, uint64_t(k));
  std::vector<double> values = field->param_values();
  for (const std::string& name : free) {
    if (CameraRig::index_of(name) >= 0) continue;
    const size_t index = field->param_index(name);
    const ParamSpec& param = field->param_specs()[index];
    auto [lower, upper] = std::make_pair(param.lower, param.upper);
    if (auto it = spec.bounds.find(name); it != spec.bounds.end()) std::tie(lower, upper) = it->second;
    values[index] = lower + rng.uniform() * (upper - lower);
  }
  return field->with_param_values(values);
}

// A pair counts as met within its met tolerance (accept_angle times its range, or its own): a trace
// less accurate than that could call a pair met that a finer trace misses by metres (a trial: tol
// 1e3 "met" a pair at 5e-10 m that the default tol misses by 2.4 m), and an rk4 step longer than
// the pair's range cannot follow its path at all.
void check_trace_accuracy(const std::vector<PointPair>& pairs, const PairOptions& options, double accept_angle) {
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double allowed = pairs[i].met_tolerance(accept_angle), range = pairs[i].range();
    if (options.trace == TraceMethod::kRk45 && options.tol > allowed) {
      throw_invalid("tol = ", options.tol, " m is more than pair ", i, " may miss its source by (", allowed,
                    " m, accept_angle x its range or its tolerance): a trace that coarse cannot tell a met "
                    "pair; lower tol");
    }
    if (options.trace == TraceMethod::kRk4 && options.step > range) {
      throw_invalid("step = ", options.step, " m is longer than pair ", i, "'s range (", range,
                    " m): rk4 cannot follow its path; lower step");
    }
  }
}

}  // namespace

SolveSummary solve_edit(const FieldPtr& field, const std::vector<PointPair>& pairs,
                        const ProblemSpec& spec, const SolveSettings& settings, WorkControl& control) {
  settings.validate();
  check_trace_accuracy(pairs, spec.pair, settings.accept_angle);
  SolveBudget budget(settings, control);
  SolveSummary best = solve_from(field, pairs, spec, settings, budget);
  if (settings.starts == 1) {
    budget.finish();
    return best;
  }
  // Further starts share what the ones before them left of the budget; the best result is kept
  // (every pair met first, then the lowest cost), with every start's evaluations, traces and time.
  const double initial_cost = best.initial_cost;
  int64_t pair_traces = best.pair_traces;
  double time = best.time;
  int run = 1, best_start = 0;
  std::string stopped = best.stopped_by;
  // Every random start draws the parameters the field given depends on; which of them another
  // start finds no pair depending on there, it holds at their drawn values.
  const std::vector<std::string> free = best.free, insensitive = best.insensitive;
  for (int k = 1; k < settings.starts; ++k) {
    const FieldPtr start = random_start(field, free, spec, settings.seed, k);
    StopReason reason = budget.exhausted();
    if (reason == StopReason::kIterations && settings.backend != SolveBackend::kCeres) reason = StopReason::kNone;
    if (reason != StopReason::kNone) {
      stopped = stop_reason_name(reason);
      break;
    }
    SolveSummary trial;
    try {
      trial = solve_from(start, pairs, spec, settings, budget);
    } catch (const NumericalError&) {
      continue;  // this start cannot trace every pair: try the next
    }
    ++run;
    pair_traces += trial.pair_traces;
    time += trial.time;
    stopped = trial.stopped_by;
    if (std::make_pair(trial.success, -trial.cost) > std::make_pair(best.success, -best.cost)) {
      best = std::move(trial);
      best_start = k;
    }
  }
  if (best_start > 0) {
    // Reported against the field given: a parameter the winning start drew (start 0's free) or
    // optimised (its own free) is changed, even where that start held it (trials: h_ciso drawn
    // from 1 to 87 was listed as held fixed; inversion_base and inversion_thickness, idle at start
    // 0 but solved by start 2, were too); held fixed only what neither did.
    std::vector<std::string> changed = free;
    for (const std::string& name : best.free) {
      if (std::find(changed.begin(), changed.end(), name) == changed.end()) changed.push_back(name);
    }
    std::vector<std::string> held;
    for (const std::string& name : insensitive) {
      if (std::find(changed.begin(), changed.end(), name) == changed.end()) held.push_back(name);
    }
    best.free = changed;
    best.insensitive = held;
  }
  best.initial_cost = initial_cost;
  best.pair_traces = pair_traces;
  best.time = time;
  best.evaluations = budget.evaluations_used();
  best.stopped_by = stopped;
  // The stages above are the best start's ("from the start": from that start's point).
  best.stages.push_back(concat("starts: ", run, " of ", settings.starts, " run",
                               stopped.empty() ? "" : "; stopped by the " + stopped, "; the result is start ",
                               best_start, best_start == 0 ? " (the field given)" : " (random within the bounds)"));
  budget.finish();
  return best;
}

}  // namespace refracta
