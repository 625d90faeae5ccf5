// The Ceres back-end: one residual block per pair, Levenberg-Marquardt over the free parameters
// mapped to [0, 1] by their bounds (EditProblem::to_unit; box constraints), an optional robust loss, every pair traced in
// parallel before each evaluation (PairBatch: results independent of the thread count), an
// iteration callback for history, progress, Ctrl-C and the target cost.
#include "refracta/edit/edit_settings.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

// Per iteration: the history, the budget's iterations, and the stops -- Ctrl-C (abort), the
// target cost, the call's evaluation limit and the solve's budget (both end with the current
// point, as usable as any).
class EditCallback : public ceres::IterationCallback {
 public:
  EditCallback(const SolveSettings& settings, SolveBudget& budget, const int64_t& evaluations,
               BackendResult* out)
      : settings_(settings), budget_(budget), evaluations_(evaluations), out_(out) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    // A rejected step leaves the solver where it was: the history follows the accepted points.
    auto& history = out_->history;
    const bool moved = summary.iteration == 0 || summary.step_is_successful || history.empty();
    history.push_back(moved ? summary.cost : history.back());
    if (summary.iteration > 0) budget_.spend_iterations(1);
    if (budget_.cancelled()) return ceres::SOLVER_ABORT;
    if (summary.cost <= settings_.target_cost) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    StopReason stop = budget_.exhausted();
    if (stop == StopReason::kNone && evaluations_ >= settings_.max_evaluations) stop = StopReason::kEvaluations;
    if (stop != StopReason::kNone) {
      out_->stopped = stop;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const SolveSettings& settings_;
  SolveBudget& budget_;
  const int64_t& evaluations_;
  BackendResult* out_;
};

// Every pair traced at once, in parallel on the oneTBB pool, before Ceres reads any residual block
// (Ceres' EvaluationCallback; Ceres copies the point into `unit` first). Ceres itself then runs on
// one thread: its sums over blocks (cost, gradient) have one order, so a solve gives the same
// result whatever the thread count (refracta.set_threads) -- Ceres' own threads add block costs
// in per-thread partial sums whose grouping depends on scheduling.
class PairBatch : public ceres::EvaluationCallback {
 public:
  PairBatch(const EditProblem& problem, const std::vector<double>& unit, SolveBudget& budget)
      : problem_(problem), unit_(unit), budget_(budget) {}

  void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override {
    if (!new_evaluation_point && (jacobians_ || !evaluate_jacobians)) return;  // have what is asked
    const int m = problem_.num_free();
    std::vector<double> x(m);
    for (int j = 0; j < m; ++j) x[j] = problem_.from_unit(j, unit_[j]);
    ok_ = problem_.evaluate(x, &residuals_, evaluate_jacobians ? &jacobian_ : nullptr);
    jacobians_ = evaluate_jacobians;
    ++evaluations_;
    budget_.spend_evaluations(1);
    if (ok_) {
      double cost = 0.0;
      for (double r : residuals_) cost += 0.5 * r * r;
      if (cost < best_cost_) best_cost_ = cost, best_x_ = x;
    }
  }

  int64_t evaluations() const { return evaluations_; }
  const int64_t& evaluations_ref() const { return evaluations_; }
  // The lowest-cost point evaluated (empty if none succeeded): the result when an interrupted
  // evaluation leaves Ceres' own end point unusable.
  const std::vector<double>& best_x() const { return best_x_; }

  // Pair i's 3 residuals and, when asked, its 3 x m Jacobian with respect to the unit box
  // (d/du = d/dx * dx/du); false when the batch's evaluation failed.
  bool block(int i, double* residuals, double* jacobian) const {
    if (!ok_ || (jacobian && !jacobians_)) return false;
    const int m = problem_.num_free();
    std::copy_n(residuals_.data() + 3 * i, 3, residuals);
    if (jacobian) {
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < m; ++j) jacobian[k * m + j] = jacobian_[size_t(3 * i + k) * m + j] * problem_.dx_du(j, unit_[j]);
      }
    }
    return true;
  }

 private:
  const EditProblem& problem_;
  const std::vector<double>& unit_;
  SolveBudget& budget_;
  std::vector<double> residuals_, jacobian_, best_x_;
  double best_cost_ = std::numeric_limits<double>::infinity();
  int64_t evaluations_ = 0;
  bool ok_ = false, jacobians_ = false;
};

// Pair i's residual block over the free parameters mapped to [0, 1] by their bounds (x = lower +
// u (upper - lower)), as nlopt sees them too: the trust region then measures steps as fractions
// of each parameter's range, whatever its unit. Its values come from the PairBatch.
class UnitBoxCost : public ceres::CostFunction {
 public:
  UnitBoxCost(const PairBatch& batch, int pair, int num_free) : batch_(batch), pair_(pair) {
    set_num_residuals(3);
    mutable_parameter_block_sizes()->push_back(num_free);
  }
  bool Evaluate(double const* const* /*parameters: the batch's point*/, double* residuals,
                double** jacobians) const override {
    return batch_.block(pair_, residuals, jacobians ? jacobians[0] : nullptr);
  }

