// Options and results shared by every ray integrator.
#pragma once

#include "refracta/core/error.h"
#include "refracta/rays/ray_node.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

namespace refracta {

enum class TraceMethod { kRk4, kRk45, kStratified };

TraceMethod parse_trace_method(const std::string& name);  // "rk4", "rk45", "stratified"
const char* trace_method_name(TraceMethod method);

// rk4's fixed step when none is given [m]: the original editor's.
constexpr double kRk4DefaultStep = 0.3;
// stratified: the largest distance between path nodes when no step is given [m].
constexpr double kStratifiedDefaultSpacing = 100.0;
// The least tol, of max_length: a position's round-off in doubles.
constexpr double kMinRelativeTol = 1e-15;

// Options of refracta.trace_ray and trace_rays, with their defaults (defined once, here). Set any
// field by name; validate() reports every bad value at once. Pickles through its fields.
struct TraceOptions {
  // The ray integrator (one name across the library: RenderOptions::trace, PairOptions' too).
  TraceMethod trace = TraceMethod::kRk45;
  // rk45 and stratified: target error of positions along the path [m]. rk45 holds each step's local
  // error to its share of it, which in smooth air keeps the global error within tol (measured
  // 0.002-0.5 tol); a thin hot layer or a duct amplifies errors (a trial: 10x tol at 1e-4 over 30 km
  // in a duct, 1.6x at 1e-5), and at a tol near the layer's own scale (1e-2 m and looser over a
  // 0.1 m road layer) a step can cross the layer unseen: keep tol well below the thinnest layer.
  // stratified meets tol down to about 1e-11 of max_length, its floor.
  double tol = 1e-6;
  // rk4: the fixed step [m] (default kRk4DefaultStep). rk45: the largest step (default: no
  // limit). stratified: the largest distance between path nodes (default
  // kStratifiedDefaultSpacing). 0 selects the default.
  double step = 0.0;
  double max_length = 1000.0;           // arc length at which the path ends [m]
  // The path ends where it descends through this height [m] (a ground); unset (None): no ground.
  std::optional<double> stop_height;
  // A guard against runaway step-size collapse: a path needing more steps is refused up front.
  int64_t max_steps = 10'000'000;
  // stratified: a lower bound of n over every height the path can reach (None: unknown). A ray
  // whose invariant beta = n cos e stays clearly below it can never turn, so its heights are not
  // scanned metre by metre for turning points (a path climbing 100 km: 70 000 nodes, else ~1 000).
  std::optional<double> ior_floor;
  // stratified: positions between nodes (PathSegment's quintic through them: RayPath.crossings,
  // sample) held to tol as the nodes are, with a node added where the panels alone leave them
  // farther apart (75 m across a hot road's layer: 1.4e-4 m off at tol 1e-6). Not bound: trace_ray's
  // paths always hold it to tol.
  bool hold_between_nodes = true;
  // A tolerance that grows along the path: max(floor, per_metre * (from + s)) at arc length s [m].
  struct GrowingTolerance {
    double floor = 0.0, per_metre = 0.0, from = 0.0;
    double at(double s) const { return std::max(floor, per_metre * (from + s)); }
  };
  // stratified, holding between nodes: when set, held to this instead of tol. The renderers (Caster,
  // ElevationTable) hold them to a share of the stray a pixel allows where they are: their tol is
  // the stray at the path's end, and nodes up to a chord (1 km) apart, read between with no hold,
  // strayed 15 mm from the path 300 m out, 0.43 of a 0.8-deg lens's pixel (tests/render/test_chords.py).
  std::optional<GrowingTolerance> between_nodes;
  // Polled at every step: when set, the trace throws Cancelled (Ctrl-C in a long batch).
  const std::atomic<bool>* cancel = nullptr;

  // rk4's step and stratified's node spacing, the defaults applied.
  double rk4_step() const { return step > 0.0 ? step : kRk4DefaultStep; }
  double stratified_spacing() const { return step > 0.0 ? step : kStratifiedDefaultSpacing; }
  // The shortest step the method takes over a whole path (rk4: its step; stratified: its node
  // spacing; rk45: the largest step given, 0 when none is): a path of max_length has at least
  // max_length / least_step() nodes.
  double least_step() const {
    return trace == TraceMethod::kRk4 ? rk4_step() : trace == TraceMethod::kStratified ? stratified_spacing() : step;
  }

  // Throws std::invalid_argument listing every bad field (refracta::Problems).
  void validate() const;
  // The same problems, added to a collector (options nested in others').
  void check(Problems& problems) const;
};

enum class TraceStop { kMaxLength, kStopHeight, kVisitor };
const char* trace_stop_name(TraceStop stop);

template <class T>
struct TraceEnd {
  RayNode<T> end;
  TraceStop stop = TraceStop::kMaxLength;
  int64_t steps = 0;
  int64_t evaluations = 0;  // field evaluations (n and grad n together count as one)
};

}  // namespace refracta
