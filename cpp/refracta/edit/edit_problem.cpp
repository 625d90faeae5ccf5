// EditProblem: free parameters, bounds and residual evaluation shared by both back-ends.
#include "refracta/edit/edit_problem.h"

#include "refracta/core/parallel.h"
#include "refracta/edit/pair_miss.h"
#include "refracta/rays/trace.h"

#include <ceres/cost_function.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace refracta {

namespace {

// Positive bounds wider than this factor are searched in log space (edit_problem.h).
constexpr double kLogScaleRatio = 100.0;

}  // namespace

EditProblem::EditProblem(FieldPtr field, std::vector<PointPair> pairs, const ProblemSpec& spec,
                         const std::atomic<bool>* cancel)
    : field_(std::move(field)), spec_(spec), pairs_(std::move(pairs)), options_(spec.pair),
      derivatives_(spec.derivatives), context_(std::make_unique<EvaluationContext>()) {
  if (!field_) throw_invalid("field must be an IndexField (got None)");
  options_.validate();
  validate_pairs(pairs_, options_);
  context_->cancel = cancel;
  values_ = field_->param_values();
  const auto& specs = field_->param_specs();

  std::vector<std::string> names = spec.free;
  if (names.empty()) {
    const auto gauge = field_->gauge_params();
    for (const auto& s : specs) {
      if (std::find(gauge.begin(), gauge.end(), s.name) == gauge.end()) names.push_back(s.name);
    }
  }
  for (const auto& name : names) {
    const int index = int(field_->param_index(name));  // throws, listing the valid names
    if (std::find(free_.begin(), free_.end(), index) != free_.end()) {
      throw_invalid("free parameter '", name, "' is listed twice");
    }
    free_.push_back(index);
  }
  for (const auto& [name, box] : spec.bounds) {
    field_->param_index(name);
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw_invalid("bounds given for '", name, "', which is not a free parameter");
    }
  }
  for (int index : free_) {
    const ParamSpec& s = specs[index];
    double lo = s.lower, hi = s.upper;
    if (auto it = spec.bounds.find(s.name); it != spec.bounds.end()) std::tie(lo, hi) = it->second;
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
      throw_invalid("bounds of '", s.name, "' must be finite with lower < upper (got [", lo, ", ", hi, "])");
    }
    const double x = values_[index];
    if (x < lo || x > hi) {
      const std::string unit = s.unit.empty() || s.unit == "1" ? "" : " " + s.unit;  // "1": dimensionless
      throw_invalid("the start value of '", s.name, "' (", x, unit, ") lies outside its bounds [", lo, ", ", hi,
                    "]; widen them with bounds={'", s.name, "': (lower, upper)}");
    }
    start_.push_back(x);
    lower_.push_back(lo);
    upper_.push_back(hi);
    log_scaled_.push_back(lo > 0.0 && hi >= kLogScaleRatio * lo);
  }
  if (free_.empty()) throw_invalid("no free parameters: name at least one in free");
  spec_.free = names;
  costs_ = make_pair_costs(field_, values_, free_, pairs_, options_, derivatives_, context_.get());
}

EditProblem::~EditProblem() = default;

std::unique_ptr<EditProblem> EditProblem::with_tolerance(double tol, int64_t max_steps) const {
  ProblemSpec spec = spec_;
  spec.pair.tol = tol;
  spec.pair.max_steps = std::min(spec.pair.max_steps, max_steps);
  return std::make_unique<EditProblem>(field_, pairs_, spec, context_->cancel);
}

std::vector<std::string> EditProblem::free_names() const {
  std::vector<std::string> names;
  for (int index : free_) names.push_back(field_->param_specs()[index].name);
  return names;
}

