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

// A traced light path. Arrays are per node (the integrator's steps; the path between nodes is the
// quintic Hermite interpolant of positions, tangents and curvatures, accurate to O(step^6)).
//
// points (N,3) [m]; directions (N,3) unit tangents; arc_length (N,) [m]; ior (N,) n at each node;
// ray_vectors (N,3) the integrated v (``|v| = n``); stop: why the path ended ('max_length',
// 'stop_height'); evaluations: field evaluations used.
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
  // Every point where the path crosses height y [m] (the plane +y . x = y), in path order.
  std::vector<Vec3d> at_height(double y) const;
  // count >= 2 points evenly spaced in arc length on the continuous path.
  std::vector<Vec3d> sample(int count) const;

  // Per node: positions x, unit tangents v / |v|, ray vectors v, arc lengths s, indices n.
  std::vector<Vec3d> points() const;
  std::vector<Vec3d> directions() const;
  std::vector<Vec3d> ray_vectors() const;
  std::vector<double> arc_lengths() const;
  std::vector<double> iors() const;

  // The nodes as rows (s, x, v, n, grad n): what a copy is rebuilt from exactly (pickling);
  // unpacked() refuses no rows or a bad stop reason.
  using PackedNodes = Eigen::Matrix<double, Eigen::Dynamic, 11, Eigen::RowMajor>;
  PackedNodes packed() const;
  static RayPath unpacked(const PackedNodes& rows, int stop, int64_t evaluations);

 private:
  size_t segment_index(double s) const;

  std::vector<RayNode<double>> nodes_;
  TraceStop stop_;
  int64_t evaluations_;
};

}  // namespace refracta
