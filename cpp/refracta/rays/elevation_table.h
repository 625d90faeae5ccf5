// ElevationTable: paths by launch elevation from one eye height in a height-only field. Every ray
// with the same elevation from the same height follows the same path in its vertical plane, so a
// whole image (any azimuth) is served from a few thousand exact (stratified) traces.
// The table refines adaptively: an interval of elevations is accepted when the path traced at its
// midpoint agrees with the cubic interpolation of its neighbours to within `tol` [m] at the end
// and at three interior arc lengths. Neighbours of different kind (one hits the ground, the other
// turns; a different number of turning points) are never interpolated: the interval is bisected
// down to `min_spacing`, and queries falling in what remains are traced exactly.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/media/index_field.h"
#include "refracta/rays/ray_path.h"
#include "refracta/rays/trace.h"
#include "refracta/rays/trace_options.h"

#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace refracta {

// A point of a path in its vertical plane: horizontal distance r, height h, arc length s and the
// unit tangent (cos e, sin e).
struct PlaneState {
  double r, h, s;
  double cos_e, sin_e;
  TraceStop stop;
};

// Where a path in the table's plane (eye at (0, eye_height, 0), launched toward +x) has left
// everything it could meet for good: given a node and the path length still to go, the state where
// it leaves the air (r, h, s, direction there), or nullopt to trace on. Renders over a spherical
// Earth end each entry there (Caster::plane_escape: above every object, rising, unable to turn,
// the rest from Bouguer's invariant), so a path to the horizon costs its first kilometres.
using PlaneEscape = std::function<std::optional<PlaneState>(const RayNode<double>& node, double remaining)>;

// Options of refracta.ElevationTable beside its eye height and elevation range, with their
// defaults (defined once, here). `trace` holds the exact traces' TraceOptions (their integrator is
// always 'stratified'; their tol is trace_tol, or tol when None). Pickles through its fields.
struct ElevationTableOptions {
  double eye_height = 1.5;          // [m]
  double min_elevation = -0.0175;   // [rad]
  double max_elevation = 0.0175;    // [rad]
  double tol = 1e-3;                // interpolation tolerance along the whole path [m] (renders add angular_tol)
  double angular_tol = 0.0;         // added to tol per metre of path [rad] (renders: a pixel; not bound)
  // Beyond this many exact traces, unresolved intervals stay exact (traced exactly per query).
  int64_t max_rays = 200000;
  int initial_rays = 65;            // exact traces before refining
  double min_spacing = 1e-7;        // [rad]
  // TraceOptions of the exact traces (max_length, stop_height, step): their integrator is forced to
  // stratified, and their tol is trace_tol, or the table's tol when unset (the traces then as
  // accurate as the interpolation asks).
  TraceOptions trace;
  std::optional<double> trace_tol;  // the exact traces' tolerance [m]; unset (None): tol
  // Unset: every path is traced to its end (max_length or the stop height). Set: a path ends at
  // the first node where it escapes; its escape state is interpolated as the ends are, and the
  // table's check holds it to angular_tol in direction (see PlaneEscape).
  PlaneEscape escape;
  // Nothing to meet above this height [m] (renders: the highest object). Where an escaping path
  // stays above it from a point on, that part is not held to tol (chords are not tested there):
  // the escape state is. Escape points sit on trace nodes, so their arc lengths jump from one
  // elevation to the next, and the paths compared at equal fractions of their lengths part along
  // the way by up to a node's spacing there.
  double ceiling = std::numeric_limits<double>::infinity();

  // Throws std::invalid_argument listing every bad field (refracta::Problems).
  void validate() const;
};

// A ray's end in 3-D: the plane state turned to `azimuth` [rad] about the vertical through the eye
// (measured from +x toward +z).
struct TableRayEnd {
  Vec3d point, direction;
  double length;
  TraceStop stop;
};

class ElevationTable {
 public:
  ElevationTable(FieldPtr field, const ElevationTableOptions& options, WorkControl& control);

  // End of the path launched at `elevation` [rad].
  PlaneState end(double elevation) const;
  // The same end at `azimuth` [rad] from +x toward +z, in 3-D.
  TableRayEnd end(double elevation, double azimuth) const;
  // The ends of many rays [rad] in parallel: azimuths one per elevation, or one for all (no
  // field evaluations: `evaluations` are 0). Throws std::invalid_argument for mismatched counts.
  RayBatchEnds ends(const std::vector<double>& elevations, std::vector<double> azimuths, WorkControl& control) const;
  // Point at arc length s [m] (clamped to the path's length) of the path launched at `elevation`.
  PlaneState at(double elevation, double s) const;
  // The whole path launched at `elevation`, in the vertical plane z = 0 with the eye at
  // (0, eye_height, 0): interpolated at the node fractions of the nearer traced elevation, or
  // traced exactly inside an interval where interpolation is not allowed.
  RayPath path(double elevation) const;

