// The nlopt back-end: any nlopt algorithm by name on the same residual blocks. The free
// parameters are mapped to [0, 1] by their bounds (EditProblem::to_unit, as Ceres sees them), so
// derivative-free methods see a well-scaled box; gradient-based ones get J^T r from the automatic (or numeric) derivatives.
#include "refracta/edit/edit_settings.h"

#include <nlopt.hpp>

#include <algorithm>
#include <memory>

#include <cmath>
#include <limits>

namespace refracta {

void check_nlopt_algorithm(const std::string& algorithm) {
  if (nlopt_algorithm_from_string(algorithm.c_str()) == nlopt_algorithm(-1)) {
    throw_invalid("unknown nlopt algorithm '", algorithm,
                  "' (e.g. LN_BOBYQA, LN_NELDERMEAD, LN_SBPLX, LN_COBYLA, GN_DIRECT_L, LD_LBFGS, LD_MMA)");
  }
}

namespace {

struct Objective {
  const EditProblem& problem;
  const SolveSettings& settings;
  SolveBudget& budget;
  BackendResult& out;
  nlopt::opt* opt = nullptr;
  double best = std::numeric_limits<double>::infinity();

  std::vector<double> to_params(const std::vector<double>& unit) const {
    std::vector<double> x(unit.size());
    for (size_t i = 0; i < unit.size(); ++i) x[i] = problem.from_unit(int(i), std::clamp(unit[i], 0.0, 1.0));
    return x;
  }

  // Stops nlopt once the caller cancels or a limit is reached: a composite algorithm's (MLSL,
  // AUGLAG) local optimiser is a copy nlopt owns and keeps its own counters, so the limits are
  // enforced here, where every evaluation of either passes; calls after the stop cost nothing.
  bool stopping() {
    if (budget.cancelled()) {
      opt->force_stop();
      return true;
    }
    StopReason stop = budget.exhausted();
    if (stop == StopReason::kNone && out.evaluations >= settings.max_evaluations) stop = StopReason::kEvaluations;
    if (stop == StopReason::kIterations) stop = StopReason::kNone;  // nlopt counts evaluations only
    if (stop == StopReason::kNone) return false;
    if (out.stopped == StopReason::kNone) out.stopped = stop;
    opt->force_stop();
    return true;
  }

  double operator()(const std::vector<double>& unit, std::vector<double>& grad) {
    if (stopping()) {
      std::fill(grad.begin(), grad.end(), 0.0);
      return std::isfinite(best) ? best : 1e300;
    }
    const std::vector<double> x = to_params(unit);
    std::vector<double> r, jacobian;
    ++out.evaluations;
    budget.spend_evaluations(1);
    double cost = std::numeric_limits<double>::infinity();
    if (problem.evaluate(x, &r, grad.empty() ? nullptr : &jacobian)) {
      cost = 0.0;
      for (double v : r) cost += 0.5 * v * v;
    }
    if (!grad.empty()) {
      const int m = problem.num_free();
      for (int j = 0; j < m; ++j) {
        double g = 0.0;
        if (std::isfinite(cost)) {
          for (int k = 0; k < problem.num_residuals(); ++k) g += jacobian[size_t(k) * m + j] * r[k];
        }
        grad[j] = g * problem.dx_du(j, std::clamp(unit[j], 0.0, 1.0));
      }
    }
    if (cost < best) best = cost, out.x = x;
    out.history.push_back(best);
    // nlopt has no "failed evaluation": a huge finite cost steers it away.
    return std::isfinite(cost) ? cost : 1e300;
  }
};

std::string result_name(nlopt::result result) {
  switch (result) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "target cost reached";
    case nlopt::FTOL_REACHED: return "cost tolerance reached";
    case nlopt::XTOL_REACHED: return "parameter tolerance reached";
    case nlopt::MAXEVAL_REACHED: return "evaluation limit reached";
    case nlopt::MAXTIME_REACHED: return "time limit reached";
    default: return concat("result ", int(result));
  }
}

}  // namespace

