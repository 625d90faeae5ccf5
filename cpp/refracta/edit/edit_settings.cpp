// SolveSettings (edit_settings.h): the Python spellings of its enums, and validate().
#include "refracta/edit/edit_settings.h"

#include "refracta/core/error.h"
#include "refracta/core/math.h"

#include <cmath>
#include <utility>

namespace refracta {

namespace {
constexpr const char* kNloptPrefix = "nlopt:";
constexpr std::pair<RobustLoss, const char*> kLossNames[] = {{RobustLoss::kNone, "none"},
                                                             {RobustLoss::kHuber, "huber"},
                                                             {RobustLoss::kSoftL1, "soft_l1"},
                                                             {RobustLoss::kCauchy, "cauchy"},
                                                             {RobustLoss::kArctan, "arctan"}};
}  // namespace

std::string backend_name(const SolveSettings& settings) {
  return settings.backend == SolveBackend::kCeres ? "ceres" : kNloptPrefix + settings.nlopt_algorithm;
}

void parse_backend(const std::string& name, SolveSettings* settings) {
  const std::string prefix = kNloptPrefix;
  if (name == "ceres") {
    settings->backend = SolveBackend::kCeres;
    settings->nlopt_algorithm.clear();
  } else if (name.rfind(prefix, 0) == 0) {
    settings->backend = SolveBackend::kNlopt;
    settings->nlopt_algorithm = name.substr(prefix.size());
  } else {
    throw_invalid("backend must be 'ceres' or 'nlopt:<ALGORITHM>' (got '", name, "')");
  }
}

const char* strategy_name(SolveStrategy strategy) { return strategy == SolveStrategy::kAuto ? "auto" : "local"; }

SolveStrategy parse_strategy(const std::string& name) {
  if (name == "auto") return SolveStrategy::kAuto;
  if (name == "local") return SolveStrategy::kLocal;
  throw_invalid("strategy must be 'auto' or 'local' (got '", name, "')");
}

const char* loss_name(RobustLoss loss) {
  for (const auto& [value, name] : kLossNames) {
    if (value == loss) return name;
  }
  return "none";
}

RobustLoss parse_loss(const std::string& name) {
  for (const auto& [value, spelling] : kLossNames) {
    if (name == spelling) return value;
  }
  throw_invalid("loss must be 'none', 'huber', 'soft_l1', 'cauchy' or 'arctan' (got '", name, "')");
}

void SolveSettings::validate() const {
  Problems problems("SolveSettings");
  if (backend == SolveBackend::kNlopt) {
    try {
      check_nlopt_algorithm(nlopt_algorithm);
    } catch (const std::invalid_argument& error) {
      problems.add(error.what());
    }
  }
  const std::pair<const char*, int> at_least_one[] = {
      {"max_iterations", max_iterations}, {"max_evaluations", max_evaluations},
      {"quick_iterations", quick_iterations}, {"design_per_param", design_per_param},
      {"local_starts", local_starts}, {"starts", starts}};
  for (const auto& [name, value] : at_least_one) problems.check(value >= 1, name, " must be >= 1 (got ", value, ")");
  problems.check(design_per_param <= kMostDesignPerParam, "design_per_param must be <= ", kMostDesignPerParam, " (got ",
                 design_per_param, ")");
  // Ceres' own limits of a trust region (Solver::Options' min and max_trust_region_radius): outside
  // them its CHECK fails, or it reported its own option's name (a trial's 1e-300 and 1e300).
  constexpr double kSmallestTrustRegion = 1e-32, kLargestTrustRegion = 1e16;
  problems.check(trust_region >= kSmallestTrustRegion && trust_region <= kLargestTrustRegion, "trust_region must be in [",
                 kSmallestTrustRegion, ", ", kLargestTrustRegion, "] (got ", trust_region, ")");
  const std::pair<const char*, double> non_negative[] = {
      {"time_limit", time_limit}, {"function_tolerance", function_tolerance},
      {"parameter_tolerance", parameter_tolerance}, {"gradient_tolerance", gradient_tolerance},
      {"target_cost", target_cost}, {"accept_angle", accept_angle}, {"pixel_tolerance", pixel_tolerance}};
  for (const auto& [name, value] : non_negative) {
    problems.check(value >= 0.0 && std::isfinite(value), name, " must be >= 0 and finite (got ", value, ")");
  }
  // A miss [m]: from a micrometre to the scene's reach. Beyond, the loss's own arithmetic fails (a
  // trial's cauchy at 1e300: a NaN cost change, the parameters left at the start).
  constexpr double kSmallestLossScale = 1e-6;
  problems.check(loss_scale >= kSmallestLossScale && loss_scale <= kSceneReach, "loss_scale must be in [",
                 kSmallestLossScale, ", ", kSceneReach, "] m (got ", loss_scale, ")");
  problems.check(loss == RobustLoss::kNone || backend == SolveBackend::kCeres, "a robust loss needs backend 'ceres'");
  problems.throw_if_any();
}

}  // namespace refracta
