// RayPath queries on the continuous path.
#include "refracta/rays/ray_path.h"

#include "refracta/core/error.h"
#include "refracta/core/memory.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

RayPath::RayPath(std::vector<RayNode<double>> nodes, TraceStop stop, int64_t evaluations)
    : nodes_(std::move(nodes)), stop_(stop), evaluations_(evaluations) {
  if (nodes_.empty()) throw std::logic_error("RayPath needs at least one node");
}

size_t RayPath::segment_index(double s) const {
  auto it = std::upper_bound(nodes_.begin(), nodes_.end(), s,
                             [](double value, const RayNode<double>& n) { return value < n.s; });
  const size_t i = size_t(it - nodes_.begin());
  return std::clamp<size_t>(i, 1, nodes_.size() - 1) - 1;
}

Vec3d RayPath::point_at(double s, Vec3d* direction) const {
  if (!(s >= 0.0 && s <= length() * (1 + 1e-12) + 1e-12)) {
    throw_invalid("s must be in [0, ", length(), "] m (got ", s, ")");
  }
  if (nodes_.size() == 1) {
    if (direction) *direction = nodes_[0].tangent().normalized();
    return nodes_[0].x;
  }
  const size_t i = segment_index(s);
  const PathSegment<double> seg(nodes_[i], nodes_[i + 1]);
  const double u = seg.length() > 0 ? std::clamp((s - seg.start()) / seg.length(), 0.0, 1.0) : 0.0;
  if (direction) *direction = seg.velocity(u).normalized();
  return seg.position(u);
}

ClosestPoint RayPath::closest_point(const Vec3d& q) const {
  // Farther out, the distances to a path's points differ by less than a double resolves there
  // (1e20 m away a 100 m path's ends are equally far): the answer would be its start, s = 0.
  if (!within_reach(q)) {
    throw_invalid("closest_point: the point must be finite and within ", kSceneReach, " m of the origin (got (", q.x(),
                  ", ", q.y(), ", ", q.z(), "))");
  }
  ClosestPoint best{nodes_[0].x, (nodes_[0].x - q).norm(), 0.0};
  for (size_t i = 0; i + 1 < nodes_.size(); ++i) {
    const RayNode<double>& a = nodes_[i];
    const RayNode<double>& b = nodes_[i + 1];
    if (segment_distance_bound(a, b, q) > best.distance) continue;
    const PathSegment<double> seg(a, b);
    double d2;
    const double u = closest_on_segment(seg, q, &d2);
    if (std::sqrt(d2) < best.distance) {
      best = {seg.position(u), std::sqrt(d2), seg.start() + u * seg.length()};
    }
  }
  return best;
}

std::vector<Crossing> RayPath::crossings(const Vec3d& normal, double offset) const {
  if (!is_finite(normal) || normal.norm() == 0.0 || !std::isfinite(offset)) {
    throw_invalid("crossings: the plane must have a finite, non-zero normal and a finite offset");
  }
  const Vec3d unit = normal.normalized();
  const double off = offset / normal.norm();
  std::vector<Crossing> out;
  auto add = [&](const PathSegment<double>& seg, double u) {
    const double s = seg.start() + u * seg.length();
    if (!out.empty() && std::abs(out.back().s - s) <= 1e-9 * (1.0 + s)) return;  // at a node
    out.push_back({seg.position(u), s, seg.velocity(u).normalized()});
  };
  if (nodes_.size() == 1 && unit.dot(nodes_[0].x) == off) {
    out.push_back({nodes_[0].x, 0.0, nodes_[0].tangent().normalized()});
  }
  // Every root of each segment's quintic (a path that dips through the plane and back within one
  // segment reports both crossings, however brief the dip).
  for (size_t i = 0; i + 1 < nodes_.size(); ++i) {
    const PathSegment<double> seg(nodes_[i], nodes_[i + 1]);
    const std::array<double, 6> g = seg.across(unit, off);
    if (!may_vanish(g)) continue;
    const PolynomialRoots<6> roots = polynomial_roots(g, 0.0, 1.0);
    for (size_t k = 0; k < roots.count; ++k) add(seg, roots.at[k]);
  }
  return out;
}

