// A point pair of the mirage editor (Choi 2017): light launched from the eye toward a destination
// (where the artist wants the image) should pass through a source (the scene point to be seen
// there). PairOptions say how that light path is traced and measured.
#pragma once

#include "refracta/core/math.h"
#include "refracta/rays/trace_options.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// The largest and least pair weights (a cost of weight x miss^2 must stay within float64).
inline constexpr double kMostPairWeight = 1e100;
inline constexpr double kLeastPairWeight = 1e-100;

struct PointPair {
  Vec3d origin = Vec3d::Zero();     // the eye [m]
  Vec3d direction = Vec3d::UnitX(); // toward the destination (any length > 0)
  Vec3d source = Vec3d::UnitX();    // the scene point to be seen along it [m]
  double weight = 1.0;              // importance, in [kLeastPairWeight, kMostPairWeight]; the residual is scaled by sqrt(weight)
  // A miss up to this distance [m] costs nothing (a dead zone: residual = miss (1 - margin/|miss|)
  // outside it, so the cost stays C1); less important points get larger margins.
  double margin = 0.0;
  // [m] beyond the margin, a miss up to this counts as met (a pixel destination: a fraction of the
  // pixel's footprint at the source, SolveSettings::pixel_tolerance); it leaves the cost alone.
  double tolerance = 0.0;
  // A pixel (u, v) of the edit's camera (ProblemSpec::camera) the destination is: when camera
  // parameters are free the launch direction follows the camera (CameraRig); direction is then
  // the start camera's ray through it. Unset: a 3D destination, whose direction is fixed.
  std::optional<Eigen::Vector2d> pixel;

  double range() const { return (source - origin).norm(); }  // [m]
  // What a miss beyond the margin may be for the pair to count as met: the larger of its tolerance
  // and accept_angle [rad] times its range (a tolerance far below a pixel) [m].
  double met_tolerance(double accept_angle) const { return std::max(tolerance, accept_angle * range()); }
  // The largest miss [m] at which the pair counts as met.
  double allowed_miss(double accept_angle) const { return margin + met_tolerance(accept_angle); }
};

// How far a path passes from its source.
//   continuous: closest approach of the continuous (quintic Hermite) path, smooth in the field's
//               parameters;
//   vertex:     the nearest integrator node (the original editor's measure, piecewise constant; with
//               trace rk4 only: rk45's nodes are far apart).
enum class PairDistance { kContinuous, kVertex };

// How an edit's pairs are traced and measured (refracta.edit.solve, distances, jacobian and
// EditResult.paths take these fields as keywords), with their defaults (defined once, in C++'s
// PairOptions). validate() reports every bad value at once.
struct PairOptions {
  TraceMethod trace = TraceMethod::kRk45;   // the ray integrator: rk45 or rk4 (stratified has no derivatives)
  double tol = 1e-9;   // rk45 target position error [m] (at least 1e-13 per metre of path)
  double step = 0.0;                        // rk4 step [m] (0: 0.3, the original editor's)
  // Paths end where they descend through it (a ground) [m]; unset (None): no ground.
  std::optional<double> stop_height;
  PairDistance distance = PairDistance::kContinuous;
  // The path is traced to reach x (the eye-to-source distance) + 1 m (reach in [1, 100]), and
  // stops early once it is past the source.
  double reach = 1.5;
  // Integration steps a trace may take (TraceOptions::max_steps): beyond them the evaluation fails.
  int64_t max_steps = 10'000'000;

  // Throws std::invalid_argument listing every bad field.
  void validate() const;
  // How `pair`'s path is traced: the one rule every measure of the pair, and its drawn path, use.
  TraceOptions trace_options(const PointPair& pair) const;
};

PairDistance parse_pair_distance(const std::string& name);  // "continuous", "vertex"
const char* pair_distance_name(PairDistance distance);

// Throws std::invalid_argument naming the pair and the bad value (NaN, zero direction,
// weight <= 0, margin < 0, source at the eye, eye below the ground, a non-finite pixel).
void validate_pairs(const std::vector<PointPair>& pairs, const PairOptions& options);

// Pairs from per-pair arrays (the Python boundary's shape): weights, margins and tolerances empty
// for 1, 0 and 0; pixels no rows for none, else one (u, v) per pair, NaN for a 3D destination.
// Throws std::invalid_argument when the counts differ.
using PixelRows = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
std::vector<PointPair> make_point_pairs(const std::vector<Vec3d>& origins, const std::vector<Vec3d>& directions,
                                        const std::vector<Vec3d>& sources, std::vector<double> weights = {},
                                        std::vector<double> margins = {}, std::vector<double> tolerances = {},
                                        const PixelRows& pixels = PixelRows());

}  // namespace refracta
