// Chord plans of table paths (chord_plan.h).
#include "refracta/render/chord_plan.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace refracta {

namespace {

// Distance of q from the line through a along unit u.
double off_line(const Vec3d& q, const Vec3d& a, const Vec3d& u) {
  const Vec3d d = q - a;
  return (d - u * d.dot(u)).norm();
}

}  // namespace

ChordPlan plan_chords(const RayPath& path, const std::function<double(double)>& tolerance, double max_chord) {
  const auto& nodes = path.nodes();
  ChordPlan plan;
  if (nodes.size() < 2) return plan;
  // The continuous path at the quarter points of every segment.
  std::vector<std::array<Vec3d, 3>> quarters(nodes.size() - 1);
  for (size_t k = 0; k + 1 < nodes.size(); ++k) {
    const PathSegment<double> segment(nodes[k], nodes[k + 1]);
    for (int q = 0; q < 3; ++q) quarters[k][q] = segment.position(0.25 * (q + 1));
  }
  // Whether the chord from node i to node j stays within tol of the path between them.
  auto straight_enough = [&](size_t i, size_t j, double tol) {
    const Vec3d a = nodes[i].x, ab = nodes[j].x - a;
    const double length = ab.norm();
    if (length == 0.0) return true;
    const Vec3d u = ab / length;
    for (size_t k = i; k < j; ++k) {
      if (k > i && off_line(nodes[k].x, a, u) > tol) return false;
      for (const Vec3d& q : quarters[k]) {
        if (off_line(q, a, u) > tol) return false;
      }
    }
    return true;
  };
  for (size_t i = 0; i + 1 < nodes.size();) {
    const double tol = tolerance(nodes[i].s);
    const double own = (nodes[i + 1].x - nodes[i].x).norm();
    if (!straight_enough(i, i + 1, tol) || own > max_chord) {
      // Deviation falls with the square of the number of pieces.
      double deviation = 0.0;
      const Vec3d u = (nodes[i + 1].x - nodes[i].x) / std::max(own, 1e-300);
      for (const Vec3d& q : quarters[i]) deviation = std::max(deviation, off_line(q, nodes[i].x, u));
      const int by_sagitta = int(std::ceil(std::sqrt(deviation / tol)));
      const int pieces = std::clamp(std::max(by_sagitta, int(std::ceil(own / max_chord))), 1, 1 << 20);
      plan.push_back({uint32_t(i), uint32_t(i + 1), uint32_t(pieces)});
      ++i;
      continue;
    }
    // A chord does not reach across a node where the path turns up or down: a path that dips
    // under a level (the sea) and rises again, or tops a level and falls again, within the
    // tolerance would otherwise be cut over by a chord that never crosses it.
    const double rising = nodes[i + 1].x.y() - nodes[i].x.y();
    auto same_way = [&](size_t k) { return (nodes[k + 1].x.y() - nodes[k].x.y()) * rising > 0.0; };
    size_t j = i + 1;
    while (j + 1 < nodes.size() && same_way(j) && (nodes[j + 1].x - nodes[i].x).norm() <= max_chord &&
           straight_enough(i, j + 1, tol)) {
      ++j;
    }
    plan.push_back({uint32_t(i), uint32_t(j), 1});
    i = j;
  }
  return plan;
}

}  // namespace refracta