  // The same path node by node, built only as far as a caller walks it.
  class LazyPath {
   public:
    size_t size() const;
    RayNode<double> node(size_t k) const;
    // Node k's place and direction in the plane alone (node(k) without the field's n and grad there).
    PlaneState state(size_t k) const;
    // A lower bound of the path's height from node k on (for early exits above a scene).
    double lowest_from(size_t k) const;
    TraceStop stop() const;
    // Where the path leaves the air when it ends by the table's escape (PlaneEscape), in the plane.
    std::optional<PlaneState> escape() const;
    // The table entry whose node fractions this path has (its nodes correspond one to one), or
    // kExact when the path is traced exactly.
    size_t template_entry() const { return exact_ ? kExact : template_; }
    static constexpr size_t kExact = size_t(-1);

   private:
    friend class ElevationTable;
    const ElevationTable* table_ = nullptr;
    size_t interval_ = 0, template_ = 0;
    double elevation_ = 0.0;
    std::shared_ptr<const RayPath> exact_;  // inside an exact interval
    std::optional<PlaneState> exact_escape_;  // its escape state
    std::vector<double> exact_lowest_;
    // Interpolation stencil of this elevation (served from the interval's precomputed states).
    double weights_[4] = {0, 0, 0, 0};
    size_t count_ = 0;
    double length_ = 0.0;
  };
  // tol [m] > the table's: a path inside an exact interval is traced to it instead (a camera ray
  // that may stray a fraction of its pixel's footprint, as a ray traced per pixel does).
  LazyPath lazy_path(double elevation, double tol = 0.0) const;

  size_t size() const { return entries_.size(); }
  // The path traced at elevations()[i].
  const RayPath& entry_path(size_t i) const { return *entries_.at(i).path; }
  int64_t evaluations() const { return evaluations_; }
  size_t exact_intervals() const;  // intervals where queries are traced exactly
  const ElevationTableOptions& options() const { return options_; }
  // The options the table was built with (a copy), as a caller gives them: without the build's
  // cancel flag and the ior_floor the table found from its field.
  ElevationTableOptions built_options() const;
  const std::vector<double>& elevations() const { return elevations_; }

 private:
  struct Entry {
    std::shared_ptr<const RayPath> path;
    int kind = 0;                  // stop reason and number of turning points, packed
    std::vector<double> lowest;    // lowest height from each node to the end
    std::optional<PlaneState> escape;  // options.escape's state where the path ended by it
  };
  RayNode<double> node_of(const PlaneState& p) const;
  // The stencil of interval i: its first entry and count (4 neighbours of one kind, else 2).
  std::pair<size_t, size_t> stencil(size_t i) const;
  // Per interval and template (0: its lower entry, 1: its upper), the stencil entries' states at
  // the template's node fractions, node-major: what every pixel of that interval interpolates.
  struct StencilStates {
    std::vector<PlaneState> at_nodes[2];
  };
  void precompute_stencils();
  // cancel: polled at every step of the trace (the constructor's Ctrl-C), or none.
  // tol: the trace's tolerance when larger than the table's (lazy_path).
  Entry trace_entry(double elevation, const std::atomic<bool>* cancel = nullptr, double tol = 0.0) const;
  static PlaneState state_of(const RayPath& path, double s);
  // Interpolated state at `elevation` inside interval i of (elevations, entries), at the given
  // fraction of the interpolated length: cubic through four neighbours of one kind, else linear.
  static PlaneState interpolate(const std::vector<double>& elevations, const std::vector<Entry>& entries,
                                size_t i, double elevation, double fraction);
  // Largest distance between the path at `elevation` and its interpolation, less what the
  // tolerance allows at each checked arc length (<= 0: close enough).
  double excess(const std::vector<double>& elevations, const std::vector<Entry>& entries, size_t i,
                const Entry& mid, double elevation, double scale) const;
  // Index i with elevations_[i] <= e <= elevations_[i + 1].
  size_t interval(double elevation) const;

  FieldPtr field_;
  ElevationTableOptions options_;
  std::vector<double> elevations_;
  std::vector<Entry> entries_;
  std::vector<bool> exact_;  // per interval: trace queries exactly
  std::vector<StencilStates> stencils_;
  int64_t evaluations_ = 0;
};

}  // namespace refracta
