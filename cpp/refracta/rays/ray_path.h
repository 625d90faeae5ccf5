// RayPath: a traced path as its nodes, with queries on the continuous (quintic Hermite) path.
#pragma once

#include "refracta/rays/ray_node.h"
#include "refracta/rays/trace_options.h"

#include <vector>

namespace refracta {

struct ClosestPoint {
  Vec3d point;
  double distance;
  double s;  // arc length [m]
};

struct Crossing {
  Vec3d point;
  double s;
  Vec3d direction;  // unit tangent
};

class RayPath {
 public:
  RayPath(std::vector<RayNode<double>> nodes, TraceStop stop, int64_t evaluations);

  const std::vector<RayNode<double>>& nodes() const { return nodes_; }
  TraceStop stop() const { return stop_; }
  int64_t evaluations() const { return evaluations_; }
  double length() const { return nodes_.back().s; }

  // Position and unit tangent at arc length s in [0, length].
  Vec3d point_at(double s, Vec3d* direction = nullptr) const;
  // The point of the continuous path closest to q.
  ClosestPoint closest_point(const Vec3d& q) const;
  // Every crossing of the plane normal . x = offset, in path order.
  std::vector<Crossing> crossings(const Vec3d& normal, double offset) const;

 private:
  size_t segment_index(double s) const;

  std::vector<RayNode<double>> nodes_;
  TraceStop stop_;
  int64_t evaluations_;
};

}  // namespace refracta
