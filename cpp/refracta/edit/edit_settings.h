// Options of an edit solve and the summary it returns (Ceres' Solver::Options / Summary style:
// every field has a default and a meaning; validate() reports the first problem).
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/edit/edit_problem.h"

#include <string>
#include <vector>

namespace refracta {

struct SolveSettings {
  // "ceres" (Levenberg-Marquardt) or "nlopt:<ALGORITHM>" with any nlopt algorithm name.
  std::string backend = "ceres";
  // "auto": a short local solve from the start (ceres: continued while its cost still falls,
  // solve.cpp's kStillFalling); if it does not meet every pair, the global stage
  // (global_stage.h: axis scans through the start and quasi-random points of the free box, costs
  // in parallel) and local solves from its best points until one meets every pair. "local": the
  // back-end from the start only (the behaviour before strategies).
  std::string strategy = "auto";
  // auto: iterations of the first local solve (and of each continuation). Measured on
  // benchmarks/bench_edit.py: LM meets, or is still closing in on, every case it solves from its
  // start at all within 15 iterations.
  int quick_iterations = 15;
  // auto: points per free parameter of the global stage (scan points on its axis; as many again
  // quasi-random points, half over the box, half near the start).
  int design_per_param = 16;
  // auto: local solves from the global stage's best points, at most.
  int local_starts = 4;
  int max_iterations = 200;        // ceres: LM iterations
  int max_evaluations = 3000;      // nlopt: cost evaluations
  double max_time = 0.0;           // [s]; 0: no limit
  double function_tolerance = 1e-14;   // relative change of the cost that ends the solve
  double parameter_tolerance = 1e-12;  // relative change of the parameters that ends it
  double gradient_tolerance = 1e-16;   // ceres: max-norm of the projected gradient
  double target_cost = 0.0;        // stop once the cost is <= this (0: never early)
  // ceres: initial trust-region radius of Levenberg-Marquardt in the unit box of the free
  // parameters (1 = each parameter's whole bound range). Cautious first steps keep LM out of the
  // flat regions of narrow layers (a logistic inversion far from every ray) that a bold first
  // step lands in; measured on benchmarks/bench_edit.py: 1e4 (Ceres' default) fails the 16-pair
  // logistic case, 0.1 solves every case.
  double trust_region = 0.1;
  // Ceres robust loss on each pair's squared miss: "none", "huber", "soft_l1", "cauchy", "arctan";
  // loss_scale [m] is the miss where it starts to down-weight.
  std::string loss = "none";
  double loss_scale = 1.0;
  // A pair is met when its miss is at most accept_angle * (eye-to-source distance) [rad]:
  // 1e-6 rad is far below a pixel of any camera.
  double accept_angle = 1e-6;

  void validate() const;
};

struct SolveSummary {
  std::vector<double> values;        // every parameter of the solved field
  std::vector<std::string> free;     // the parameters that were optimised
  std::vector<std::string> insensitive;  // requested free, but no pair depends on them: held fixed
  std::string backend, derivatives;
  double initial_cost = 0.0, cost = 0.0;   // 1/2 sum of weight * miss^2 [m^2]
  std::vector<double> distances;     // per pair, unweighted [m]
  std::vector<double> history;       // cost per iteration (ceres) or best cost per evaluation (nlopt)
  int iterations = 0;
  int64_t evaluations = 0;           // cost evaluations (each traces every pair)
  int64_t pair_traces = 0;           // traced pairs, derivative passes included
  double time = 0.0;                 // [s] solving, set-up excluded
  bool converged = false;            // the back-end ended normally
  bool success = false;              // every pair met (and, for the local strategy, converged)
  std::vector<char> met;             // per pair: miss <= PointPair::allowed_miss(accept_angle)
  std::string message;
  std::string strategy;              // "auto" or "local"
  std::vector<std::string> stages;   // what the strategy did, one line per stage
  std::string solver_report;         // the back-end's own report of the run that gave the result
};

// What a back-end reports; solve() completes the summary.
struct BackendResult {
  std::vector<double> x;             // free values
  std::vector<double> history;
  int iterations = 0;
  int64_t evaluations = 0;
  bool converged = false;
  double trust_region = 0.0;         // ceres: the radius at the end (a continued solve starts there); 0: none
  std::string message;
  std::string report;                // ceres: Solver::Summary::FullReport(); nlopt: the message
};

// The back-ends, from free values x0 (inside the bounds).
BackendResult solve_with_ceres(const EditProblem& problem, const std::vector<double>& x0,
                               const SolveSettings& settings, WorkControl& control);
BackendResult solve_with_nlopt(const EditProblem& problem, const std::string& algorithm,
                               const std::vector<double>& x0, const SolveSettings& settings,
                               WorkControl& control);
// Throws std::invalid_argument for a name nlopt does not know.
void check_nlopt_algorithm(const std::string& algorithm);

}  // namespace refracta