bool EditProblem::evaluate(const std::vector<double>& x, std::vector<double>* residuals,
                           std::vector<double>* jacobian, bool parallel) const {
  const int m = num_free();
  residuals->assign(num_residuals(), 0.0);
  if (jacobian) jacobian->assign(size_t(num_residuals()) * m, 0.0);
  std::vector<char> ok(pairs_.size(), 0);
  auto pair = [&](int64_t i) {
    const double* parameters[] = {x.data()};
    double* block = jacobian ? jacobian->data() + 3 * i * m : nullptr;
    double* blocks[] = {block};
    ok[i] = costs_[i]->Evaluate(parameters, residuals->data() + 3 * i, jacobian ? blocks : nullptr);
  };
  if (parallel) {
    WorkControl control;
    parallel_for_each(int64_t(pairs_.size()), 1, control, pair);
  } else {
    for (int64_t i = 0; i < int64_t(pairs_.size()) && !context_->cancelled(); ++i) pair(i);
  }
  return std::all_of(ok.begin(), ok.end(), [](char v) { return v != 0; });
}

double EditProblem::cost(const std::vector<double>& x, bool parallel) const {
  std::vector<double> r;
  if (!evaluate(x, &r, nullptr, parallel)) return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return 0.5 * sum;
}

int EditProblem::count_met(const std::vector<double>& residuals, double accept_angle) const {
  int met = 0;
  for (size_t i = 0; i < pairs_.size(); ++i) {
    const double length = std::sqrt(std::pow(residuals[3 * i], 2) + std::pow(residuals[3 * i + 1], 2) +
                                    std::pow(residuals[3 * i + 2], 2));
    // Beyond its margin the block is sqrt(weight) (miss - margin): met within its met tolerance.
    if (length <= std::sqrt(pairs_[i].weight) * pairs_[i].met_tolerance(accept_angle)) ++met;
  }
  return met;
}

bool EditProblem::all_met(const std::vector<double>& residuals, double accept_angle) const {
  return count_met(residuals, accept_angle) == int(pairs_.size());
}

double EditProblem::to_unit(int j, double x) const {
  if (log_scaled_[j]) return std::log(x / lower_[j]) / std::log(upper_[j] / lower_[j]);
  return (x - lower_[j]) / (upper_[j] - lower_[j]);
}

double EditProblem::from_unit(int j, double u) const {
  if (log_scaled_[j]) return std::clamp(lower_[j] * std::exp(u * std::log(upper_[j] / lower_[j])), lower_[j], upper_[j]);
  return std::clamp(lower_[j] + u * (upper_[j] - lower_[j]), lower_[j], upper_[j]);
}

double EditProblem::dx_du(int j, double u) const {
  if (log_scaled_[j]) return from_unit(j, u) * std::log(upper_[j] / lower_[j]);
  return upper_[j] - lower_[j];
}

std::vector<double> EditProblem::full_values(const std::vector<double>& x) const {
  std::vector<double> full = values_;
  for (size_t i = 0; i < free_.size(); ++i) full[free_[i]] = x[i];
  return full;
}

FieldPtr EditProblem::field_at(const std::vector<double>& x) const {
  return field_->with_param_values(full_values(x));
}

std::vector<double> pair_distances(const IndexField& field, const std::vector<PointPair>& pairs,
                                   const PairOptions& options) {
  options.validate();
  validate_pairs(pairs, options);
  std::vector<double> out(pairs.size());
  WorkControl control;
  parallel_for_each(int64_t(pairs.size()), 1, control, [&](int64_t i) {
    out[i] = pair_miss<double>(field, pairs[i], options).distance;
  });
  return out;
}

std::vector<RayPath> pair_paths(const IndexField& field, const std::vector<PointPair>& pairs,
                                const PairOptions& options, WorkControl& control) {
  options.validate();
  validate_pairs(pairs, options);
  std::vector<std::optional<RayPath>> paths(pairs.size());
  parallel_for_each(int64_t(pairs.size()), 1, control, [&](int64_t i) {
    paths[i] = trace_path(field, pairs[i].origin, pairs[i].direction, options.trace_options(pairs[i]));
  });
  std::vector<RayPath> out;
  for (auto& path : paths) out.push_back(std::move(*path));
  return out;
}

std::vector<double> EditProblem::distances(const std::vector<double>& x) const {
  return pair_distances(*field_at(x), pairs_, options_);
}

}  // namespace refracta
