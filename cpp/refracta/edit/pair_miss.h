// The miss of a point pair: how far the light path launched from the eye toward the destination
// passes from the source. Templated on the scalar: with ceres::Jet the derivatives flow through
// the integrator's steps and through the closest-approach solve inside its segment
// (refine_closest's Newton step in T), so they are exact for the discrete path.
#pragma once

#include "refracta/edit/point_pair.h"
#include "refracta/media/model_field.h"
#include "refracta/rays/march.h"

#include <atomic>
#include <optional>

namespace refracta {

template <class T>
struct PairMiss {
  // (I - t t^T)(x(s*) - p): the miss vector at the closest approach, perpendicular to the path's
  // tangent t there [m]. At an interior closest approach x(s*) - p is already perpendicular to t.
  Vec3<T> miss;
  double distance = 0.0;     // |x(s*) - p| [m]
  double s = 0.0;            // arc length of the closest approach [m]
  int64_t evaluations = 0;   // field evaluations of the trace
};

namespace detail {

// Distance of the path's progress along the eye-to-source direction (horizontal when the source
// is not straight above or below): the trace stops once it is well past the source.
struct PastSource {
  Vec3d origin, axis;
  double source_along;

  explicit PastSource(const PointPair& pair) : origin(pair.origin) {
    const Vec3d to_source = pair.source - pair.origin;
    Vec3d horizontal(to_source.x(), 0.0, to_source.z());
    axis = horizontal.norm() > 1e-6 * to_source.norm() ? horizontal.normalized() : to_source.normalized();
    source_along = to_source.dot(axis);
  }
  bool beyond(const Vec3d& x) const {
    return (x - origin).dot(axis) > 1.25 * source_along + 1.0;
  }
};

}  // namespace detail

// Traces the pair's path through `field` (anything with evaluate(Vec3<T>, T*, Vec3<T>*)) from the
// eye along `direction` (unit; the pair's own, or a solved camera's ray through its pixel) and
// measures its miss. cancel, when given, is polled every step (throws Cancelled).
template <class T, class Field>
PairMiss<T> pair_miss_along(const Field& field, const PointPair& pair, const Vec3<T>& direction,
                            const PairOptions& options, const std::atomic<bool>* cancel = nullptr) {
  TraceOptions trace = options.trace_options(pair);
  trace.cancel = cancel;
  const Vec3<T> x0 = pair.origin.cast<T>();
  const Vec3<T>& t0 = direction;
  const Vec3<T> p = pair.source.cast<T>();
  const detail::PastSource past(pair);

  // The search runs on the nodes' double values; only the winning segment is revisited in T.
  double best = std::numeric_limits<double>::infinity(), best_u = 0.0;
  std::optional<RayNode<T>> best_a, best_b;  // the segment (or, for vertex, the node best_a)
  auto visit = [&](const RayNode<T>& a, const RayNode<T>& b) {
    const RayNode<double> av = node_values(a), bv = node_values(b);
    if (options.distance == PairDistance::kVertex) {
      for (const auto& [node, value] : {std::pair(&a, &av), std::pair(&b, &bv)}) {
        const double d = (value->x - pair.source).norm();
        if (d < best) best = d, best_a = *node;
      }
    } else {
      if (segment_distance_bound(av, bv, pair.source) < best) {
        double d2;
        const double u = closest_on_segment(PathSegment<double>(av, bv), pair.source, &d2);
        if (std::sqrt(d2) < best) best = std::sqrt(d2), best_a = a, best_b = b, best_u = u;
      }
    }
    return !past.beyond(bv.x);
  };

  TraceEnd<T> end;
  if (options.trace == TraceMethod::kRk4) {
    Rk4Stepper<T, Field> stepper(options.step > 0.0 ? options.step : kRk4DefaultStep);
    end = march(field, x0, t0, trace, stepper, visit);
  } else {
    Rk45Stepper<T, Field> stepper(trace.tol, trace.max_length, trace.max_length);
    const std::vector<LocalRegion> regions = regions_of(field);
    stepper.keep_within(&regions);
    end = march(field, x0, t0, trace, stepper, visit);
  }
  if (!best_a) {  // no segment at all: the eye on the ground (stop_height) looking down
    best_a = end.end;
    best = (node_values(end.end).x - pair.source).norm();  // a trial: the distance was inf
  }

  PairMiss<T> out;
  Vec3<T> x, tangent;
  if (best_b) {
    const PathSegment<T> segment(*best_a, *best_b);
    const T u = refine_closest(segment, p, best_u);
    x = segment.position(u);
    tangent = segment.velocity(u);
    out.s = value_of(segment.start()) + best_u * value_of(segment.length());
  } else {
    x = best_a->x;
    tangent = best_a->v;
    out.s = value_of(best_a->s);
  }
  tangent = tangent / tangent.norm();
  const Vec3<T> offset = x - p;
  // At a closest approach at the path's start or end (a source behind the eye, or beyond where
  // the path stops) the offset runs along the path: its perpendicular part was ~0, and a source
  // 40 km behind the eye "met" (a trial). There the whole offset is the miss, as the vertex
  // measure (the original editor's) always takes it.
  const bool at_start = best_b && best_u <= 0.0 && value_of(best_a->s) == 0.0;  // paths start at s = 0
  const bool at_end = best_b && best_u >= 1.0 && value_of(best_b->s) >= value_of(end.end.s);
  out.miss = best_b && !at_start && !at_end ? Vec3<T>(offset - tangent * tangent.dot(offset)) : offset;
  out.distance = best;
  out.evaluations = end.evaluations;
  return out;
}

// The miss of the pair's path launched along its own direction.
template <class T, class Field>
PairMiss<T> pair_miss(const Field& field, const PointPair& pair, const PairOptions& options,
                      const std::atomic<bool>* cancel = nullptr) {
  return pair_miss_along<T>(field, pair, Vec3<T>(pair.direction.normalized().cast<T>()), options, cancel);
}

}  // namespace refracta
