// The global stage's design and its evaluation (global_stage.h).
#include "refracta/edit/global_stage.h"

#include "refracta/core/low_discrepancy.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

// The near-start points lie within this fraction of each parameter's range of the start.
constexpr double kNearFraction = 0.1;
// Axis scans are refined around the lowest local minima of their cost profile: this many minima,
// this many points across the neighbouring cells, this many times (each time a cell shrinks by
// kRefinePoints / 2). A layer's height matters on the layer's width -- a fifth of a unit in the
// original editor's logistic profile, whose h_ciso box spans 110 units: 16 points miss its basin,
// three refinements of the two best minima find it (benchmarks/bench_edit.py's original case).
constexpr int kRefineMinima = 2;
constexpr int kRefinePoints = 8;
constexpr int kRefineLevels = 3;

// Evaluates points[from...] in parallel, as many as the budget's evaluations allow, until its
// interrupt (time limit, cancel) is raised; the rest keep cost +inf. Returns how many it evaluated.
int64_t evaluate_points(const EditProblem& problem, std::vector<DesignPoint>* points, size_t from, SolveBudget& budget) {
  const int64_t count = std::min<int64_t>(int64_t(points->size() - from), budget.evaluations_left());
  for (size_t i = from; i < points->size(); ++i) (*points)[i].cost = std::numeric_limits<double>::infinity();
  std::atomic<int64_t> evaluated{0};
  WorkControl local;
  parallel_for_each(count, 1, local, [&](int64_t i) {
    if (budget.interrupt()->load(std::memory_order_relaxed)) return;
    DesignPoint& p = (*points)[from + i];
    std::vector<double> r;
    p.cost = std::numeric_limits<double>::infinity();
    if (problem.evaluate(p.x, &r, nullptr, /*parallel=*/false) && !budget.interrupt()->load(std::memory_order_relaxed)) {
      p.cost = 0.0;
      for (double v : r) p.cost += 0.5 * v * v;
      p.vertical.resize(problem.pairs().size());
      for (size_t k = 0; k < p.vertical.size(); ++k) p.vertical[k] = r[3 * k + 1];
    }
    evaluated.fetch_add(1);
    budget.spend_evaluations(1);
  });
  budget.check_cancelled();
  return evaluated.load();
}

// Unit coordinates (sorted) and costs of one axis's scan: the indices of its lowest local minima.
std::vector<size_t> lowest_minima(const std::vector<std::pair<double, double>>& profile, int count) {
  std::vector<size_t> minima;
  for (size_t i = 0; i < profile.size(); ++i) {
    const double c = profile[i].second;
    if (!std::isfinite(c)) continue;
    const bool left = i == 0 || !(profile[i - 1].second < c);
    const bool right = i + 1 == profile.size() || !(profile[i + 1].second < c);
    if (left && right) minima.push_back(i);
  }
  std::sort(minima.begin(), minima.end(), [&](size_t a, size_t b) { return profile[a].second < profile[b].second; });
  if (int(minima.size()) > count) minima.resize(count);
  return minima;
}

}  // namespace

Design evaluate_design(const EditProblem& problem, int per_param, SolveBudget& budget) {
  Design out;
  const int m = problem.num_free();
  const std::vector<std::string> names = problem.free_names();
  std::vector<DesignPoint> points;
  auto on_axis = [&](int j, double u, const std::string& label) {
    std::vector<double> x = problem.start();
    x[j] = problem.from_unit(j, std::clamp(u, 0.0, 1.0));
    points.push_back({x, 0.0, label, {}});
  };
  // 1. Scans along each axis through the start, and quasi-random points.
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < per_param; ++k) on_axis(j, (k + 0.5) / per_param, "scan of " + names[j]);
  }
  const QuasiRandom sequence(m);
  const int64_t spread = int64_t(per_param) * m;
  for (int64_t n = 0; n < spread; ++n) {
    const std::vector<double> u = sequence.point(n + 1);
    std::vector<double> x(m);
    const bool near = n % 2 == 1;
    for (int j = 0; j < m; ++j) {
      const double start = problem.to_unit(j, problem.start()[j]);
      x[j] = problem.from_unit(j, near ? std::clamp(start + (2.0 * u[j] - 1.0) * kNearFraction, 0.0, 1.0) : u[j]);
    }
    points.push_back({x, 0.0, near ? "near the start" : "in the box", {}});
  }
  out.evaluated += evaluate_points(problem, &points, 0, budget);

  // 2. Each axis's profile refined around its lowest minima.
  std::vector<std::vector<std::pair<double, double>>> profiles(m);  // (u, cost) per axis
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < per_param; ++k) profiles[j].push_back({(k + 0.5) / per_param, points[size_t(j) * per_param + k].cost});
  }
  double cell = 1.0 / per_param;
  for (int level = 0; level < kRefineLevels; ++level) {
    const size_t from = points.size();
    std::vector<int> axis_of;
    for (int j = 0; j < m; ++j) {
      std::sort(profiles[j].begin(), profiles[j].end());
      for (size_t i : lowest_minima(profiles[j], kRefineMinima)) {
        const double centre = profiles[j][i].first;
        for (int k = 0; k < kRefinePoints; ++k) {
          const double u = centre + cell * (2.0 * (k + 0.5) / kRefinePoints - 1.0);
          if (u < 0.0 || u > 1.0) continue;
          on_axis(j, u, "scan of " + names[j] + ", refined");
          axis_of.push_back(j);
        }
      }
    }
    if (points.size() == from || budget.evaluations_left() == 0 || budget.interrupt()->load()) {
      points.resize(from);  // none of this level was evaluated (a cost of 0 would rank them first)
      break;
    }
    out.evaluated += evaluate_points(problem, &points, from, budget);
    for (size_t i = from; i < points.size(); ++i) {
      const int j = axis_of[i - from];
      profiles[j].push_back({problem.to_unit(j, points[i].x[j]), points[i].cost});
    }
    cell *= 2.0 / kRefinePoints;
  }
  std::stable_sort(points.begin(), points.end(),
                   [](const DesignPoint& a, const DesignPoint& b) { return a.cost < b.cost; });
  const StopReason stop = budget.exhausted();
  if (stop == StopReason::kTimeLimit || stop == StopReason::kEvaluations) out.stopped = stop;
  out.points = std::move(points);
  return out;
}

std::vector<DesignPoint> spread_best(const EditProblem& problem, const std::vector<DesignPoint>& sorted, int count,
                                     double spacing) {
  std::vector<DesignPoint> chosen;
  auto unit_distance = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0.0;
    for (size_t j = 0; j < a.size(); ++j) {
      d = std::max(d, std::abs(problem.to_unit(int(j), a[j]) - problem.to_unit(int(j), b[j])));
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
