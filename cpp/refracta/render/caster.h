// The curved caster: "what does this ray see". Camera rays, bounce rays and shadow rays alike go
// through it: without a field (or for method 'straight') a straight Embree query; through a
// field the integrator's path cut into chords (at most options.chord long, within
// options.sagitta of the continuous path) tested against the scene, the hit refined on the path.
// Camera rays from the eye of a height-only field are served by the eye's ElevationTable.
#pragma once

#include "refracta/media/index_field.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/ray_node.h"
#include "refracta/rays/trace_options.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/embree_scene.h"

#include <optional>

namespace refracta {

// Where a ray ends: a surface hit, or the sky seen along `direction`.
struct PathEnd {
  std::optional<Hit> hit;
  Vec3d direction;     // unit, along the path at its end (toward the hit or the sky)
  double length = 0.0; // path length [m]
  int64_t chords = 0;  // straight chords tested against the scene on the way
};

class Caster {
 public:
  // field may be null (straight rays). Checks nothing but keeps references: scene, field and
  // options must outlive the caster.
  Caster(const Scene& scene, const IndexField* field, const RenderOptions& options);

  // Serve rays that start at `eye` from this table (its eye height must be eye.y()).
  void use_table(const ElevationTable* table, const Vec3d& eye);

  // The end of the path from origin along unit dir, at most max_length [m] long
  // (max_length <= 0: options.max_length for curved paths, the straight limit otherwise).
  PathEnd cast(const Vec3d& origin, const Vec3d& dir, double max_length = 0.0) const;
  // Whether anything lies on the path from origin along dir within `distance` [m] of path
  // length (shadow rays toward finite lights, straight: no field bends metres-long segments
  // measurably, see render/README in the shading tests).
  bool occluded_straight(const Vec3d& origin, const Vec3d& dir, double distance) const;

  bool curved() const { return field_ != nullptr; }
  const IndexField* field() const { return field_; }
  const Scene& scene() const { return scene_; }
  // n of the air at p (1 without a field).
  double ior(const Vec3d& p) const;

 private:
  PathEnd cast_straight(const Vec3d& origin, const Vec3d& dir, double max_length) const;
  PathEnd cast_traced(const Vec3d& origin, const Vec3d& dir, double max_length) const;
  PathEnd cast_table(const Vec3d& dir) const;
  // Height-only fields: the direction a ray at x moving along v leaves the air along, when it is
  // above every object, rising, and cannot turn within `remaining` [m] of path (n stays above
  // its invariant n(h) cos e); nullopt otherwise.
  std::optional<Vec3d> escape_direction(const Vec3d& x, const Vec3d& v, double remaining) const;

  const Scene& scene_;
  const IndexField* field_;
  const RenderOptions& options_;
  const ElevationTable* table_ = nullptr;
  Vec3d eye_ = Vec3d::Zero();
};

// Tests the path segment a -> b against the scene in chords; on a hit fills `end` and returns true.
bool hit_on_segment(const Scene& scene, const RayNode<double>& a, const RayNode<double>& b,
                    const RenderOptions& options, PathEnd* end);

// The trace options of curved render rays from origin through field.
TraceOptions curved_trace_options(const Scene& scene, const IndexField& field, const Vec3d& origin,
                                  const RenderOptions& options, double max_length);

}  // namespace refracta
