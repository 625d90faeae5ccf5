// The double-precision entry points over rk4, rk45 and stratified.
#include "refracta/rays/trace.h"

#include "refracta/core/error.h"
#include "refracta/core/memory.h"
#include "refracta/rays/march.h"
#include "refracta/rays/stratified.h"

#include <cmath>

namespace refracta {

namespace {

// The largest relative drift of |v| from n an rk4 path may show (1 %: far above a resolving
// step's round-off, far below the 27 % of a step that jumps a layer).
constexpr double kRk4Drift = 1e-2;

// The options and the field (once per call), then each ray.
void validate_trace(const IndexField& field, const TraceOptions& options) {
  options.validate();
  if (options.trace == TraceMethod::kStratified && !field.height_only()) {
    throw_invalid("trace='stratified' needs a field that depends on height only; ",
                  field.type_name(), " does not (use trace='rk45')");
  }
}

void validate_ray(const Vec3d& origin, const Vec3d& direction, const TraceOptions& options) {
  if (!is_finite(origin)) {
    throw_invalid("origin must be finite (got (", origin.x(), ", ", origin.y(), ", ", origin.z(), "))");
  }
  if (!is_finite(direction) || direction.cwiseAbs().maxCoeff() == 0.0) {
    throw_invalid("direction must be finite and non-zero (got (", direction.x(), ", ",
                  direction.y(), ", ", direction.z(), "))");
  }
  if (options.stop_height && origin.y() < *options.stop_height) {
    throw_invalid("origin height ", origin.y(), " m is below stop_height ", *options.stop_height, " m");
  }
}

// trace() of a ray and options already validated.
TraceEnd<double> trace_valid(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                             const TraceOptions& options, const SegmentVisitor& visit) {
  const Vec3d t0 = direction.stableNormalized();  // scaled first: 1e200 or 1e-300 components stay exact
  switch (options.trace) {
    case TraceMethod::kRk4: {
      Rk4Stepper<double, IndexField> stepper(options.rk4_step());
      // A fixed step too long for the air leaves the ray equation's invariant |v| = n behind: a
      // trial's LogisticProfile path (a 1 mm hot layer, 1 m steps) ended 29 m off, |v| / n at
      // 1.27, without a word. A drift beyond kRk4Drift is refused; a step that resolves the air
      // keeps it to round-off (2e-16 over the README's rays).
      const SegmentVisitor checked = [&](const RayNode<double>& a, const RayNode<double>& b) {
        const double drift = b.v.norm() / b.n - 1.0;
        if (!(std::abs(drift) <= kRk4Drift)) {
          throw_numerical("rk4: its fixed step of ", options.rk4_step(), " m is too long for this air: |v| / n drifted to ",
                          1.0 + drift, " at (", b.x.x(), ", ", b.x.y(), ", ", b.x.z(), ") after ", b.s,
                          " m; give a smaller step or trace='rk45' (error-controlled)");
        }
        return visit(a, b);
      };
      return march(field, origin, t0, options, stepper, checked);
    }
    case TraceMethod::kRk45: {
      const double max_step = options.step > 0 ? options.step : options.max_length;
      Rk45Stepper<double, IndexField> stepper(options.tol, max_step, options.max_length);
      const std::vector<LocalRegion> regions = field.local_regions();
      stepper.keep_within(&regions);
      return march(field, origin, t0, options, stepper, visit);
    }
    case TraceMethod::kStratified: {
      StratifiedTracer<IndexField> tracer(field, options);
      return tracer.trace(origin, t0, visit);
    }
  }
  throw std::logic_error("unknown trace method");
}

}  // namespace

TraceEnd<double> trace(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                       const TraceOptions& options, const SegmentVisitor& visit) {
  validate_trace(field, options);
  validate_ray(origin, direction, options);
  return trace_valid(field, origin, direction, options, visit);
}

RayPath trace_path(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                   const TraceOptions& options) {
  // Every node is kept: refused where they would pass half of this machine's memory (max_steps
  // bounds the count, not the bytes: rk4 with step 1e-3 m over 1000 km and max_steps 1e9 asked for
  // 88 GB). Up front where the step gives the count a path of max_length has at least; as they grow
  // otherwise, at a quarter (the vector's growth copies them once more).
  constexpr double kNodeBytes = sizeof(RayNode<double>);
  const double memory = physical_memory_bytes();
  const double least_step = options.least_step();
  if (memory > 0.0 && least_step > 0.0 && options.max_length / least_step * kNodeBytes > memory / 2.0) {
    throw_invalid("trace_ray: a path of max_length ", options.max_length, " m in steps of ", least_step, " m keeps ",
                  whole_bytes(options.max_length / least_step), " nodes of ", kNodeBytes, " bytes, more than half of ",
                  "this machine's ", readable_bytes(memory), ": raise step or lower max_length");
  }
  const double most_nodes = memory > 0.0 ? memory / 4.0 / kNodeBytes : HUGE_VAL;
  std::vector<RayNode<double>> nodes;
  const TraceEnd<double> end =
      trace(field, origin, direction, options, [&](const RayNode<double>& a, const RayNode<double>& b) {
        if (nodes.empty()) nodes.push_back(a);
        if (double(nodes.size()) >= most_nodes) {
          throw_invalid("trace_ray: the path's ", nodes.size(), " nodes so far fill a quarter of this machine's ",
                        readable_bytes(memory), ": raise step or lower max_length");
        }
        nodes.push_back(b);
        return true;
      });
  if (nodes.empty()) nodes.push_back(end.end);
  return RayPath(std::move(nodes), end.stop, end.evaluations);
}

RayBatchEnds trace_batch(const IndexField& field, const std::vector<Vec3d>& origins,
                         const std::vector<Vec3d>& directions, const TraceOptions& options,
                         WorkControl& control) {
  if (origins.size() != directions.size()) {
    throw_invalid("origins and directions must have the same length (", origins.size(), " vs ",
                  directions.size(), ")");
  }
  const int64_t count = int64_t(origins.size());
  validate_trace(field, options);
  for (int64_t i = 0; i < count; ++i) {
    try {
      validate_ray(origins[i], directions[i], options);
    } catch (const std::invalid_argument& error) {
      throw_invalid("ray ", i, ": ", error.what());
    }
  }
  RayBatchEnds out;
  out.points.resize(count);
  out.directions.resize(count);
  out.lengths.resize(count);
  out.stops.resize(count);
  out.evaluations.resize(count);
  const auto keep_going = [](const RayNode<double>&, const RayNode<double>&) { return true; };
  TraceOptions cancellable = options;
  cancellable.cancel = &control.cancel;
  parallel_for_each(count, 1, control, [&](int64_t i) {
    const TraceEnd<double> end = [&] {
      try {  // which ray of the batch met the trouble (a CustomField's NaN named a point, not the ray)
        return trace_valid(field, origins[i], directions[i], cancellable, keep_going);
      } catch (const NumericalError& error) {
        throw_numerical("ray ", i, ": ", error.what());
      }
    }();
    out.points[i] = end.end.x;
    out.directions[i] = end.end.v.normalized();
    out.lengths[i] = end.end.s;
    out.stops[i] = int(end.stop);
    out.evaluations[i] = end.evaluations;
  });
  return out;
}

}  // namespace refracta
