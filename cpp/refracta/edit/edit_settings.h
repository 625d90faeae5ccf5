// Options of an edit solve and the summary it returns (Ceres' Solver::Options / Summary style:
// every field has a default and a meaning; validate() reports every problem).
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/edit/edit_problem.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace refracta {

// The back-end that minimises the cost: Ceres' Levenberg-Marquardt, or an nlopt algorithm.
enum class SolveBackend { kCeres, kNlopt };
// "auto" (a local solve, then the global stage and local solves from its best points) or "local".
enum class SolveStrategy { kAuto, kLocal };
// Ceres' robust losses on each pair's squared miss (none: plain least squares).
enum class RobustLoss { kNone, kHuber, kSoftL1, kCauchy, kArctan };

// The most design points per free parameter: the whole design is built before it is evaluated
// (2 x this x the free parameters), and 10^5 already takes far longer to evaluate than a solve's
// time limit allows (a pair traces in ~0.1-1 ms); 10^8 filled 23 GB before its first evaluation.
inline constexpr int kMostDesignPerParam = 100000;

// Settings of refracta.edit.solve, with their defaults (defined once, in C++'s SolveSettings). Set
// any field by name, or pass them to solve() as keywords; validate() reports every bad value at
// once.
struct SolveSettings {
  // Python spells the back-end "ceres" or "nlopt:<ALGORITHM>" (any nlopt algorithm name,
  // nlopt_algorithm; checked by validate()).
  SolveBackend backend = SolveBackend::kCeres;
  std::string nlopt_algorithm;
  // "auto": a short local solve from the start (ceres: continued while its cost still falls,
  // solve.cpp's kStillFalling); if it does not meet every pair, the global stage
  // (global_stage.h: axis scans through the start and quasi-random points of the free box, costs
  // in parallel) and local solves from its best points until one meets every pair. "local": the
  // back-end from the start only (the behaviour before strategies).
  SolveStrategy strategy = SolveStrategy::kAuto;
  // auto: iterations of the first local solve (and of each continuation). Measured on
  // benchmarks/bench_edit.py: LM meets, or is still closing in on, every case it solves from its
  // start at all within 15 iterations.
  int quick_iterations = 15;
  // auto: points per free parameter of the global stage (scan points on its axis; as many again
  // quasi-random points, half over the box, half near the start), at most 100000 (kMostDesignPerParam).
  int design_per_param = 16;
  // auto: local solves from the global stage's best points, at most.
  int local_starts = 4;
  // Limits of the whole solve: every stage (the first local solve, its continuations, the global
  // stage's design points, the local solves from them, and every start) draws on one budget. What
  // stopped a stage is named in SolveSummary::stages.
  int max_iterations = 200;        // LM iterations of the whole solve (ceres); nlopt has none: max_evaluations stops it
  // Cost evaluations of the whole solve, each tracing every pair (ceres: residual and Jacobian passes; nlopt: every
  // call of the objective; the global stage: every design point).
  int max_evaluations = 3000;
  // [s] wall-clock limit of the solve from its call; 0: none. A trace running when it expires is
  // interrupted (EvaluationContext's flag, polled every step), and the solve then measures the best
  // point found (its misses: one or two evaluations more, not interrupted -- seconds where that
  // point itself ducts a long ray: 28 s over the limit for the 1e7 m pair, before its
  // residuals were reused; a fraction of a second for ordinary pairs). 300 s is generous: the slowest
  // edit of benchmarks/bench_edit.py takes under a second, while a trial atmosphere that ducts a
  // ray over a long path costs seconds per evaluation (issue 23: 7.7 M steps for 150 km).
  double time_limit = 300.0;
  double function_tolerance = 1e-14;   // relative change of the cost that ends the solve
  double parameter_tolerance = 1e-12;  // relative change of the parameters that ends the solve
  double gradient_tolerance = 1e-16;   // ceres: max-norm of the projected gradient
  double target_cost = 0.0;        // [m^2] stop once the cost is <= this (0: never early)
  // ceres: initial trust-region radius of Levenberg-Marquardt in the unit box of the free
  // parameters (1 = each parameter's whole bound range). Cautious first steps keep LM out of the
  // flat regions of narrow layers (a logistic inversion far from every ray) that a bold first
  // step lands in; measured on benchmarks/bench_edit.py: 1e4 (Ceres' default) fails the 16-pair
  // logistic case, 0.1 solves every case.
  double trust_region = 0.1;
  // Ceres robust loss on each pair's squared miss (Python: "none", "huber", "soft_l1", "cauchy",
  // "arctan"); loss_scale [m] is the miss where it starts to down-weight.
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 1.0;  // [m] the miss where the robust loss starts to down-weight
  // A pair is met when its miss beyond its margin is at most accept_angle * (eye-to-source
  // distance) [rad], or its tolerance if larger (PointPair::allowed_miss): 1e-6 rad is far below a
  // pixel of any camera.
  double accept_angle = 1e-6;
  // [pixels] a pair with a pixel destination is met when its miss is within its margin plus this
  // fraction of the pixel's footprint at the source (the camera's pixel angle times the source's
  // range; PointPair::tolerance), when that exceeds accept_angle times its range. A tenth of a
  // pixel cannot be seen in the image, and it spares an edit from failing on a miss of 0.01 px
  // (issue 23: 5.9 mm at 1.9 km). It judges the result only: the cost still pulls every pair onto
  // its source. refracta.edit.solve converts it to metres per pair (C++ sees metres only).
  double pixel_tolerance = 0.1;
  // Starts of the whole strategy: the first from the field as given, the others uniformly random
  // within the free parameters' bounds (seeded by `seed`); the best result is kept (every pair
  // met first, then the lowest cost). All starts share the budget above; a start whose field
  // cannot trace every pair is skipped.
  int starts = 1;
  uint64_t seed = 0;  // seed of the random starts

  // Throws std::invalid_argument listing every bad field.
  void validate() const;
};

// "ceres" or "nlopt:<ALGORITHM>"; parse_backend sets backend and nlopt_algorithm (throws
// std::invalid_argument for another spelling; the algorithm name is checked by validate()).
std::string backend_name(const SolveSettings& settings);
void parse_backend(const std::string& name, SolveSettings* settings);
const char* strategy_name(SolveStrategy strategy);    // "auto", "local"
SolveStrategy parse_strategy(const std::string& name);
const char* loss_name(RobustLoss loss);               // "none", "huber", "soft_l1", "cauchy", "arctan"
RobustLoss parse_loss(const std::string& name);

// What an edit solve returned (read-only; refracta.edit.EditResult forwards its fields, values
// aside: there the solved field, EditResult.field, holds them).
struct SolveSummary {
  std::vector<double> values;        // every parameter of the solved field
  // With camera parameters free: every camera parameter at the result (CameraRig::names() order:
  // yaw, pitch, roll offsets and vfov [deg]) and the solved camera; else empty and none.
  std::vector<double> camera_values;
  std::optional<Camera> camera;
  std::vector<std::string> free;     // the parameters that were optimised
  // Requested free, but no pair depends on them: held fixed (when none is depended on, left free
  // and reported: the solver stays at the start).
  std::vector<std::string> insensitive;
  // Free parameters the result left on a bound of the search box (within 1e-6 of its unit width):
  // the best fit may lie beyond it (the message says which bound, and how to widen it).
  std::vector<std::string> at_bounds;
  std::string backend, derivatives;
  double initial_cost = 0.0, cost = 0.0;   // 1/2 sum of weight * miss^2 [m^2]
  std::vector<double> distances;     // per pair, unweighted [m]
  std::vector<double> history;       // cost per iteration (ceres) or best cost per evaluation (nlopt)
  int iterations = 0;                // of the start that gave the result
  int64_t evaluations = 0;           // cost evaluations (each traces every pair), every start's
  int64_t pair_traces = 0;           // traced pairs, derivative passes included, every start's
  double time = 0.0;                 // [s] solving, set-up excluded, every start's
  bool converged = false;            // the back-end ended normally
  bool success = false;              // every pair met (and, for the local strategy, converged)
  std::vector<char> met;             // per pair: miss <= PointPair::allowed_miss(accept_angle)
  std::string message;
  std::string strategy;              // "auto" or "local"
  int starts = 1;                    // starts asked for (SolveSettings::starts)
  // What the strategy did, one line per stage, and what stopped it (several starts: the best
  // start's stages, then a line "starts: k of n run").
  std::vector<std::string> stages;
  // What stopped the solve before its strategy finished: "" (nothing), "iteration limit",
  // "evaluation limit", "time limit".
  std::string stopped_by;
  // The Jacobian of the residuals in the free parameters' unit box at a result that meets every
  // pair (else 0 and 0): its singular
  // values' ratio (largest / smallest; inf when rank-deficient) and numerical rank. A large
  // condition number means the pairs fix some combination of the free parameters only weakly:
  // other parameter values meet them as well (SolveSummary::message says so).
  double condition = 0.0;
  int rank = 0;
  // Every pair met, and the pairs fix every free parameter: condition <= 1e6, and a move of a
  // quarter of the search box (unit box) either way along the combination they determine least
  // no longer meets every pair: no other values meet them as well. An underdetermined solve (one
  // landmark, five free parameters) succeeds, but not uniquely.
  bool unique = false;
  std::string solver_report;         // the back-end's own report of the run that gave the result
};

// Why a back-end or stage stopped before it converged.
enum class StopReason { kNone, kIterations, kEvaluations, kTimeLimit };
const char* stop_reason_name(StopReason reason);  // "", "iteration limit", "evaluation limit", "time limit"

// The one budget of a solve (SolveSettings' max_iterations, max_evaluations, time_limit), shared
// by its stages, with its progress and stopping. A watcher thread raises interrupt() when the
// caller cancels (WorkControl::cancel) or the time limit passes; traces poll it every step
// (EditProblem's cancel flag), so neither waits for a long evaluation to end. Progress:
// control.done of control.total = kProgressTotal is the largest fraction used of the three limits.
class SolveBudget {
 public:
  static constexpr int64_t kProgressTotal = 1000;

  SolveBudget(const SolveSettings& settings, WorkControl& control);
  ~SolveBudget();  // stops the watcher
  SolveBudget(const SolveBudget&) = delete;
  SolveBudget& operator=(const SolveBudget&) = delete;

  const std::atomic<bool>* interrupt() const { return &interrupt_; }
  bool cancelled() const { return control_.cancel.load(); }
  // Throws Cancelled once the caller has cancelled.
  void check_cancelled() const;

  void spend_iterations(int n);
  void spend_evaluations(int64_t n);
  int iterations_left() const { return std::max(0, max_iterations_ - iterations_.load()); }
  int64_t evaluations_left() const { return std::max<int64_t>(0, max_evaluations_ - evaluations_.load()); }
  int iterations_used() const { return iterations_.load(); }
  int64_t evaluations_used() const { return evaluations_.load(); }
  double seconds() const;
  double seconds_left() const;  // +inf without a limit
  // The first limit used up (time, evaluations, iterations), or kNone.
  StopReason exhausted() const;
  // After the time limit interrupted the work: lets the result be measured (the interrupt stays
  // raised for a cancellation).
  void resume_for_measurement();
  // Progress complete (the solve has ended).
  void finish();

 private:
  void update_progress();

  WorkControl& control_;
  const int max_iterations_;
  const int64_t max_evaluations_;
  const double time_limit_;
  const std::chrono::steady_clock::time_point begin_;
  std::atomic<int> iterations_{0};
  std::atomic<int64_t> evaluations_{0};
  std::atomic<bool> interrupt_{false}, timed_out_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread watcher_;
};

// What a back-end reports; solve() completes the summary.
struct BackendResult {
  std::vector<double> x;             // free values
  std::vector<double> history;
  int iterations = 0;
  int64_t evaluations = 0;
  bool converged = false;
  StopReason stopped = StopReason::kNone;  // a limit of the call or of the solve's budget
  std::vector<double> residuals;     // at x, once the strategy has measured them (else empty)
  double trust_region = 0.0;         // ceres: the radius at the end (a continued solve starts there); 0: none
  std::string message;
  std::string report;                // ceres: Solver::Summary::FullReport(); nlopt: the message
};

// The back-ends, from free values x0 (inside the bounds). settings' max_iterations and
// max_evaluations bound this call (the strategy passes what is left of the budget, or less), and
// the budget's time limit and interrupt stop it; every evaluation is spent from the budget. The
// result is the best point evaluated when the back-end's own end point is not usable.
BackendResult solve_with_ceres(const EditProblem& problem, const std::vector<double>& x0,
                               const SolveSettings& settings, SolveBudget& budget);
BackendResult solve_with_nlopt(const EditProblem& problem, const std::string& algorithm,
                               const std::vector<double>& x0, const SolveSettings& settings,
                               SolveBudget& budget);
// Throws std::invalid_argument for a name nlopt does not know.
void check_nlopt_algorithm(const std::string& algorithm);

}  // namespace refracta