BackendResult solve_with_nlopt(const EditProblem& problem, const std::string& algorithm,
                               const std::vector<double>& x0, const SolveSettings& settings,
                               SolveBudget& budget) {
  check_nlopt_algorithm(algorithm);
  const int m = problem.num_free();
  BackendResult out;
  out.x = x0;
  Objective objective{problem, settings, budget, out};
  std::vector<double> unit(m);
  for (int i = 0; i < m; ++i) {
    unit[i] = problem.to_unit(i, x0[i]);
  }
  const std::string prefix = concat("nlopt ", algorithm, ": ");
  try {
    nlopt::opt opt(algorithm.c_str(), unsigned(m));
    objective.opt = &opt;
    opt.set_lower_bounds(std::vector<double>(m, 0.0));
    opt.set_upper_bounds(std::vector<double>(m, 1.0));
    opt.set_min_objective(
        [](unsigned n, const double* x, double* grad, void* data) {
          std::vector<double> point(x, x + n), gradient(grad ? n : 0);
          const double f = (*static_cast<Objective*>(data))(point, gradient);
          if (grad) std::copy(gradient.begin(), gradient.end(), grad);
          return f;
        },
        &objective);
    opt.set_ftol_rel(settings.function_tolerance);
    opt.set_xtol_rel(settings.parameter_tolerance);
    opt.set_maxeval(settings.max_evaluations);
    const double seconds_left = budget.seconds_left();
    if (std::isfinite(seconds_left)) opt.set_maxtime(std::max(1e-3, seconds_left));
    if (settings.target_cost > 0.0) opt.set_stopval(settings.target_cost);
    // MLSL and AUGLAG run a local optimiser that nlopt leaves unset (it then crashes): LD_LBFGS
    // for the gradient-based variants, LN_BOBYQA (bounded, derivative-free) for the others.
    std::unique_ptr<nlopt::opt> local;
    if (algorithm.find("MLSL") != std::string::npos || algorithm.find("AUGLAG") != std::string::npos) {
      const bool gradient = algorithm.size() > 1 && algorithm[1] == 'D';
      local = std::make_unique<nlopt::opt>(gradient ? nlopt::LD_LBFGS : nlopt::LN_BOBYQA, unsigned(m));
      local->set_lower_bounds(std::vector<double>(m, 0.0));
      local->set_upper_bounds(std::vector<double>(m, 1.0));
      local->set_ftol_rel(settings.function_tolerance);
      local->set_xtol_rel(settings.parameter_tolerance);
      local->set_maxeval(settings.max_evaluations);
      if (std::isfinite(seconds_left)) local->set_maxtime(std::max(1e-3, seconds_left));
      opt.set_local_optimizer(*local);
    }
    if (algorithm.front() == 'G') {
      // A global algorithm (DIRECT, CRS, ISRES, ...) searches the box and never evaluates x0: its
      // start is measured first, so that the stage never ends above it (a trial: GN_DIRECT from a
      // start of cost 123 m^2, and from a design point of 0.24 m^2, returned 512 m^2).
      std::vector<double> no_gradient;
      objective(unit, no_gradient);
    }
    double minimum;
    const nlopt::result result = opt.optimize(unit, minimum);
    if (result == nlopt::MAXEVAL_REACHED && out.stopped == StopReason::kNone) out.stopped = StopReason::kEvaluations;
    if (result == nlopt::MAXTIME_REACHED && out.stopped == StopReason::kNone) out.stopped = StopReason::kTimeLimit;
    out.converged = result > 0 && out.stopped == StopReason::kNone;
    out.message = prefix + (out.stopped != StopReason::kNone ? concat("stopped by the ", stop_reason_name(out.stopped))
                                                             : result_name(result));
  } catch (const nlopt::forced_stop&) {
    budget.check_cancelled();
    out.message = prefix + (out.stopped != StopReason::kNone ? concat("stopped by the ", stop_reason_name(out.stopped))
                                                             : std::string("forced stop"));
  } catch (const nlopt::roundoff_limited&) {
    out.converged = true;  // nlopt's own advice: the result is usually still useful
    out.message = prefix + "stopped by round-off (the cost cannot be reduced further)";
  } catch (const std::invalid_argument& error) {
    // Refused before its first evaluation: the algorithm cannot take this problem at all (LN_NEWUOA
    // one free parameter, an algorithm this nlopt lacks): a user's error, not a verdict on the
    // atmosphere (a trial's CLI edit reported "the destination lies above every image" and wrote
    // the start's field).
    if (out.evaluations == 0) {
      throw_invalid("backend 'nlopt:", algorithm, "' cannot solve this problem (", m, " free parameter",
                    m == 1 ? "" : "s", "): nlopt says '", error.what(),
                    "' (LN_BOBYQA, LN_SBPLX and LD_LBFGS take any number of parameters)");
    }
    out.message = prefix + "invalid arguments: " + error.what();
  } catch (const std::bad_alloc&) {
    out.message = prefix + "out of memory";
  } catch (const std::runtime_error& error) {
    out.message = prefix + "failure: " + error.what();
  }
  budget.check_cancelled();
  out.iterations = int(out.evaluations);
  out.report = concat(out.message, " after ", out.evaluations, " evaluations; best cost ", objective.best, " m^2");
  return out;
}

}  // namespace refracta
