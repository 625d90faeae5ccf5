// Tracing curved rays in double precision: one entry point over the three integrators, the
// RayPath that records a path, and batches over oneTBB. The renderer and the plots call these;
// editing instantiates march.h with Jets directly.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/media/index_field.h"
#include "refracta/rays/ray_path.h"
#include "refracta/rays/trace_options.h"

#include <functional>
#include <vector>

namespace refracta {

using SegmentVisitor = std::function<bool(const RayNode<double>&, const RayNode<double>&)>;

// Traces from origin [m] along direction (any length > 0) and calls visit on every segment.
// Throws std::invalid_argument for bad input, NumericalError where n <= 0 or non-finite.
TraceEnd<double> trace(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                       const TraceOptions& options, const SegmentVisitor& visit);

// Trace one curved ray through `field` and return its RayPath (the whole path recorded).
//
// The ray equations dx/ds = v/n, dv/ds = grad n are launched with ``v0 = n(origin) * direction /
// |direction|``. options: a refracta.TraceOptions, or None for its defaults; any of its fields may
// also be given as keywords (trace, tol, step, max_length, stop_height, max_steps, ior_floor), e.g.
// ``trace_ray(field, o, d, trace='rk4', step=0.1)``; ``method=`` is the deprecated name of
// ``trace=``. Raises ValueError for bad arguments (a path needing more than max_steps nodes is
// refused up front), refracta.NumericalError where n <= 0 or is not finite; Ctrl-C
// (KeyboardInterrupt) stops it.
RayPath trace_path(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                   const TraceOptions& options);

struct RayBatchEnds {
  std::vector<Vec3d> points, directions;
  std::vector<double> lengths;
  std::vector<int> stops;  // TraceStop
  std::vector<int64_t> evaluations;
};

// Traces many rays in parallel (oneTBB); only the ends are kept.
RayBatchEnds trace_batch(const IndexField& field, const std::vector<Vec3d>& origins,
                         const std::vector<Vec3d>& directions, const TraceOptions& options,
                         WorkControl& control);

}  // namespace refracta