std::vector<Vec3d> RayPath::at_height(double y) const {
  if (!std::isfinite(y)) throw_invalid("at_height: y must be a finite height [m] (got ", y, ")");
  std::vector<Vec3d> out;
  for (const Crossing& c : crossings(Vec3d::UnitY(), y)) out.push_back(c.point);
  return out;
}

std::vector<Vec3d> RayPath::sample(int count) const {
  if (count < 2) throw_invalid("count must be >= 2 (got ", count, ")");
  // 24 bytes a point here and again in the caller's array: refused before allocating past half of
  // this machine's memory (2**31 points asked the allocator for 51 GB).
  if (const double memory = physical_memory_bytes(), bytes = 48.0 * double(count); memory > 0.0 && bytes > memory / 2.0) {
    throw_invalid("sample: count=", count, " points need ", readable_bytes(bytes),
                  " (as many here as in the array returned), more than half of this machine's ", readable_bytes(memory));
  }
  std::vector<Vec3d> out(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) out[size_t(i)] = point_at(length() * i / (count - 1));
  return out;
}

namespace {

template <class Get>
auto per_node(const std::vector<RayNode<double>>& nodes, Get get) {
  std::vector<decltype(get(nodes[0]))> out;
  out.reserve(nodes.size());
  for (const auto& node : nodes) out.push_back(get(node));
  return out;
}

}  // namespace

std::vector<Vec3d> RayPath::points() const {
  return per_node(nodes_, [](const RayNode<double>& n) { return n.x; });
}

std::vector<Vec3d> RayPath::directions() const {
  return per_node(nodes_, [](const RayNode<double>& n) { return Vec3d(n.v.normalized()); });
}

std::vector<Vec3d> RayPath::ray_vectors() const {
  return per_node(nodes_, [](const RayNode<double>& n) { return n.v; });
}

std::vector<double> RayPath::arc_lengths() const {
  return per_node(nodes_, [](const RayNode<double>& n) { return n.s; });
}

std::vector<double> RayPath::iors() const {
  return per_node(nodes_, [](const RayNode<double>& n) { return n.n; });
}

RayPath::PackedNodes RayPath::packed() const {
  PackedNodes out(Eigen::Index(nodes_.size()), 11);
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const RayNode<double>& n = nodes_[i];
    out.row(Eigen::Index(i)) << n.s, n.x.transpose(), n.v.transpose(), n.n, n.grad.transpose();
  }
  return out;
}

RayPath RayPath::unpacked(const PackedNodes& rows, int stop, int64_t evaluations) {
  if (rows.rows() < 1) throw_invalid("RayPath: bad pickle state (nodes)");
  if (stop < 0 || stop > int(TraceStop::kVisitor)) throw_invalid("RayPath: bad pickle state (stop ", stop, ")");
  if (evaluations < 0) throw_invalid("RayPath: bad pickle state (evaluations ", evaluations, ")");
  // What a trace makes: finite nodes in order of arc length (a trial's NaN nodes gave length nan).
  if (!rows.allFinite()) throw_invalid("RayPath: bad pickle state (nodes must be finite)");
  for (Eigen::Index i = 1; i < rows.rows(); ++i) {
    if (!(rows(i, 0) >= rows(i - 1, 0))) throw_invalid("RayPath: bad pickle state (arc lengths must not fall)");
  }
  std::vector<RayNode<double>> nodes(size_t(rows.rows()));
  for (size_t i = 0; i < nodes.size(); ++i) {
    const auto r = rows.row(Eigen::Index(i));
    nodes[i] = RayNode<double>{r(0), r.segment<3>(1).transpose(), r.segment<3>(4).transpose(), r(7),
                               r.segment<3>(8).transpose()};
  }
  return RayPath(std::move(nodes), TraceStop(stop), evaluations);
}

}  // namespace refracta
