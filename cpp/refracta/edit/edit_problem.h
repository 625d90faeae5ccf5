// An edit: a field, its free parameters with bounds, and the point pairs' residual blocks.
// Parameters the backends see are the free ones only; the rest stay at the start values.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/edit/pair_cost.h"
#include "refracta/rays/ray_path.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace refracta {

// Each pair's unweighted distance [m] for a field, measured as an edit would (pairs in parallel).
// Throws std::invalid_argument for bad pairs or options; control.cancel stops it (throws Cancelled).
std::vector<double> pair_distances(const IndexField& field, const std::vector<PointPair>& pairs,
                                   const PairOptions& options, WorkControl& control);

// Each pair's whole path through `field`, traced by the rule its miss is measured with
// (PairOptions::trace_options), pairs in parallel: what a plot of an edit draws. control.cancel
// stops it (throws Cancelled).
std::vector<RayPath> pair_paths(const IndexField& field, const std::vector<PointPair>& pairs,
                                const PairOptions& options, WorkControl& control);

struct ProblemSpec {
  // Names of the free parameters (the field's, and with a camera CameraRig::names()); empty:
  // every parameter of the field except the model's gauge ones.
  std::vector<std::string> free;
  // Bounds overriding the model's search box, by parameter name.
  std::map<std::string, std::pair<double, double>> bounds;
  Derivatives derivatives = Derivatives::kAutomatic;
  PairOptions pair;
  // The camera whose pixels the pairs' pixel destinations are (CameraRig): needed for the camera
  // parameters; without them free it changes nothing.
  std::optional<Camera> camera;
};

class EditProblem {
 public:
  // Throws std::invalid_argument for unknown names (listing the valid ones), empty or inverted
  // bounds, a start outside the bounds, bad pairs, or camera parameters without a camera.
  EditProblem(FieldPtr field, std::vector<PointPair> pairs, const ProblemSpec& spec,
              const std::atomic<bool>* cancel);
  ~EditProblem();

  // The same problem with pairs traced to `tol` [m] in at most `max_steps` steps each (the global
  // stage ranks points by a coarser, bounded cost; its results never reach the user).
  std::unique_ptr<EditProblem> with_tolerance(double tol, int64_t max_steps) const;
  const PairOptions& pair_options() const { return options_; }

  int num_free() const { return int(free_.size()); }
  int num_residuals() const { return 3 * int(pairs_.size()); }
  const std::vector<PointPair>& pairs() const { return pairs_; }
  const std::vector<int>& free() const { return free_; }
  std::vector<std::string> free_names() const;
  const std::vector<double>& start() const { return start_; }   // free values at the start
  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }
  Derivatives derivatives() const { return derivatives_; }
  const std::vector<std::unique_ptr<ceres::CostFunction>>& costs() const { return costs_; }
  EvaluationContext& context() const { return *context_; }

  // Weighted residuals (3 per pair) at free values x and, if jacobian is given, the row-major
  // (num_residuals x num_free) Jacobian; pairs in parallel unless `parallel` is false (callers
  // that run several points at once: each thread then builds the model once per point). False
  // when an evaluation failed.
  bool evaluate(const std::vector<double>& x, std::vector<double>* residuals,
                std::vector<double>* jacobian = nullptr, bool parallel = true) const;
  // 1/2 sum of squared weighted residuals, or +inf when an evaluation failed.
  double cost(const std::vector<double>& x, bool parallel = true) const;
  // Whether every pair is met (PointPair::allowed_miss) by these residuals: a residual block's
  // length is sqrt(weight) times the miss beyond the margin.
  bool all_met(const std::vector<double>& residuals, double accept_angle) const;
  // How many pairs these residuals meet.
  int count_met(const std::vector<double>& residuals, double accept_angle) const;

  // The unit box both back-ends and the global stage search: each free parameter mapped to [0, 1]
  // by its bounds, linearly, or logarithmically where its bounds are positive and span a factor
  // of 100 or more (widths, depths, radii: a step is then a fraction of the value, not of a range
  // 2000 times the value, so a bound of 0.005..10 m does not make 1 mm steps invisible).
  double to_unit(int j, double x) const;
  double from_unit(int j, double u) const;
  double dx_du(int j, double u) const;  // the map's slope

  // Every parameter value of the field with the free ones at x, and the field they make.
  std::vector<double> full_values(const std::vector<double>& x) const;
  // The camera parameters (CameraRig::names() order) with the free ones at x, and the camera they
  // make; empty / none without a camera rig.
  std::vector<double> camera_values(const std::vector<double>& x) const;
  std::optional<Camera> camera_at(const std::vector<double>& x) const;
  // Whether a camera rig is present (ProblemSpec::camera was given and some camera name is free).
  bool has_camera() const { return rig_ != nullptr; }
  FieldPtr field_at(const std::vector<double>& x) const;
  // The pairs launched as at x: pixel destinations along the camera's rays at x.
  std::vector<PointPair> pairs_at(const std::vector<double>& x) const;
  // Unweighted distance of each pair's path from its source [m] for the field (and camera) at x.
  std::vector<double> distances(const std::vector<double>& x) const;

 private:
  FieldPtr field_;
  ProblemSpec spec_;  // as given, with the free names filled in
  std::vector<PointPair> pairs_;
  PairOptions options_;
  Derivatives derivatives_;
  std::vector<double> values_;  // the field's, then the rig's (if any)
  size_t field_count_ = 0;
  std::shared_ptr<const CameraRig> rig_;
  std::vector<int> free_;
  std::vector<double> start_, lower_, upper_;
  std::vector<char> log_scaled_;
  std::unique_ptr<EvaluationContext> context_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
};

// The weighted residuals (3 per pair) and their Jacobian in the free parameters at the spec's
// start, for sensitivity studies: the spec's bounds are opened (camera parameters as wide as
// their map allows) so any start is accepted. Throws NumericalError when an evaluation fails.
struct PairJacobian {
  Eigen::VectorXd residuals;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian;  // (3 pairs, free)
  std::vector<std::string> free;
};
PairJacobian pair_jacobian(const FieldPtr& field, std::vector<PointPair> pairs, ProblemSpec spec);

}  // namespace refracta
