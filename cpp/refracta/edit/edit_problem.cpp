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

// "'a', 'b', 'c'" (quoted) or "a, b, c".
std::string concat_names(const std::vector<std::string>& names, bool only_camera) {
  std::string out;
  for (const auto& name : names) {
    if (only_camera && CameraRig::index_of(name) < 0) continue;
    out += (out.empty() ? "" : ", ") + (only_camera ? "'" + name + "'" : name);
  }
  return out;
}

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
  field_count_ = values_.size();
  const auto& specs = field_->param_specs();

  std::vector<std::string> names = spec.free;
  if (names.empty()) {
    const auto gauge = field_->gauge_params();
    for (const auto& s : specs) {
      if (std::find(gauge.begin(), gauge.end(), s.name) == gauge.end()) names.push_back(s.name);
    }
  }
  const bool camera_free = std::any_of(names.begin(), names.end(), [](const std::string& name) {
    return CameraRig::index_of(name) >= 0;
  });
  if (camera_free) {
    if (!spec.camera) {
      throw_invalid("camera parameters (", concat_names(names, true),
                    ") need the camera whose pixels the destinations are: pass a Camera as eye_or_camera");
    }
    rig_ = std::make_shared<const CameraRig>(*spec.camera);
    for (double v : rig_->start_values()) values_.push_back(v);
  }
  // Index into values_ of a parameter name; throws listing every valid name.
  auto index_of = [&](const std::string& name) -> int {
    if (const int k = CameraRig::index_of(name); k >= 0) return int(field_count_) + k;
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].name == name) return int(i);
    }
    std::vector<std::string> valid;
    for (const auto& s : specs) valid.push_back(s.name);
    for (const char* c : CameraRig::names()) valid.emplace_back(c);
    throw_invalid("unknown parameter '", name, "' of ", field_->type_name(), "; valid names: ",
                  concat_names(valid, false));
  };
  for (const auto& name : names) {
    const int index = index_of(name);
    if (std::find(free_.begin(), free_.end(), index) != free_.end()) {
      throw_invalid("free parameter '", name, "' is listed twice");
    }
    free_.push_back(index);
  }
  for (const auto& [name, box] : spec.bounds) {
    index_of(name);
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw_invalid("bounds given for '", name, "', which is not a free parameter");
    }
  }
  for (int index : free_) {
    const bool camera = index >= int(field_count_);
    const int k = index - int(field_count_);
    const std::string name = camera ? std::string(CameraRig::names()[k]) : specs[index].name;
    double lo, hi;
    std::tie(lo, hi) = camera ? rig_->default_bounds(k) : std::make_pair(specs[index].lower, specs[index].upper);
    if (auto it = spec.bounds.find(name); it != spec.bounds.end()) std::tie(lo, hi) = it->second;
    if (camera) CameraRig::check_bounds(k, lo, hi);
    // The solvers work in the unit box (x - lower) / (upper - lower): its width must be finite too.
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || !std::isfinite(hi - lo)) {
      throw_invalid("bounds of '", name, "' must be finite with lower < upper and a finite width upper - lower (got [",
                    lo, ", ", hi, "])");
    }
    const double x = values_[index];
    if (x < lo || x > hi) {
      const std::string& raw = camera ? std::string("deg") : specs[index].unit;
      const std::string unit = raw.empty() || raw == "1" ? "" : " " + raw;  // "1": dimensionless
      throw_invalid("the start value of '", name, "' (", x, unit, ") lies outside its bounds [", lo, ", ", hi,
                    "]; widen them with bounds={'", name, "': (lower, upper)}");
    }
    start_.push_back(x);
    lower_.push_back(lo);
    upper_.push_back(hi);
    log_scaled_.push_back(lo > 0.0 && hi >= kLogScaleRatio * lo);
  }
  if (free_.empty() && field_count_ == 0) {
    throw_invalid("no free parameters: this ", field_->type_name(), " has no parameters to solve for (",
                  rig_ ? "only the camera's: free=['camera_yaw', ...]" : "and without a camera none of the camera's",
                  "); a model such as PhysicalAtmosphere has them");
  }
  if (free_.empty()) throw_invalid("no free parameters: name at least one in free");
  spec_.free = names;
  costs_ = make_pair_costs(field_, values_, free_, pairs_, options_, derivatives_, rig_, context_.get());
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
  for (int index : free_) {
    names.push_back(index >= int(field_count_) ? std::string(CameraRig::names()[index - field_count_])
                                               : field_->param_specs()[index].name);
  }
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
  full.resize(field_count_);
  return full;
}

std::vector<double> EditProblem::camera_values(const std::vector<double>& x) const {
  if (!rig_) return {};
  std::vector<double> full = values_;
  for (size_t i = 0; i < free_.size(); ++i) full[free_[i]] = x[i];
  return std::vector<double>(full.begin() + field_count_, full.end());
}

std::optional<Camera> EditProblem::camera_at(const std::vector<double>& x) const {
  if (!rig_) return std::nullopt;
  return rig_->camera(camera_values(x).data());
}

FieldPtr EditProblem::field_at(const std::vector<double>& x) const {
  return field_->with_param_values(full_values(x));
}

std::vector<double> pair_distances(const IndexField& field, const std::vector<PointPair>& pairs,
                                   const PairOptions& options, WorkControl& control) {
  options.validate();
  validate_pairs(pairs, options);
  std::vector<double> out(pairs.size());
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

std::vector<PointPair> EditProblem::pairs_at(const std::vector<double>& x) const {
  std::vector<PointPair> out = pairs_;
  if (!rig_) return out;
  const std::vector<double> camera = camera_values(x);
  for (PointPair& pair : out) {
    if (pair.pixel) pair.direction = rig_->direction<double>((*pair.pixel)[0], (*pair.pixel)[1], camera.data());
  }
  return out;
}

std::vector<double> EditProblem::distances(const std::vector<double>& x) const {
  WorkControl control;  // inside the solve's own (the thread's cancel scope still stops it)
  return pair_distances(*field_at(x), pairs_at(x), options_, control);
}

PairJacobian pair_jacobian(const FieldPtr& field, std::vector<PointPair> pairs, ProblemSpec spec) {
  for (const auto& name : spec.free) {
    const int k = CameraRig::index_of(name);
    spec.bounds[name] = k >= 0 ? CameraRig::widest_bounds(k) : std::pair<double, double>(-1e300, 1e300);
  }
  const EditProblem problem(field, std::move(pairs), spec, nullptr);
  std::vector<double> r, jacobian;
  if (!problem.evaluate(problem.start(), &r, &jacobian)) {
    throw_numerical("evaluation failed: ", problem.context().first_failure());
  }
  PairJacobian out;
  out.residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), Eigen::Index(r.size()));
  out.jacobian = Eigen::Map<const decltype(out.jacobian)>(jacobian.data(), problem.num_residuals(), problem.num_free());
  out.free = problem.free_names();
  return out;
}

}  // namespace refracta
