// The Ceres back-end: one residual block per pair, Levenberg-Marquardt over the free parameters
// mapped to [0, 1] by their bounds (box constraints), an optional robust loss, an iteration callback for history, progress,
// Ctrl-C and the target cost.
#include "refracta/edit/edit_settings.h"

#include <ceres/ceres.h>

namespace refracta {

namespace {

class EditCallback : public ceres::IterationCallback {
 public:
  EditCallback(const SolveSettings& settings, WorkControl& control, std::vector<double>* history)
      : settings_(settings), control_(control), history_(history) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    // A rejected step leaves the solver where it was: the history follows the accepted points.
    const bool moved = summary.iteration == 0 || summary.step_is_successful || history_->empty();
    history_->push_back(moved ? summary.cost : history_->back());
    control_.done = summary.iteration;
    if (control_.cancel.load()) return ceres::SOLVER_ABORT;
    if (summary.cost <= settings_.target_cost) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const SolveSettings& settings_;
  WorkControl& control_;
  std::vector<double>* history_;
};

// A pair's cost over the free parameters mapped to [0, 1] by their bounds (x = lower + u (upper -
// lower)), as nlopt sees them too: the trust region then measures steps as fractions of each
// parameter's range, whatever its unit.
class UnitBoxCost : public ceres::CostFunction {
 public:
  UnitBoxCost(const ceres::CostFunction& cost, const EditProblem& problem) : cost_(cost), problem_(problem) {
    set_num_residuals(cost.num_residuals());
    *mutable_parameter_block_sizes() = cost.parameter_block_sizes();
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int m = problem_.num_free();
    std::vector<double> x(m);
    for (int j = 0; j < m; ++j) x[j] = problem_.lower()[j] + parameters[0][j] * range(j);
    const double* block[] = {x.data()};
    if (!cost_.Evaluate(block, residuals, jacobians)) return false;
    if (jacobians && jacobians[0]) {
      for (int k = 0; k < num_residuals(); ++k) {
        for (int j = 0; j < m; ++j) jacobians[0][k * m + j] *= range(j);
      }
    }
    return true;
  }

 private:
  double range(int j) const { return problem_.upper()[j] - problem_.lower()[j]; }
  const ceres::CostFunction& cost_;
  const EditProblem& problem_;
};

ceres::LossFunction* make_loss(const SolveSettings& settings) {
  // Ceres' losses act on the squared residual norm s; scale a makes them quadratic for s << a^2.
  const double a = settings.loss_scale;
  if (settings.loss == "huber") return new ceres::HuberLoss(a);
  if (settings.loss == "soft_l1") return new ceres::SoftLOneLoss(a);
  if (settings.loss == "cauchy") return new ceres::CauchyLoss(a);
  if (settings.loss == "arctan") return new ceres::ArctanLoss(a);
  return nullptr;
}

}  // namespace

BackendResult solve_with_ceres(const EditProblem& problem, const SolveSettings& settings,
                               WorkControl& control) {
  BackendResult out;
  const int m = problem.num_free();
  std::vector<double> unit(m);
  for (int j = 0; j < m; ++j) {
    unit[j] = (problem.start()[j] - problem.lower()[j]) / (problem.upper()[j] - problem.lower()[j]);
  }
  ceres::Problem ceres_problem;
  for (const auto& cost : problem.costs()) {
    ceres_problem.AddResidualBlock(new UnitBoxCost(*cost, problem), make_loss(settings), unit.data());
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
  if (settings.max_time > 0.0) options.max_solver_time_in_seconds = settings.max_time;
  options.num_threads = 2;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  EditCallback callback(settings, control, &out.history);
  options.callbacks.push_back(&callback);
  control.total = settings.max_iterations;

  std::string why;
  if (!options.IsValid(&why)) throw_invalid("ceres options: ", why);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  if (control.cancel.load()) throw Cancelled();

  out.iterations = int(summary.iterations.size()) - 1;  // iteration 0 is the start
  out.evaluations = summary.num_residual_evaluations;
  out.converged = summary.termination_type == ceres::CONVERGENCE ||
                  summary.termination_type == ceres::USER_SUCCESS;
  out.message = concat("ceres (Levenberg-Marquardt): ", ceres::TerminationTypeToString(summary.termination_type),
                       ": ", summary.message);
  out.x = problem.start();
  if (summary.IsSolutionUsable()) {
    for (int j = 0; j < m; ++j) {
      out.x[j] = problem.lower()[j] + unit[j] * (problem.upper()[j] - problem.lower()[j]);
    }
  }
  return out;
}

}  // namespace refracta
