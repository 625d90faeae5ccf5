// Validation of point pairs and their trace options.
#include "refracta/edit/point_pair.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {
constexpr double kRoundOffTolerance = 1e-13;  // per metre of path
constexpr double kLongestReach = 100.0;
}  // namespace

PairDistance parse_pair_distance(const std::string& name) {
  if (name == "continuous") return PairDistance::kContinuous;
  if (name == "vertex") return PairDistance::kVertex;
  throw_invalid("distance must be 'continuous' or 'vertex' (got '", name, "')");
}

const char* pair_distance_name(PairDistance distance) {
  return distance == PairDistance::kContinuous ? "continuous" : "vertex";
}

void PairOptions::validate() const {
  Problems problems("PairOptions");
  problems.check(trace != TraceMethod::kStratified,
                 "trace must be 'rk45' or 'rk4' (got 'stratified': the stratified tracer has no derivatives)");
  problems.check(tol > 0.0 && std::isfinite(tol), "tol must be > 0 (got ", tol, ")");
  problems.check(step >= 0.0 && std::isfinite(step), "step must be >= 0 (got ", step, ")");
  problems.check(!stop_height || std::isfinite(*stop_height), "stop_height must be finite (got ",
                 stop_height.value_or(0.0), ")");
  // A path runs to reach x its source's range: far enough for paths that turn back (ducts, a
  // Fata Morgana's loops); 1e6 ran paths of 1e9 m, whose round-off collapsed the steps.
  problems.check(reach >= 1.0 && reach <= kLongestReach, "reach must be in [1, ", kLongestReach, "] (got ", reach,
                 ")");
  problems.check(max_steps >= 1, "max_steps must be >= 1 (got ", max_steps, ")");
  // The nearest node measures the path only where the nodes are close: rk45's are hundreds of
  // metres apart on km paths (a trial: misses of 3 131 m for images met to 2 um).
  problems.check(distance != PairDistance::kVertex || trace == TraceMethod::kRk4,
                 "distance='vertex' needs trace='rk4' (the nearest of fixed steps, the original editor's 0.3 m; "
                 "rk45's nodes are far apart, so its nearest node misses the source by up to half a step)");
  problems.throw_if_any();
}

TraceOptions PairOptions::trace_options(const PointPair& pair) const {
  TraceOptions options;
  options.trace = trace;
  options.step = step;
  options.max_length = reach * pair.range() + 1.0;
  // Below ~1e-13 of the path length a position tolerance asks for more than round-off allows.
  options.tol = std::max(tol, kRoundOffTolerance * options.max_length);
  options.stop_height = stop_height;
  options.max_steps = max_steps;
  return options;
}

void validate_pairs(const std::vector<PointPair>& pairs, const PairOptions& options) {
  if (pairs.empty()) throw_invalid("pairs is empty: give at least one PointPair");
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PointPair& p = pairs[i];
    if (!is_finite(p.origin)) throw_invalid("pair ", i, ": the eye position is not finite");
    if (!is_finite(p.direction) || p.direction.norm() == 0.0) {
      throw_invalid("pair ", i, ": the destination direction must be finite and non-zero");
    }
    if (!is_finite(p.source)) throw_invalid("pair ", i, ": the source point is not finite");
    // The cost adds weight x miss^2 [m^2]: 1e308 overflowed it ("evaluation failed"); weights in
    // use are relative importances of order 1.
    if (!(p.weight > 0.0 && p.weight <= kMostPairWeight)) {
      throw_invalid("pair ", i, ": weight must be in (0, ", kMostPairWeight, "] (got ", p.weight, ")");
    }
    // ... and 1e-300 underflowed it: the solve stopped at once ("gradient max norm 0") and blamed the air.
    if (p.weight < kLeastPairWeight) {
      throw_invalid("pair ", i, ": weight must be at least ", kLeastPairWeight, " (got ", p.weight,
                    "): a cost that small underflows; weights are relative importances");
    }
    if (!(p.margin >= 0.0) || !std::isfinite(p.margin)) {
      throw_invalid("pair ", i, ": margin must be >= 0 and finite (got ", p.margin, ")");
    }
    if (!(p.tolerance >= 0.0) || !std::isfinite(p.tolerance)) {
      throw_invalid("pair ", i, ": tolerance must be >= 0 and finite (got ", p.tolerance, ")");
    }
    if (p.pixel && !p.pixel->allFinite()) throw_invalid("pair ", i, ": the destination pixel is not finite");
    if (!(p.range() > 0.0)) throw_invalid("pair ", i, ": the source is at the eye");
    if (options.stop_height && p.origin.y() < *options.stop_height) {
      throw_invalid("pair ", i, ": the eye (height ", p.origin.y(), " m) is below the ground (stop_height ",
                    *options.stop_height, " m)");
    }
  }
}

std::vector<PointPair> make_point_pairs(const std::vector<Vec3d>& origins, const std::vector<Vec3d>& directions,
                                        const std::vector<Vec3d>& sources, std::vector<double> weights,
                                        std::vector<double> margins, std::vector<double> tolerances,
                                        const PixelRows& pixels) {
  const size_t n = origins.size();
  if (weights.empty()) weights.assign(n, 1.0);
  if (margins.empty()) margins.assign(n, 0.0);
  if (tolerances.empty()) tolerances.assign(n, 0.0);
  if (directions.size() != n || sources.size() != n || weights.size() != n || margins.size() != n ||
      tolerances.size() != n) {
    throw_invalid("one eye, direction, source, weight, margin and tolerance per pair (got ", n, ", ",
                  directions.size(), ", ", sources.size(), ", ", weights.size(), ", ", margins.size(), ", ",
                  tolerances.size(), ")");
  }
  if (pixels.rows() != 0 && size_t(pixels.rows()) != n) {
    throw_invalid("pixels must be one (u, v) or NaN row per pair (got ", pixels.rows(), " rows for ", n, " pairs)");
  }
  std::vector<PointPair> pairs(n);
  for (size_t i = 0; i < n; ++i) {
    pairs[i] = {origins[i], directions[i], sources[i], weights[i], margins[i], tolerances[i], std::nullopt};
    if (pixels.rows() == 0) continue;
    const Eigen::Vector2d uv = pixels.row(Eigen::Index(i)).transpose();
    if (!uv.array().isNaN().all()) pairs[i].pixel = uv;
  }
  return pairs;
}

}  // namespace refracta
