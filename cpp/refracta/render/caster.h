// The curved caster: "what does this ray see". Camera rays, bounce rays and shadow rays alike go
// through it: without a field (or for method 'straight') a straight Embree query; through a
// field the integrator's path cut into chords (at most options.chord long, within
// options.sagitta of the continuous path) tested against the scene, the hit refined on the path.
// Camera rays from the eye of a height-only field are served by the eye's ElevationTable.
//
// Fields that are height-only except in local regions (areal hot spots, a turbulent layer;
// media/local_region.h) are cast in legs: the height-only part's path (table, Bouguer chords,
// stratified) while it stays outside every region -- its chords are tested against the regions'
// borders as well as the scene -- then the full field's path (rk45) from the last state before a
// region until it has left every region, then the height-only part's again.
#pragma once

#include "refracta/media/index_field.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/ray_node.h"
#include "refracta/rays/trace_options.h"
#include "refracta/render/azimuth_ceiling.h"
#include "refracta/render/chord_plan.h"
#include "refracta/render/height_cover.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/embree_scene.h"
#include "refracta/shading/aerial_perspective.h"

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace refracta {

class BouguerBranch;

// Lower bounds of a height-only field's n: among the scene's objects, and everywhere a ray goes;
// and over the objects' heights sampled (render_ior_floors): the least n at and below each
// sampled height and at and above it, so that a ray rising from h (falling to below the objects)
// is held to the air it can meet, not to the least n anywhere among the objects (a hot road's
// surface, a hill top's thin air).
struct IorFloors {
  double objects, everywhere;
  struct Profile {
    std::vector<double> heights, below, above;  // ascending [m]; least n at and below / above each
  };
  std::shared_ptr<const Profile> profile;  // null: `objects` for every ray
  // An upper bound of |d ln n / dh| [1/m] over heights (render_ior_floors: every height a ray can
  // reach), how much a path can bend there (Caster::straight_rest). Sampled as the floors are;
  // each interval between samples is bounded by the larger of its ends' and its secant's slope,
  // widened by kGradientMargin (a feature narrower than the spacing hides as a floor's dip does).
  struct Gradients {
    std::vector<double> heights;            // ascending [m]
    std::vector<std::vector<double>> most;  // most[k][i]: the bound over intervals i .. i + 2^k - 1
    // The bound over [lo, hi] [m]; inf where that reaches outside the sampled heights.
    double steepest(double lo, double hi) const;
    // climbed[i]: the bound integrated from heights[0] to heights[i], from most[0] (sum_up: call
    // after changing it). Between two heights it bounds the total variation of ln n.
    std::vector<double> climbed;
    void sum_up();
    // climbed at the samples at or below and at or above h (their difference between two heights
    // a and b, the lower one's below and the upper one's above, bounds ln n's variation between);
    // false outside the samples.
    bool climbed_around(double h, double* below, double* above) const;
  };
  std::shared_ptr<const Gradients> gradients;  // null: no bound (no path goes straight)
  // Over a spherical Earth: the scene's highest geometry over the ground (cast_monotone's rays that
  // climb past nothing; the renderer builds it once for all its casters); null: none.
  std::shared_ptr<const HeightCover> cover;
  // The least n between h and the top of the objects (rising), or the bottom and h (falling).
  double objects_from(double h, bool rising) const;
  // The lower of both floors and the larger gradient bound (a spectral render's ends of the
  // dispersion range).
  void merge(const IorFloors& other);
};

// A state of a path where one leg of a cast hands over to the next (fields with local regions).
struct Handoff {
  Vec3d x;       // position [m]
  Vec3d dir;     // unit direction
  double s;      // arc length from the leg's start [m]
};

// Where a ray ends: a surface hit, or the sky seen along `direction`.
struct PathEnd {
  std::optional<Hit> hit;
  Vec3d direction;     // unit, along the path at its end (toward the hit or the sky; for the sky in
                       // the world frame: a CurvedEarth's flat-frame direction turned by its
                       // central angle, IndexField::sky_direction)
  Vec3d end_point = Vec3d::Zero();  // where a path without a hit ended [m]
  double length = 0.0; // path length [m]
  int64_t chords = 0;  // straight chords tested against the scene on the way
  // Legs of a cast through local regions: where this leg stopped (entering a region, or having
  // left them all) for the next to go on; unset at the path's true end.
  std::optional<Handoff> handoff;
  // A camera ray's texture footprint at its hit: two vectors [m] on the hit's plane spanning where
  // the paths of the sample's neighbours meet it (Caster::footprint); unset: the ray cone's.
  std::optional<std::array<Vec3d, 2>> footprint;
};

class Caster {
 public:
  // field may be null (straight rays). Checks nothing but keeps references: scene, field and
  // options must outlive the caster.
  Caster(const Scene& scene, const IndexField* field, const RenderOptions& options);

  // Serve rays that start at `eye` from this table (its eye height must be eye.y()); each
  // entry's chords are planned to within max(sagitta, sagitta_pixels * pixel_angle * s) [m].
  void use_table(const ElevationTable* table, const Vec3d& eye, double pixel_angle);
  // Height-only fields: lower bounds of n (render_ior_floors); rays whose invariant n cos e lies
  // below one cannot turn where it holds (cast_monotone among the objects, escape_direction above).
  void set_ior_floors(const IorFloors& floors) { floors_ = floors; }
  // Rays cast without a spread of their own (shadow and bounce rays) stand for at least a pixel
  // of this angle [rad] (the camera's): their paths may stray sagitta_pixels * spread * s too.
  // A mirror's reflection widens a pixel's cone as the camera ray would have, never narrows it
  // (flat or convex; s counts from the bounce, or from origin_width / spread behind it: cast's
  // origin_width); a shadow ray toward a distant light
  // decides a penumbra as wide as the light's disc (the sun: 9.3e-3 rad per metre from the
  // blocker), 40-4000x a quarter pixel's stray (camera pixels span 1e-5 to 1e-3 rad). Coarser
  // pixels (a thumbnail: 16 px across 20 deg are 0.022 rad) count as kMaxSecondarySpread: the
  // direction a path toward the sun leaves in must stay well inside its 4.6e-3 rad disc (at
  // 0.022 rad a 1 deg sun's irradiance was 2 % off, at 1.1e-3 rad 0.15 %).
  static constexpr double kMaxSecondarySpread = 1e-3;
  void set_secondary_spread(double pixel_angle) {
    secondary_spread_ = std::clamp(pixel_angle, 0.0, kMaxSecondarySpread);
  }

  // The end of the path from origin along unit dir, at most max_length [m] long
  // (max_length <= 0: options.max_length for curved paths, the straight limit otherwise).
  // spread > 0 [rad]: the ray stands for a pixel of that angle (camera rays): its path may stray
  // sagitta_pixels * spread * s from the exact one at arc length s (chords and rk45 tolerance).
  // origin_width [m]: a shadow or bounce ray's cone where it starts: the pixel's footprint on the
  // surface it leaves as the ray sees it (SurfaceInteraction::cone_width_along). Every ray leaving
  // that footprint stands for the same pixel, so the path may stray sagitta_pixels of that width
  // too: so far across the ray its origin, a shadow's edge or a reflection moves within a quarter
  // of the footprint on the surface, as the pixel's own samples spread over all of it. The cone
  // then widens by spread per metre, as if its apex were origin_width / spread behind the origin.
  // (A mirage that magnifies the surface M times makes that M quarter pixels in the image, as it
  // does a camera ray's own stray.) The renderer gives none after a specular event: a curved
  // mirror or a lens may narrow the cone.
  PathEnd cast(const Vec3d& origin, const Vec3d& dir, double max_length = 0.0, double spread = 0.0,
               double origin_width = 0.0) const;
  // Whether anything lies on the path from origin along dir within `distance` [m] of path
  // length (shadow rays toward finite lights, straight: no field bends metres-long segments
  // measurably, see render/README in the shading tests).
  bool occluded_straight(const Vec3d& origin, const Vec3d& dir, double distance) const;

  // The eye table's escape (ElevationTableOptions::escape, PlaneEscape): where a path of the
  // table's plane at `node`, with `remaining` [m] to go, leaves the air as escape_direction finds
  // it for a camera ray standing for a pixel of `spread` [rad]; nullopt where it may still turn
  // or meet something.
  std::optional<PlaneState> plane_escape(const RayNode<double>& node, double remaining, double spread) const;

  // Fields with local regions: use this (tabulated) height-only part outside them instead of the
  // field's own height_only_part().
  void use_layered(const IndexField* layered) { layered_ = layered; }

  // Ray differentials through the curved air (Igehy 1999, "Tracing Ray Differentials", by finite
  // differences of whole paths): where the paths launched from `origin` along each of
  // `neighbours` (two pairs of directions: the sample's footprint is spanned by the differences
  // of each pair's meeting points with the hit's plane) meet the plane of `end`'s hit, near its
  // arc length. The same machinery as cast (the eye's table, or the integrator through the field),
  // so a mirage's squeezed or stretched image gets its true footprint. nullopt where a neighbour's
  // path misses the plane near the hit (silhouettes): the cone then.
  std::optional<std::array<Vec3d, 2>> footprint(const Vec3d& origin, const PathEnd& end,
                                                const std::array<std::array<Vec3d, 2>, 2>& neighbours) const;

  bool curved() const { return field_ != nullptr; }
  // Nothing to hit, and no region to enter, above this height [m].
  double ceiling() const { return ceiling_; }
  const IndexField* field() const { return field_; }
  // The height-only air rays see outside every local region: the field itself when height-only,
  // its height_only_part, or null (a 3-D field: everything is traced).
  const IndexField* layered() const { return layered_; }
  const std::vector<LocalRegion>& regions() const { return regions_; }
  const Scene& scene() const { return scene_; }
  // How scene points sit on the physical sky's planet for aerial perspective: a CurvedEarth's flat
  // frame when the field has an Earth radius, else the flat scene.
  AirFrame air_frame() const { return field_ ? AirFrame{field_->earth_radius()} : AirFrame{}; }
  // n of the air at p (1 without a field).
  double ior(const Vec3d& p) const;

 private:
  PathEnd cast_straight(const Vec3d& origin, const Vec3d& dir, double max_length) const;
  // Over a spherical Earth, a camera ray's path that ended in the air (after max_length) above every
  // object goes on through the air -- nothing is above it to meet -- to where it leaves the air
  // (escape_direction): its sky is seen there. Unchanged where it sinks under the objects on the
  // way, and over a flat Earth (turbulent air, whose perturbed walks end without it, is never over
  // a spherical one: CurvedEarth takes height-only air). Shadow and bounce rays keep their ends:
  // the sun reaches them through light sampling's exit map, and tracing the level ones on from the
  // sea cost the cold sea 11 % and the Fata Morgana 13 % of their CPU for the sky near the
  // horizon, which changes slowly (camera rays alone: no measurable cost, paired runs at 320 x 120).
  void continue_to_sky(PathEnd* end, double spread) const;
  // secondary: a shadow or bounce ray (cast without a spread of its own): the rest of its path may
  // go on straight above the bending air (straight_rest). s0 [m]: the arc length of the ray's
  // cone at origin (cast's origin_width / spread): its tolerance at arc length s is that at s0 + s.
  PathEnd cast_traced(const Vec3d& origin, const Vec3d& dir, double max_length, double spread,
                      bool secondary = false, double s0 = 0.0) const;
  PathEnd cast_table(const Vec3d& dir) const;
  // Fields with local regions: the legs of one cast.
  PathEnd cast_in_legs(const Vec3d& origin, const Vec3d& dir, double max_length, double spread, bool from_eye,
                       bool secondary, double s0) const;
  // The full field's path (rk45) from a state next to or inside a region, until it has been inside
  // and has left every region (handoff), hits the scene or ends (`exits`: false on the last leg).
  // s0: the path's arc length at origin (the footprint's growth from there bounds the leg's tolerance).
  PathEnd cast_in_regions(const Vec3d& origin, const Vec3d& dir, double max_length, double spread, double s0,
                          bool exits) const;
  bool inside_region(const Vec3d& p) const;
  // rk45's largest step through the regions: half their smallest scale (its error estimate cannot
  // step over a feature), at most a chord.
  double step_in_regions() const;
  // The chord p -> p + len d against the scene and, for fields with local regions, against the
  // regions' borders: fills end->hit, or end->handoff with `from` (the chord's start state) when a
  // region comes first; true when either stopped the path.
  // regions = false: the scene alone (the legs inside regions).
  bool chord_blocked(const Vec3d& p, const Vec3d& d, double len, const Handoff& from, PathEnd* end,
                     bool regions = true) const;
  // Tests the path segment a -> b in chords (within `sagitta` of it; options.sagitta when <= 0).
  bool segment_blocked(const RayNode<double>& a, const RayNode<double>& b, PathEnd* end, double sagitta = 0.0,
                       bool regions = true) const;
  bool pieces_blocked(const PathSegment<double>& segment, int pieces, PathEnd* end, bool regions = true) const;
  // A hit refined onto the path may lie beyond a surface the path crosses first: the path strays
  // up to the sagitta from its chord, so a grazing ray dips into the ground under a chord that
  // passes above it and was refined onto a box beyond, below the ground (a trial, trace='rk45').
  // The chord from the chord's start `from` to the refined point `to` is a chord of the path as
  // well: the surface it meets before `to`, with the fraction of the way to `to` it lies at.
  struct EarlierHit {
    Hit hit;
    double fraction;
  };
  std::optional<EarlierHit> earlier_hit(const Vec3d& from, const Vec3d& to, PathEnd* end) const;
  // Re-checks of a refined hit (each finds a surface nearer the start; a path seldom crosses
  // more than one between its chord and itself).
  static constexpr int kEarlierHitChecks = 4;
  // Where the path from origin along dir crosses the plane through `point` with `normal`, the
  // crossing nearest arc length s_near; nullopt if none within [s_near / 2, 3 s_near / 2 + 1 m].
  std::optional<Vec3d> meets_plane(const Vec3d& origin, const Vec3d& dir, const Vec3d& point, const Vec3d& normal,
                                   double s_near) const;
  // Height-only fields: where a ray at x moving along v leaves the air (at straight_above(), however
  // far: nothing is above it to meet) and its direction there -- or, in air with no such top, where
  // it ends after `remaining` [m] of path -- when it is above every object, rising, and cannot turn
  // on the way (n stays above its invariant n(h) cos e); nullopt otherwise. spread: as cast's; over
  // a spherical Earth the run (which turns the exit by run / R) is integrated to sagitta_pixels *
  // spread * R.
  struct Escape {
    Vec3d direction, point;
    double length;  // path length from x to point [m]
  };
  std::optional<Escape> escape_direction(const Vec3d& x, const Vec3d& v, double remaining, double spread) const;
  // A rising ray's run and length [m] from height h0 up to h1 over ground where nothing stands
  // (cast_monotone): the trapezoid rule over the samples of panels, each kept where the gradient
  // bound (IorFloors::Gradients) says the rates of run and length, cot e and 1 / sin e, cannot
  // change between neighbouring samples enough to move either by more than its share of `tol` [m]
  // -- a bound, not an estimate: a layer thinner than the quadrature's samples (the cold sea's
  // inversion) cannot hide from it (only one thinner than the bound's own samples, 0.1 % of the
  // height apart). False where the ray may turn, or the gaps would be too many or cannot shrink.
  struct Climb {
    double run = 0.0, length = 0.0;
  };
  bool climb_clear(const BouguerBranch& branch, double h0, double h1, double tol, Climb* out) const;
  // Height-only fields with an ior floor: a ray so steep that it cannot turn at any height it
  // can reach, cut into chords from Bouguer's invariant (bouguer_branch.h) up past every object
  // (then out of the air) or down below them; nullopt where that does not apply (trace it).
  // spread: as cast's (the chords' tolerance grows with the arc length from origin); s0: as cast_traced's.
  std::optional<PathEnd> cast_monotone(const Vec3d& origin, const Vec3d& dir, double max_length, double spread,
                                       bool secondary = false, double s0 = 0.0) const;
  // Shadow and bounce rays through height-only fields with a gradient bound (IorFloors::gradients;
  // camera rays keep their traced paths: a horizontal silhouette grazed within the quarter pixel
  // would flip a row of pixels against the eye's table): the rest of a path at x
  // moving along v, at arc length s [m] of its cast with `remaining` [m] to go (or down to
  // `bottom` [m], the cast's stop height), as ONE straight line -- tested against the scene in
  // chords of at most options.chord -- where the bound says the air cannot bend the path off that
  // line by more than its tolerance (caster_straight.cpp). spread: as cast's; s0: as cast_traced's.
  // Fills end (hit or end point, direction, length; adds its chords) and returns true; false, end
  // untouched, where the bound does not hold or the line meets a local region.
  bool straight_rest(const Vec3d& x, const Vec3d& v, double s, double remaining, double bottom, double spread,
                     PathEnd* end, double s0 = 0.0) const;

  const Scene& scene_;
  const IndexField* field_;
  const RenderOptions& options_;
  FieldPtr own_layered_;            // the field's height_only_part, when use_layered gives none
  const IndexField* layered_ = nullptr;
  std::vector<LocalRegion> regions_;
  bool legs_ = false;               // cast in legs (cast_in_legs): fields with regions, unless rk45 is forced
  double ceiling_ = 0.0;            // nothing to hit, and no region to enter, above this height [m]
  const ElevationTable* table_ = nullptr;
  Vec3d eye_ = Vec3d::Zero();
  std::optional<IorFloors> floors_;
  double secondary_spread_ = 0.0;   // set_secondary_spread
  std::vector<ChordPlan> plans_;  // per table entry
  AzimuthCeiling azimuth_ceiling_;  // about the eye (use_table); none (+inf) with local regions
  double exact_tol_ = 0.0;        // [m] camera rays inside the table's exact intervals are traced to this
};

// The trace options of curved render rays from origin through field.
TraceOptions curved_trace_options(const Scene& scene, const IndexField& field, const Vec3d& origin,
                                  const RenderOptions& options, double max_length);

// Every height a render ray can reach: from 1 m below the lowest geometry (or the eye) to
// max_length above the highest.
std::pair<double, double> render_heights(const Scene& scene, const Vec3d& eye, const RenderOptions& options);
// A height-only field's least n (lowest_ior_sampled) among the objects (render_heights' lower
// end to the highest object or the eye) and over all of render_heights.
IorFloors render_ior_floors(const Scene& scene, const IndexField& field, const Vec3d& eye, const RenderOptions& options);
// A height-only field sampled over heights [lo, hi] [m] as lowest_ior_sampled samples (1e-3 of the
// distance from `ground` apart, at least 1 mm), and at hi: one evaluation per height, from which
// render_ior_floors reads both its floors and its gradient bound.
struct HeightSamples {
  std::vector<double> heights;  // ascending [m]
  std::vector<double> n, dn;    // n and dn/dh there; NaN where the field cannot be evaluated
};
HeightSamples sample_heights(const IndexField& field, double lo, double hi, double ground);
// A height-only field's gradient bound (IorFloors::Gradients) over the sampled heights.
std::shared_ptr<const IorFloors::Gradients> gradient_bound(const HeightSamples& samples);

}  // namespace refracta
