// The global stage's design and its evaluation (global_stage.h).
#include "refracta/edit/global_stage.h"

#include "refracta/core/low_discrepancy.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

// The near-start points lie within this fraction of each parameter's range of the start.
constexpr double kNearFraction = 0.1;

}  // namespace

std::vector<DesignPoint> evaluate_design(const EditProblem& problem, int per_param, WorkControl& control) {
  const int m = problem.num_free();
  const std::vector<double>& lo = problem.lower();
  const std::vector<double>& hi = problem.upper();
  const std::vector<std::string> names = problem.free_names();
  std::vector<DesignPoint> points;
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < per_param; ++k) {
      std::vector<double> x = problem.start();
      x[j] = lo[j] + (k + 0.5) / per_param * (hi[j] - lo[j]);
      points.push_back({x, 0.0, "scan of " + names[j]});
    }
  }
  const QuasiRandom sequence(m);
  const int spread = per_param * m;
  for (int n = 0; n < spread; ++n) {
    const std::vector<double> u = sequence.point(n + 1);
    std::vector<double> x(m);
    const bool near = n % 2 == 1;
    for (int j = 0; j < m; ++j) {
      const double range = hi[j] - lo[j];
      x[j] = near ? std::clamp(problem.start()[j] + (2.0 * u[j] - 1.0) * kNearFraction * range, lo[j], hi[j])
                  : lo[j] + u[j] * range;
    }
    points.push_back({x, 0.0, near ? "near the start" : "in the box"});
  }
  parallel_for_each(int64_t(points.size()), 1, control, [&](int64_t i) {
    points[i].cost = problem.cost(points[i].x, /*parallel=*/false);
  });
  std::stable_sort(points.begin(), points.end(),
                   [](const DesignPoint& a, const DesignPoint& b) { return a.cost < b.cost; });
  return points;
}

std::vector<DesignPoint> spread_best(const EditProblem& problem, const std::vector<DesignPoint>& sorted, int count,
                                     double spacing) {
  std::vector<DesignPoint> chosen;
  auto unit_distance = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0.0;
    for (size_t j = 0; j < a.size(); ++j) {
      d = std::max(d, std::abs(a[j] - b[j]) / (problem.upper()[j] - problem.lower()[j]));
    }
    return d;
  };
  for (const DesignPoint& p : sorted) {
    if (int(chosen.size()) == count || !std::isfinite(p.cost)) break;
    const bool apart = std::all_of(chosen.begin(), chosen.end(),
                                   [&](const DesignPoint& c) { return unit_distance(c.x, p.x) >= spacing; });
    if (apart) chosen.push_back(p);
  }
  return chosen;
}

}  // namespace refracta