 private:
  const PairBatch& batch_;
  int pair_;
};

ceres::LossFunction* make_loss(const SolveSettings& settings) {
  // Ceres' losses act on the squared residual norm s; scale a makes them quadratic for s << a^2.
  const double a = settings.loss_scale;
  switch (settings.loss) {
    case RobustLoss::kHuber: return new ceres::HuberLoss(a);
    case RobustLoss::kSoftL1: return new ceres::SoftLOneLoss(a);
    case RobustLoss::kCauchy: return new ceres::CauchyLoss(a);
    case RobustLoss::kArctan: return new ceres::ArctanLoss(a);
    case RobustLoss::kNone: break;
  }
  return nullptr;
}

}  // namespace

BackendResult solve_with_ceres(const EditProblem& problem, const std::vector<double>& x0,
                               const SolveSettings& settings, SolveBudget& budget) {
  BackendResult out;
  const int m = problem.num_free();
  std::vector<double> unit(m);
  for (int j = 0; j < m; ++j) {
    unit[j] = problem.to_unit(j, x0[j]);
  }
  PairBatch batch(problem, unit, budget);
  ceres::Problem::Options problem_options;
  problem_options.evaluation_callback = &batch;  // not owned
  ceres::Problem ceres_problem(problem_options);
  for (int i = 0; i < int(problem.pairs().size()); ++i) {
    ceres_problem.AddResidualBlock(new UnitBoxCost(batch, i, m), make_loss(settings), unit.data());
  }
  for (int j = 0; j < m; ++j) {
    ceres_problem.SetParameterLowerBound(unit.data(), j, 0.0);
    ceres_problem.SetParameterUpperBound(unit.data(), j, 1.0);
  }

  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings.max_iterations;
  options.initial_trust_region_radius = settings.trust_region;
  options.function_tolerance = settings.function_tolerance;
  options.parameter_tolerance = settings.parameter_tolerance;
  options.gradient_tolerance = settings.gradient_tolerance;
  // Ceres checks its clock once per iteration; the budget's interrupt stops a long evaluation.
  if (std::isfinite(budget.seconds_left())) options.max_solver_time_in_seconds = std::max(1e-3, budget.seconds_left());
  // No projected line search after each step inside the unit box: it costs a Jacobian
  // evaluation per iteration (half the solve); steps are projected onto the box all the same.
  options.max_num_line_search_step_size_iterations = 0;
  options.num_threads = 1;  // the pairs run in parallel in PairBatch
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  EditCallback callback(settings, budget, batch.evaluations_ref(), &out);
  options.callbacks.push_back(&callback);

  std::string why;
  if (!options.IsValid(&why)) throw_invalid("ceres options: ", why);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  budget.check_cancelled();

  // Iteration 0 is the start; a solve stopped before it (time limit, failed evaluation) has none.
  out.iterations = std::max(0, int(summary.iterations.size()) - 1);
  if (!summary.iterations.empty()) out.trust_region = summary.iterations.back().trust_region_radius;
  out.evaluations = batch.evaluations();
  if (out.stopped == StopReason::kNone && summary.termination_type == ceres::NO_CONVERGENCE) {
    // Ceres' own limits: its clock (the budget's time) or the iterations of this call.
    out.stopped = budget.exhausted() == StopReason::kTimeLimit ? StopReason::kTimeLimit : StopReason::kIterations;
  }
  if (out.stopped == StopReason::kNone && budget.exhausted() == StopReason::kTimeLimit) {
    out.stopped = StopReason::kTimeLimit;  // an interrupted evaluation made Ceres give up
  }
  out.converged = out.stopped == StopReason::kNone && (summary.termination_type == ceres::CONVERGENCE ||
                                                       summary.termination_type == ceres::USER_SUCCESS);
  out.message = concat("ceres (Levenberg-Marquardt): ", ceres::TerminationTypeToString(summary.termination_type),
                       ": ", summary.message);
  if (out.stopped != StopReason::kNone && summary.termination_type == ceres::USER_SUCCESS) {
    out.message = concat("ceres (Levenberg-Marquardt): stopped by the ", stop_reason_name(out.stopped));
  }
  out.report = summary.FullReport();
  out.x = x0;
  if (summary.IsSolutionUsable()) {
    for (int j = 0; j < m; ++j) {
      out.x[j] = problem.from_unit(j, unit[j]);
    }
  } else if (!batch.best_x().empty()) {
    out.x = batch.best_x();
  }
  return out;
}

}  // namespace refracta
