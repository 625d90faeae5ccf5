// The curved caster (caster.h).
#include "refracta/render/caster.h"

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/render/bouguer_branch.h"
#include "refracta/render/chord_plan.h"

#include <tbb/parallel_for.h>
#include "refracta/rays/march.h"
#include "refracta/rays/trace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>

namespace refracta {

namespace {

// A leg rising more steeply than this (sin of ~5.7 deg) from inside a region: cast_in_regions'
// first step (below).
constexpr double kSteepRise = 0.1;

// The longest last Newton step of an escape taken without a panel (escape_direction) [m]: the
// tabulated air checks its cubics every 0.25 m, and a ray's escape lies above every object.
constexpr double kLinearStep = 1.0;

// The eye's table path for a direction's elevation, turned about the vertical through the eye to
// the direction's azimuth (a height-only field's paths differ by that turn alone).
struct TurnedTablePath {
  // tol: lazy_path's (a path inside an exact interval is traced to it).
  TurnedTablePath(const ElevationTable& table, const Vec3d& eye, const Vec3d& dir, double tol)
      : plane(table.lazy_path(std::asin(std::clamp(dir.y(), -1.0, 1.0)), tol)), eye(eye) {
    const double horizontal = std::sqrt(dir.x() * dir.x() + dir.z() * dir.z());
    cx = horizontal > 0 ? dir.x() / horizontal : 1.0;
    cz = horizontal > 0 ? dir.z() / horizontal : 0.0;
  }
  RayNode<double> node(size_t k) const {
    RayNode<double> out = plane.node(k);
    const double r = out.x.x(), vr = out.v.x();
    out.x = Vec3d(eye.x() + r * cx, out.x.y(), eye.z() + r * cz);
    out.v = Vec3d(vr * cx, out.v.y(), vr * cz);
    return out;
  }
  // Node k's arc length, place and unit direction: what a chord needs, without the field's n there.
  struct Point {
    double s;
    Vec3d x, direction;
  };
  Point point(size_t k) const {
    const PlaneState p = plane.state(k);
    return {p.s, Vec3d(eye.x() + p.r * cx, p.h, eye.z() + p.r * cz), Vec3d(p.cos_e * cx, p.sin_e, p.cos_e * cz)};
  }

  const ElevationTable::LazyPath plane;
  const Vec3d eye;
  double cx = 1.0, cz = 0.0;
};


// Point u in [lo, hi] of the segment on the plane through `on` with normal n (n faces the arriving
// path), by Newton from u. Where Newton does not end on the plane with the path heading into it,
// the path dips through the plane and out again within the segment (a ray turning in the hot
// layer just under the ground: the hot road's fold) and Newton, started near the dip's bottom
// where the slope vanishes, slid to the rising side or stalled at a bound (measured: the ground
// met from below, shaded black, a dark line across the hot road at its fold): the first crossing
// into the surface from the segment's start (first_plane_crossing) is taken instead.
double refine_on_plane(const PathSegment<double>& seg, const Vec3d& n, const Vec3d& on, double u, double lo,
                       double hi) {
  for (int it = 0; it < 8; ++it) {
    const double f = n.dot(seg.position(u) - on), df = n.dot(seg.velocity(u));
    if (df == 0.0) break;
    const double next = std::clamp(u - f / df, lo, hi);
    const bool converged = std::abs(next - u) < 1e-14;
    u = next;
    if (converged) break;
  }
  const double offset = n.dot(on);
  const double miss = std::abs(n.dot(seg.position(u)) - offset);
  if ((miss <= 1e-9 * (1.0 + std::abs(seg.length())) && n.dot(seg.velocity(u)) < 0.0) ||
      !(n.dot(seg.position(0.0)) > offset)) {
    return u;
  }
  const double first = first_plane_crossing(seg, n, offset);
  return first >= 0.0 ? std::clamp(first, lo, hi) : u;
}

// The longest a path can run inside the regions without leaving them all: each vertical
// cylinder's diagonal from its top to `bottom` (the trace's stop height), summed, doubled for paths
// that curve (inf: a slab).
double longest_inside(const std::vector<LocalRegion>& regions, double bottom) {
  double sum = 0.0;
  for (const LocalRegion& region : regions) sum += std::hypot(2.0 * region.radius, region.top - bottom);
  return 2.0 * sum;
}

// dir with its elevation at x set by Bouguer's invariant n(h) cos e = beta of a path through the
// height-only `layered` air (its azimuth and the sign of its climb kept); dir itself where no
// elevation satisfies it (a place, within its tolerance, past the path's turning height).
Vec3d on_invariant(const IndexField& layered, const Vec3d& x, const Vec3d& dir, double beta) {
  double n, dn;
  layered.evaluate_height(x.y(), &n, &dn);
  const double cos_e = beta / n, horizontal = std::hypot(dir.x(), dir.z());
  if (!(cos_e < 1.0) || !(horizontal > 0.0)) return dir;
  const double sin_e = std::copysign(std::sqrt(1.0 - cos_e * cos_e), dir.y());
  return Vec3d(dir.x() / horizontal * cos_e, sin_e, dir.z() / horizontal * cos_e);
}

// The path's end at parameter u of seg, where it meets the surface of `hit`.
void end_at(const PathSegment<double>& seg, double u, const Hit& hit, PathEnd* end) {
  Hit refined = hit;
  refined.point = seg.position(u);
  end->hit = refined;
  end->direction = seg.velocity(u).normalized();
  end->length = seg.start() + u * seg.length();
}

}  // namespace

TraceOptions curved_trace_options(const Scene& scene, const IndexField& field, const Vec3d& origin,
                                  const RenderOptions& options, double max_length) {
  TraceOptions trace_options;
  trace_options.trace = options.trace ? *options.trace
                                       : (field.height_only() ? TraceMethod::kStratified : TraceMethod::kRk45);
  trace_options.tol = options.tol;
  trace_options.max_length = max_length;
  trace_options.step = options.chord;
  trace_options.hold_between_nodes = false;  // unless a share of the pixel's footprint is given (cast_traced, ElevationTable)
  // Nothing can be hit below the lowest geometry: end the path 1 m under it (or under the origin).
  trace_options.stop_height = std::min(scene.lowest(), origin.y()) - 1.0;
  return trace_options;
}

std::pair<double, double> render_heights(const Scene& scene, const Vec3d& eye, const RenderOptions& options) {
  return {std::min(scene.lowest(), eye.y()) - 1.0, std::max(scene.highest(), eye.y()) + options.max_length};
}

HeightSamples sample_heights(const IndexField& field, double lo, double hi, double ground) {
  HeightSamples out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto sample = [&](double h) {
    double n = nan, dn = nan;
    try {
      field.evaluate_height(h, &n, &dn);
    } catch (const std::exception&) {
      n = dn = nan;  // outside the modelled air
    }
    out.heights.push_back(h);
    out.n.push_back(n);
    out.dn.push_back(dn);
  };
  for (double h = lo; h < hi; h += std::max(1e-3, 1e-3 * std::abs(h - ground))) sample(h);
  sample(hi);
  return out;
}

IorFloors render_ior_floors(const Scene& scene, const IndexField& field, const Vec3d& eye, const RenderOptions& options) {
  const auto [lo, hi] = render_heights(scene, eye, options);
  const double top = std::max(scene.highest(), eye.y());
  // One pass over every height a ray can reach (finest near the ground, h = 0, or the end of the
  // range nearer it) feeds the floors among the objects and the gradient bound alike.
  const HeightSamples samples = sample_heights(field, lo, hi, std::clamp(0.0, lo, hi));
  // lowest_ior_sampled's margin; its samples among the objects (those up to the top), kept with
  // their heights.
  constexpr double kMargin = 1e-5;
  auto profile = std::make_shared<IorFloors::Profile>();
  for (size_t i = 0; i < samples.heights.size() && samples.heights[i] <= top; ++i) {
    const double n = samples.n[i];
    if (!(n > 0.0) || !std::isfinite(n)) continue;
    profile->heights.push_back(samples.heights[i]);
    profile->below.push_back(n - kMargin);
  }
  const size_t count = profile->heights.size();
  profile->above = profile->below;
  for (size_t i = 1; i < count; ++i) profile->below[i] = std::min(profile->below[i], profile->below[i - 1]);
  for (size_t i = count; i-- > 1;) profile->above[i - 1] = std::min(profile->above[i - 1], profile->above[i]);
  IorFloors floors;
  floors.objects = count > 0 ? profile->below.back() : 0.0;  // nothing evaluable: no bound (lowest_ior_sampled's 0)
  floors.everywhere = std::min(floors.objects, lowest_ior_sampled(field, top, hi, kMargin));
  if (count >= 2) floors.profile = std::move(profile);  // else nothing to tell heights apart
  floors.gradients = gradient_bound(samples);
  return floors;
}

double IorFloors::objects_from(double h, bool rising) const {
  if (!profile) return objects;
  const std::vector<double>& heights = profile->heights;
  // The samples either side of h both count: the air between them is bounded by neither alone.
  const size_t above_h = size_t(std::lower_bound(heights.begin(), heights.end(), h) - heights.begin());
  if (rising) return above_h == 0 ? profile->above.front() : profile->above[above_h - 1];
  return above_h >= heights.size() ? profile->below.back() : profile->below[above_h];
}

void IorFloors::merge(const IorFloors& other) {
  objects = std::min(objects, other.objects);
  everywhere = std::min(everywhere, other.everywhere);
  if (gradients && other.gradients && gradients->heights == other.gradients->heights) {
    auto most = std::make_shared<Gradients>(*gradients);
    for (size_t k = 0; k < most->most.size(); ++k) {
      for (size_t i = 0; i < most->most[k].size(); ++i) {
        most->most[k][i] = std::max(most->most[k][i], other.gradients->most[k][i]);
      }
    }
    most->sum_up();
    gradients = std::move(most);
  } else {
    gradients.reset();  // not sampled alike: no bound
  }
  if (!profile || !other.profile || profile->heights != other.profile->heights) {
    profile.reset();  // not sampled alike: the overall floors alone
    return;
  }
  auto merged = std::make_shared<IorFloors::Profile>(*profile);
  for (size_t i = 0; i < merged->heights.size(); ++i) {
    merged->below[i] = std::min(merged->below[i], other.profile->below[i]);
    merged->above[i] = std::min(merged->above[i], other.profile->above[i]);
  }
  profile = std::move(merged);
}

bool Caster::chord_blocked(const Vec3d& p, const Vec3d& d, double len, const Handoff& from, PathEnd* end,
                           bool regions) const {
  ++end->chords;
  // Each chord reaches slightly into the next so that no hit is lost at a joint.
  const double reach = len * (1.0 + 1e-6) + 1e-6;
  auto hit = scene_.intersect(p, d, reach);
  if (regions && legs_) {
    if (const auto t = first_entry(regions_, p, d, reach); t && (!hit || *t < hit->t)) {
      end->handoff = from;
      return true;
    }
  }
  if (!hit) return false;
  end->hit = hit;
  return true;
}

std::optional<Caster::EarlierHit> Caster::earlier_hit(const Vec3d& from, const Vec3d& to, PathEnd* end) const {
  const Vec3d chord = to - from;
  const double dist = chord.norm();
  if (!(dist > 0.0)) return std::nullopt;
  ++end->chords;
  // The refined point's own surface (or its neighbour across an edge) is met at the chord's end:
  // float32 geometry puts it within 1e-3 of the way.
  const auto earlier = scene_.intersect(from, chord / dist, (1.0 - 1e-3) * dist);
  if (!earlier) return std::nullopt;
  return EarlierHit{*earlier, earlier->t / dist};
}

bool Caster::segment_blocked(const RayNode<double>& a, const RayNode<double>& b, PathEnd* end, double sagitta,
                             bool regions) const {
  const PathSegment<double> seg(a, b);
  // Deviation of the path from the segment's chord, sampled; it shrinks with the square of the
  // chord length, so n chords deviate by about deviation / n^2.
  const Vec3d ab = b.x - a.x;
  const double ab2 = std::max(ab.squaredNorm(), 1e-300);
  double deviation = 0.0;
  for (double u : {0.25, 0.5, 0.75}) {
    const Vec3d q = seg.position(u) - a.x;
    deviation = std::max(deviation, (q - ab * (q.dot(ab) / ab2)).norm());
  }
  const int by_sagitta = int(std::ceil(std::sqrt(deviation / (sagitta > 0.0 ? sagitta : options_.sagitta))));
  const int pieces = std::clamp(std::max(by_sagitta, int(std::ceil(seg.length() / options_.chord))), 1, 1 << 20);
  return pieces_blocked(seg, pieces, end, regions);
}

bool Caster::pieces_blocked(const PathSegment<double>& seg, int pieces, PathEnd* end, bool regions) const {
  for (int i = 0; i < pieces; ++i) {
    const double u0 = double(i) / pieces, u1 = double(i + 1) / pieces;
    const Vec3d p0 = seg.position(u0), d = seg.position(u1) - p0;
    const double len = d.norm();
    if (len == 0.0) continue;
    const Handoff from{p0, seg.velocity(u0).normalized(), seg.start() + u0 * seg.length()};
    if (!chord_blocked(p0, d / len, len, from, end, regions)) continue;
    if (end->handoff) return true;
    Hit hit = *end->hit;
    const double du = u1 - u0;
    double u = refine_on_plane(seg, hit.normal, hit.point, u0 + du * hit.t / len, u0 - 0.5 * du,
                               std::min(u1 + 0.5 * du, 1.0));
    for (int check = 0; check < kEarlierHitChecks && u > u0; ++check) {
      const auto earlier = earlier_hit(p0, seg.position(u), end);
      if (!earlier) break;
      const double guess = u0 + (u - u0) * earlier->fraction;
      u = refine_on_plane(seg, earlier->hit.normal, earlier->hit.point, guess, u0 - 0.5 * du, u);
      hit = earlier->hit;
    }
    end_at(seg, u, hit, end);
    return true;
  }
  return false;
}

Caster::Caster(const Scene& scene, const IndexField* field, const RenderOptions& options)
    : scene_(scene), field_(options.method == RenderMethod::kStraight ? nullptr : field), options_(options) {
  ceiling_ = scene_.highest();
  if (!field_) return;
  if (field_->height_only()) {
    layered_ = field_;
  } else if ((own_layered_ = field_->height_only_part())) {
    layered_ = own_layered_.get();
    regions_ = field_->local_regions();
    ceiling_ = std::max(ceiling_, highest_top(regions_));
    // trace = 'rk45' stands for a 3-D field: every path through the full field, no legs (the
    // layered part still pre-bends shadow rays toward distant lights, and above every region
    // rays still leave along Bouguer's invariant).
    legs_ = !(options.trace && *options.trace == TraceMethod::kRk45);
    // Inside a turbulent layer (a slab: a path may run in it all its length) rk45 steps at most
    // half its scale, 8 cells: refused here, naming the cells, where that would take more steps
    // than a trace may (a trial's turbulence of 1 um cells failed each ray on TraceOptions' step).
    const double step = step_in_regions();
    const int64_t max_steps = TraceOptions().max_steps;
    const bool slab =
        std::any_of(regions_.begin(), regions_.end(), [](const LocalRegion& r) { return !std::isfinite(r.radius); });
    if (slab && step < options.chord && options.max_length / step > double(max_steps)) {
      throw_invalid("render: rk45 steps at most ", step, " m through the turbulence (half its scale of 8 cells): a ",
                    "path of max_length ", options.max_length, " m in it would take more than ", max_steps,
                    " steps; give the turbulence larger cells (Turbulence(spacing=...)) or a shorter max_length");
    }
  }
}

void Caster::use_table(const ElevationTable* table, const Vec3d& eye, double pixel_angle) {
  table_ = table;
  eye_ = eye;
  // A camera ray inside an exact interval is traced as cast_traced traces one: to a quarter of
  // its pixel's footprint at the path's end, or the sagitta.
  exact_tol_ = std::max(options_.sagitta, options_.sagitta_pixels * pixel_angle * options_.max_length);
  // Half the allowed stray for the plan: a pixel's path interpolates its entry's, and may bend a
  // little more between the same nodes.
  const double sagitta = options_.sagitta, per_metre = options_.sagitta_pixels * pixel_angle;
  auto tolerance = [&](double s) { return 0.5 * std::max(sagitta, per_metre * s); };
  if (regions_.empty()) azimuth_ceiling_ = AzimuthCeiling(scene_, eye);
  plans_.assign(table->size(), {});
  tbb::parallel_for(size_t(0), table->size(), [&](size_t i) {
    const DefaultFloatingPointMode fp_mode;  // parallel.h: whatever mode the worker was left in
    plans_[i] = plan_chords(table->entry_path(i), tolerance, options_.chord);
  });
}

double Caster::ior(const Vec3d& p) const {
  if (!field_) return 1.0;
  double n;
  Vec3d grad;
  field_->evaluate_checked(p, &n, &grad);
  return n;
}

PathEnd Caster::cast(const Vec3d& origin, const Vec3d& dir, double max_length, double spread,
                     double origin_width) const {
  if (!field_) return cast_straight(origin, dir, max_length > 0.0 ? max_length : kSceneReach);
  const bool from_eye = table_ && origin == eye_ && max_length <= 0.0;
  const bool secondary = !(spread > 0.0);  // a shadow or bounce ray
  if (secondary) spread = secondary_spread_;
  const double s0 = secondary && spread > 0.0 && origin_width > 0.0 ? origin_width / spread : 0.0;
  const double length = max_length > 0.0 ? max_length : options_.max_length;
  PathEnd end = legs_ ? cast_in_legs(origin, dir, length, spread, from_eye, secondary, s0)
                      : from_eye ? cast_table(dir) : cast_traced(origin, dir, length, spread, secondary, s0);
  if (!end.hit) {
    if (!secondary) continue_to_sky(&end, spread);
    end.direction = field_->sky_direction(end.end_point, end.direction);
  }
  return end;
}

void Caster::continue_to_sky(PathEnd* end, double spread) const {
  if (!layered_ || !std::isfinite(layered_->earth_radius())) return;
  const Vec3d x = end->end_point + Vec3d(0.0, 1e-9 * (1.0 + std::abs(end->end_point.y())), 0.0);
  if (!(x.y() > ceiling_) || !(x.y() < layered_->straight_above())) return;
  auto escaped = [&](const Vec3d& p, const Vec3d& v) {
    const auto exit = escape_direction(p, v, kSceneReach, spread);
    if (exit) end->direction = exit->direction, end->end_point = exit->point;
    return exit.has_value();
  };
  if (escaped(x, end->direction)) return;
  // Too level for the escape's quadrature, or still sinking toward its lowest point: traced on
  // until it is steep enough (Earth's curvature raises a level ray by 1 - k of a radian per R of
  // path: 1e-3 in ~8 km), at most kTableLongestPath; one that sinks under the objects (to the sea
  // beyond max_length, or trapped in a duct) keeps its end.
  TraceOptions options = curved_trace_options(scene_, *layered_, x, options_, kTableLongestPath);
  if (std::isfinite(ceiling_)) options.stop_height = ceiling_;
  try {
    trace(*layered_, x, end->direction, options,
          [&](const RayNode<double>&, const RayNode<double>& b) { return !escaped(b.x, b.v); });
  } catch (const NumericalError&) {
    // out of the modelled air before it could escape: the end stays where max_length left it
  }
}

double Caster::step_in_regions() const { return std::min(options_.chord, 0.5 * smallest_scale(regions_)); }

bool Caster::inside_region(const Vec3d& p) const {
  return std::any_of(regions_.begin(), regions_.end(), [&](const LocalRegion& r) { return r.contains(p); });
}

PathEnd Caster::cast_in_legs(const Vec3d& origin, const Vec3d& dir, double max_length, double spread,
                             bool from_eye, bool secondary, double s0) const {
  // A path that grazes a region's border could hand over back and forth: after this many legs
  // the full field traces the rest without handing over.
  constexpr int kMaxLegs = 32;
  Vec3d x = origin, d = dir;
  double s = 0.0;
  int64_t chords = 0;
  // Legs alternate: the layered air's until it meets a region, the full field's until it has left
  // them all.
  bool in_regions = inside_region(origin);
  for (int leg = 0;; ++leg) {
    const bool last = leg + 1 >= kMaxLegs;
    // Initialised in one expression: GCC 12 reads a default-constructed PathEnd's empty optionals
    // as used uninitialised when it is assigned later (-Wuninitialized under -Werror).
    // s0: a secondary ray's cone (cast); a traced leg's tolerance counts from its own start, as before.
    PathEnd part = last || in_regions     ? cast_in_regions(x, d, max_length - s, spread, s0 + s, !last)
                   : leg == 0 && from_eye ? cast_table(d)
                                          : cast_traced(x, d, max_length - s, spread, secondary, s0);
    chords += part.chords;
    if (!part.handoff || !(part.handoff->s < max_length - s)) {
      part.length += s;
      part.chords = chords;
      part.handoff.reset();
      return part;
    }
    x = part.handoff->x;
    d = part.handoff->dir;
    if (leg == 0 && from_eye && !in_regions) {
      // The table holds its interpolated paths' places to its tolerance, not their directions (a
      // mirage ray entering a turbulent layer 76 m out came 3.3e-4 rad off, and a duct above
      // trapped it): the camera ray's invariant gives the direction at the handoff's place.
      double n_eye, dn_eye;
      layered_->evaluate_height(eye_.y(), &n_eye, &dn_eye);
      d = on_invariant(*layered_, x, d, n_eye * std::hypot(dir.x(), dir.z()) / dir.norm());
    }
    s += part.handoff->s;
    if (!in_regions && leg > 0 && part.handoff->s <= 0.0) {
      // No progress: the layered path enters at once where the full one has just left (a border
      // grazed within the chords' sagitta); the full field's path goes on without handing over.
      part = cast_in_regions(x, d, max_length - s, spread, s0 + s, false);
      part.length += s;
      part.chords += chords;
      return part;
    }
    in_regions = !in_regions;
  }
}

PathEnd Caster::cast_in_regions(const Vec3d& origin, const Vec3d& dir, double max_length, double spread, double s0,
                                bool exits) const {
  PathEnd end;
  end.direction = dir;
  TraceOptions trace_options = curved_trace_options(scene_, *field_, origin, options_, max_length);
  trace_options.trace = TraceMethod::kRk45;
  trace_options.step = step_in_regions();
  // A pixel may stray sagitta_pixels of its footprint, k = sagitta_pixels * spread [m per metre of
  // path]. Regions of bounded size (hot spots): half of it for the integrated path, half for the
  // chords that stand for it (both can stray the same way: a whole row of ground hits half a pixel
  // off when each took all of it). rk45 keeps each step's position error plus its direction error
  // carried on within tol * h / max_length (march.h); tol = k/2 (s0 + max_length) holds that to
  // about k/2 h per step, so wherever the path ends -- a hit inside the leg, or beyond it after a
  // handoff -- its summed stray stays within k/2 of its length. (Holding a leg that hands over to
  // the footprint where it starts, k s0 over the whole reach, asked 600x that of a camera ray
  // entering a hot spot 20 m from the eye: 5x the steps.) A direction error is carried at most as
  // far as the path can run inside the regions (reach): beyond them the footprint grows with the
  // path as fast as the direction error's stray, and the leg holds the direction within k/2.
  // Slabs (a turbulent layer, unbounded: the strict trace the shimmer fast path is judged by)
  // keep the whole k, and a leg that hands over is held to the footprint where it starts.
  const double reach = longest_inside(regions_, *trace_options.stop_height);
  const bool bounded = std::isfinite(reach);
  const double per_metre = (bounded ? 0.5 : 1.0) * options_.sagitta_pixels * spread;
  trace_options.tol =
      std::max({trace_options.tol, options_.sagitta, per_metre * (exits && !bounded ? s0 : s0 + max_length)});
  trace_options.validate();
  bool been_inside = inside_region(origin);
  // A leg that enters a hot spot from outside starts in its border air, nearly the layered air:
  // its first step may descend a quarter of its height above the ground (rk45's default 1 m took
  // three growing steps to reach the scale of the air; a first step down into the spot's surface
  // layer is one its error estimate can pass over). A leg that rises steeply from inside (a shadow
  // or bounce ray leaving a hot surface) may climb a quarter of the way to the regions' top in its
  // first step: from its default 1 m rk45 shrank about twice a leg (33 field evaluations a leg on
  // a compact spot under the hot road's 35 deg sun, 23 with this). Other legs: 1 m.
  const Vec3d t0 = dir.normalized();
  double first_step = 0.0;
  if (bounded && !been_inside) {
    first_step = 0.25 * (origin.y() - scene_.lowest()) / std::max(std::abs(t0.y()), 1e-12);
  } else if (bounded && t0.y() > kSteepRise) {
    first_step = 0.25 * (highest_top(regions_) - origin.y()) / t0.y();
  }
  Rk45Stepper<double, IndexField> stepper(trace_options.tol, trace_options.step, trace_options.max_length,
                                          first_step, reach);
  stepper.hold_after_rejection();
  march(*field_, origin, t0, trace_options, stepper, [&](const RayNode<double>& a, const RayNode<double>& b) {
    if (segment_blocked(a, b, &end, std::max(options_.sagitta, per_metre * (s0 + a.s)), /*regions=*/false)) return false;
    end.direction = b.v.normalized();
    end.length = b.s;
    end.end_point = b.x;
    const bool inside = inside_region(b.x);
    if (!been_inside && !inside) {  // nodes may straddle a region: the chord between them may cross it
      const Vec3d ab = b.x - a.x;
      const double len = ab.norm();
      been_inside = len > 0.0 && first_entry(regions_, a.x, ab / len, len).has_value();
    }
    been_inside = been_inside || inside;
    if (exits && been_inside && !inside) {
      end.handoff = Handoff{b.x, end.direction, b.s};
      return false;
    }
    return true;
  });
  return end;
}

bool Caster::occluded_straight(const Vec3d& origin, const Vec3d& dir, double distance) const {
  return distance > 0.0 && scene_.occluded(origin, dir, distance);
}

PathEnd Caster::cast_straight(const Vec3d& origin, const Vec3d& dir, double max_length) const {
  PathEnd end;
  end.direction = dir;
  end.hit = scene_.intersect(origin, dir, std::min(max_length, kSceneReach));
  end.chords = 1;
  if (end.hit) end.length = end.hit->t;
  return end;
}

std::optional<Caster::Escape> Caster::escape_direction(const Vec3d& x, const Vec3d& v, double remaining,
                                                       double spread) const {
  if (!layered_ || !(x.y() > ceiling_) || !(v.y() > 0.0) || !(remaining > 0.0)) {
    return std::nullopt;
  }
  const Vec3d t = v.normalized();
  const double cos_e = std::sqrt(t.x() * t.x() + t.z() * t.z());
  double n_x, dn, sin_x;
  layered_->evaluate_height(x.y(), &n_x, &dn);
  const BouguerBranch branch(*layered_, n_x * cos_e);
  // Below 0.57 deg of elevation the one-panel quadrature loses digits near a turn: trace instead.
  // Over a spherical Earth the quadrature is adaptive (below), and level rays curve up in flat
  // coordinates by only 1/R per metre (0.01 rad takes 64 km): there 0.057 deg.
  const bool spherical = std::isfinite(layered_->earth_radius());
  const double kMinSine = spherical ? 1e-3 : 1e-2;
  if (!branch.at(x.y(), kMinSine, &n_x, &dn, &sin_x)) return std::nullopt;
  // The height where the path has run `remaining` metres, by Newton on s(h) = remaining (ds/dh =
  // 1/sin e); the sky is seen along the direction there, as at the end of a traced path.
  // A ray below the field's ior floor cannot turn on the way: its first guess comes from the
  // mean of sin e at both ends (the trapezoid rule in s), and Newton runs only where sin e
  // changes by more than 1 %. Otherwise every step integrates from x, and the quadrature's
  // nodes check that the ray stays clear of a turn all the way up.
  const bool cannot_turn = floors_ && branch.beta() < floors_->everywhere * std::sqrt(1.0 - kMinSine * kMinSine);
  const Vec3d across = cos_e > 0.0 ? Vec3d(t.x() / cos_e, 0.0, t.z() / cos_e) : Vec3d::Zero();
  // Over a spherical Earth a ray that reaches the top of its air goes straight in the world frame
  // from there: its sky is seen along its direction at the top (one adaptive integral instead of
  // Newton's several). That holds whatever is left of its max_length, which bounds where the scene
  // may be met: nothing is above this ray. Most of a low sun's refraction lies beyond the few
  // kilometres a scene spans: seen along the direction after the default 5 km instead, a sun 0.3
  // deg up showed 27' low (10 deg up: 4.8'), against astronomical_refraction (a trial). Over a flat
  // Earth a ray this low may still turn back toward the ground far beyond max_length: there the
  // sky stays where the path ends.
  const double top = layered_->straight_above();
  // A ray that stands for a pixel (spread) may leave turned by sagitta_pixels of it: its run, to
  // that angle times the Earth's radius (over a flat Earth the run turns nothing: unused).
  const double run_tol = spherical ? options_.sagitta_pixels * spread * layered_->earth_radius() : 0.0;
  double n, sin_h, run, length;
  if (spherical && std::isfinite(top) && top > x.y() && branch.at(top, kMinSine, &n, &dn, &sin_h) &&
      branch.integrate(x.y(), top, kMinSine, &run, &length, 1e-8, run_tol)) {
    const double scale = cos_e > 0.0 ? std::sqrt(std::max(0.0, 1.0 - sin_h * sin_h)) / cos_e : 0.0;
    return Escape{Vec3d(t.x() * scale, sin_h, t.z() * scale).normalized(),
                  Vec3d(x.x() + run * across.x(), top, x.z() + run * across.z()), length};
  }
  double h = x.y() + remaining * sin_x;
  if (!branch.at(h, kMinSine, &n, &dn, &sin_h)) return std::nullopt;  // the ray may turn below that height
  if (cannot_turn) {
    h = x.y() + remaining * 0.5 * (sin_x + sin_h);
    if (!branch.at(h, kMinSine, &n, &dn, &sin_h)) return std::nullopt;
  }
  // Over a spherical Earth (flat coordinates) the run sets the central angle that turns the exit
  // into the world frame: integrated to 1e-8 (0.01 m in 1000 km, 0.3 mas of angle).
  const double relative_tol = spherical ? 1e-8 : 0.0;
  // Run and length to the first guess, then each Newton step's own stretch added to them: one
  // 8-point panel over the step (metres, where the rates barely change: the sum is the whole
  // integral to well under the tolerance above) instead of the whole range integrated again.
  // The stretches tile every height the path climbs, so their nodes still check it all the way
  // (but a last step of at most kLinearStep, checked at its ends).
  if (!branch.integrate(x.y(), h, kMinSine, &run, &length, relative_tol, run_tol)) return std::nullopt;
  for (int it = 0; it < 6 && (!cannot_turn || std::abs(sin_h - sin_x) > 1e-2 * sin_x); ++it) {
    const double step = (remaining - length) * sin_h;
    const double h_next = h + step;
    double n_next, dn_next, sin_next;
    if (!branch.at(h_next, kMinSine, &n_next, &dn_next, &sin_next)) return std::nullopt;
    // Converged once a step turns the exit direction by a hundredth of the pixel's stray or less:
    // a height change dh turns it by cos e dn dh / (n sin e) (Bouguer's invariant). Newton
    // converges quadratically, so what the next step would add is far smaller still. Over a
    // spherical Earth the step also moves the run, which turns the exit by run / R: about as much
    // again in the flat frame's air, so the stop is at ~2e-2 of the stray. Without a pixel
    // (spread 0): once the step's cos e dn dh is below 1e-12 (1e-9 rad at the least sin e, 1e-3).
    const double cos_h = std::sqrt(std::max(0.0, 1.0 - sin_h * sin_h));
    const double cos_next = std::sqrt(std::max(0.0, 1.0 - sin_next * sin_next));
    const double turn_tol = std::max(1e-12, 1e-2 * options_.sagitta_pixels * spread * n * sin_h);
    // A last step that small -- n, and the slope at both ends, change the exit by less than that
    // -- and at most kLinearStep long, where no layer the air models hides between its ends, is
    // taken by the trapezoid rule over its ends instead of a panel: its run and length are off by
    // far less than their tolerances.
    const bool last = std::abs(step) <= kLinearStep && std::abs(n_next - n) * cos_h < turn_tol &&
                      std::abs(step * dn) * cos_h < turn_tol && std::abs(step * dn_next) * cos_next < turn_tol;
    double step_run = 0.5 * std::abs(step) * (cos_h / sin_h + cos_next / sin_next);
    double step_length = 0.5 * std::abs(step) * (1.0 / sin_h + 1.0 / sin_next);
    if (!last && !branch.integrate(h, h_next, kMinSine, &step_run, &step_length)) return std::nullopt;
    const double sign = step < 0.0 ? -1.0 : 1.0;  // integrate's panels are unsigned
    run += sign * step_run, length += sign * step_length;
    h = h_next, n = n_next, dn = dn_next, sin_h = sin_next;
    if (last || std::abs(step * dn) * cos_next < turn_tol) break;
  }
  const double cos_end = std::sqrt(std::max(0.0, 1.0 - sin_h * sin_h));
  const double scale = cos_e > 0.0 ? cos_end / cos_e : 0.0;
  return Escape{Vec3d(t.x() * scale, sin_h, t.z() * scale).normalized(),
                Vec3d(x.x() + run * across.x(), h, x.z() + run * across.z()), length};
}

std::optional<PlaneState> Caster::plane_escape(const RayNode<double>& node, double remaining, double spread) const {
  const auto exit = escape_direction(node.x, node.v, remaining, spread);
  if (!exit) return std::nullopt;
  return PlaneState{exit->point.x(), exit->point.y(), node.s + exit->length, exit->direction.x(), exit->direction.y(),
                    TraceStop::kVisitor};
}

std::optional<PathEnd> Caster::cast_monotone(const Vec3d& origin, const Vec3d& dir, double max_length,
                                             double spread, bool secondary, double s0) const {
  // sin e >= 0.01 (0.57 deg) at every height among the objects: the ray cannot turn there, and
  // the stretches' error estimate splits them where 1/sin e varies too fast for 8 points.
  constexpr double kMinSine = 0.01;
  if (!floors_ || !layered_ || dir.y() == 0.0) return std::nullopt;
  const Vec3d t = dir.normalized();
  const double cos_e0 = std::sqrt(t.x() * t.x() + t.z() * t.z());
  double n0, dn0;
  layered_->evaluate_height(origin.y(), &n0, &dn0);
  const double beta = n0 * cos_e0;
  // The least n the ray can meet among the objects: above its start when it rises, below when it falls.
  if (!(beta < floors_->objects_from(origin.y(), t.y() > 0.0) * std::sqrt(1.0 - kMinSine * kMinSine))) {
    return std::nullopt;
  }
  const BouguerBranch branch(*layered_, beta);
  const double up = t.y() > 0.0 ? 1.0 : -1.0;
  // Rising: up to the highest object, then out of the air; falling: down to the stop height.
  const double target = up > 0.0 ? ceiling_ : std::min(scene_.lowest(), origin.y()) - 1.0;
  const Vec3d across = cos_e0 > 0.0 ? Vec3d(t.x() / cos_e0, 0.0, t.z() / cos_e0) : Vec3d(1.0, 0.0, 0.0);
  auto point = [&](double run, double h) { return Vec3d(origin.x() + run * across.x(), h, origin.z() + run * across.z()); };
  auto direction = [&](double sin_e) {
    return (std::sqrt(std::max(0.0, 1.0 - sin_e * sin_e)) * across + Vec3d(0.0, up * sin_e, 0.0)).normalized();
  };
  // Stretches of height as long as one straight chord stays within the sagitta of the path
  // (its bend and the quadrature's error bounded, BouguerBranch::Stretch): one stretch for a
  // steep ray through a thin hot layer, more where the ray bends. A ray that stands for a pixel
  // (spread) may stray sagitta_pixels of its footprint at the chord's start, as traced paths do.
  const double per_metre = options_.sagitta_pixels * spread;
  PathEnd end;
  end.direction = t;
  double h = origin.y(), s = 0.0, run = 0.0, sin_e = std::abs(t.y()), n = n0, dn = dn0;
  // A rising ray with nothing over the ground it crosses up to the objects' top as high as where it
  // starts (the sea away from the ships and the coast) meets nothing there: no chords, only its run
  // and length up to that top, to what its escape needs (climb_clear). Up to the top its run is at
  // most its climb times the cotangent of its flattest elevation, where n is least (cos e = beta / n).
  const HeightCover* cover = regions_.empty() ? floors_->cover.get() : nullptr;
  if (up > 0.0 && cover && floors_->gradients && origin.y() < ceiling_) {
    const double flattest = beta / floors_->objects_from(origin.y(), true);
    const double run_up = (ceiling_ - origin.y()) * flattest / std::sqrt(1.0 - flattest * flattest);
    const Vec3d far = origin + run_up * across;
    // The escape turns its exit by run / R; the climb may add a tenth of the escape's own tolerance
    // on that (whose quadrature's estimated error lies far below it in practice).
    const double run_tol = 0.1 * options_.sagitta_pixels * spread * layered_->earth_radius();
    Climb climb;
    double n_top, dn_top, sin_top;
    if (cover->highest(origin.x(), origin.z(), far.x(), far.z()) < origin.y() &&
        climb_clear(branch, origin.y(), ceiling_, run_tol, &climb) && climb.length <= max_length &&
        branch.at(ceiling_, kMinSine, &n_top, &dn_top, &sin_top)) {
      h = ceiling_, s = climb.length, run = climb.run, n = n_top, dn = dn_top, sin_e = sin_top;
      end.direction = direction(sin_e);
      end.length = s;
      // Past the air that bends it, the rest is one line, as after the chords below.
      if (secondary && straight_rest(point(run, h), end.direction, s, max_length - s,
                                     std::min(scene_.lowest(), origin.y()) - 1.0, spread, &end, s0)) {
        return end;
      }
    }
  }
  double step = up * (target - h);
  Vec3d a = point(run, h);
  while (up * (target - h) > 0.0) {
    step = std::min(step, up * (target - h));
    double sin_b;
    BouguerBranch::Stretch stretch;
    if (!branch.at(h + up * step, kMinSine, &n, &dn, &sin_b)) return std::nullopt;
    if (!branch.integrate(h, sin_e, h + up * step, sin_b, kMinSine, &stretch)) return std::nullopt;
    const double chord = std::sqrt(stretch.run * stretch.run + step * step);
    const double tolerance = std::max(options_.sagitta, per_metre * (s0 + s));
    const bool straight = stretch.error <= 0.1 * tolerance && 0.25 * chord * stretch.turning <= tolerance &&
                          chord <= options_.chord;
    if (!straight && step > 1e-6) {
      step *= 0.25;
      continue;
    }
    if (s + stretch.length > max_length) return std::nullopt;  // ends before leaving the objects' heights: trace it
    const Vec3d b = point(run + stretch.run, h + up * step);
    const Vec3d d = b - a;
    const double len = d.norm();
    if (len > 0.0 && chord_blocked(a, d / len, len, Handoff{a, end.direction, s}, &end)) {
      if (end.handoff) return end;
      // On the chord, within the sagitta of the path; the direction there from the invariant.
      const auto hit = end.hit;
      double n_hit, dn_hit, sin_hit;
      end.direction = branch.at(hit->point.y(), 0.0, &n_hit, &dn_hit, &sin_hit) ? direction(sin_hit) : d / len;
      end.length = s + stretch.length * std::min(hit->t / len, 1.0);
      return end;
    }
    h += up * step, s += stretch.length, run += stretch.run, sin_e = sin_b;
    end.direction = direction(sin_e);
    end.length = s;
    a = b;
    step *= 4.0;
    // Past the air that bends it (a hot road's few metres): the rest is one line.
    if (secondary &&
        straight_rest(a, end.direction, s, max_length - s, std::min(scene_.lowest(), origin.y()) - 1.0, spread, &end,
                      s0)) {
      return end;
    }
  }
  end.end_point = a;
  if (up < 0.0) return end;  // below everything: the path ends there, as a traced one at its stop height
  const auto exit =
      escape_direction(a + Vec3d(0.0, 1e-9 * (1.0 + std::abs(a.y())), 0.0), n * end.direction, max_length - s, spread);
  if (!exit) return std::nullopt;
  end.direction = exit->direction;
  end.end_point = exit->point;
  return end;
}

bool Caster::climb_clear(const BouguerBranch& branch, double h0, double h1, double tol, Climb* out) const {
  // Samples more than this, or gaps halved more often: the ray is left to the chords.
  constexpr int kMostSamples = 256, kMostDepth = 40;
  if (!(tol > 0.0) || !(h1 > h0) || !floors_ || !floors_->gradients) return false;
  const IorFloors::Gradients& bound = *floors_->gradients;
  const double beta = branch.beta();
  struct Sample {
    double h, n, rate_run, rate_length, below, above;
    int depth;
  };
  auto sample = [&](double h, int depth, Sample* at) {
    double dn, sin_e;
    at->h = h, at->depth = depth;
    if (!branch.at(h, 0.0, &at->n, &dn, &sin_e) || !(sin_e > 0.0)) return false;
    at->rate_run = beta / at->n / sin_e, at->rate_length = 1.0 / sin_e;  // cot e, 1 / sin e
    return bound.climbed_around(h, &at->below, &at->above);
  };
  // The trapezoid rule over gaps between samples, each gap halved until it is kept: between its
  // ends ln n varies by at most the bound's integral, so n stays above the lower end's n times
  // (1 - that) and cos e below beta over it, and there cot e and 1 / sin e change with ln n at most
  // at cos e / sin^3 e: the rule errs over the gap by at most its width times their whole change,
  // kept within the gap's share of tol.
  std::array<Sample, kMostDepth + 2> right;  // the ends of the gaps still to do, the nearest last
  Sample left;
  int pending = 0, samples = 2;
  if (!sample(h0, 0, &left) || !sample(h1, 0, &right[0])) return false;
  pending = 1;
  out->run = out->length = 0.0;
  const double per_metre = tol / (h1 - h0);
  while (pending > 0) {
    const Sample& b = right[size_t(pending) - 1];
    const double variation = b.above - left.below;
    if (!(variation < 0.5)) return false;  // (ln n varies by ~1e-4 in the lowest kilometres)
    const double c = beta / (std::min(left.n, b.n) * (1.0 - variation));
    if (!(c < 1.0)) return false;  // the ray may turn between them
    const double sine = std::sqrt(1.0 - c * c);
    const double gap = b.h - left.h;
    if (variation * c / (sine * sine * sine) <= per_metre) {
      out->run += 0.5 * gap * (left.rate_run + b.rate_run);
      out->length += 0.5 * gap * (left.rate_length + b.rate_length);
      left = b;
      --pending;
      continue;
    }
    // Inside one interval of the bound's samples halving cannot lower its variation: chords then.
    if (left.below == b.below && left.above == b.above) return false;
    const int depth = std::max(left.depth, b.depth) + 1;
    if (depth > kMostDepth || ++samples > kMostSamples) return false;
    if (!sample(0.5 * (left.h + b.h), depth, &right[size_t(pending)])) return false;
    ++pending;
  }
  return true;
}

PathEnd Caster::cast_traced(const Vec3d& origin, const Vec3d& dir, double max_length, double spread,
                            bool secondary, double s0) const {
  PathEnd end;
  end.direction = dir;
  // A rising ray above every object that cannot turn never comes back: the invariant gives the
  // direction it leaves along, without tracing.
  end.end_point = origin;
  if (const auto exit = escape_direction(origin, dir, max_length, spread)) {
    end.direction = exit->direction;
    end.end_point = exit->point;
    return end;
  }
  const IndexField& air = legs_ ? *layered_ : *field_;  // legs outside the regions: the layered part
  TraceOptions trace_options = curved_trace_options(scene_, air, origin, options_, max_length);
  // Air that cannot bend the rest of the path off a straight line by its tolerance: one line.
  if (secondary && straight_rest(origin, dir, 0.0, max_length, *trace_options.stop_height, spread, &end, s0)) {
    return end;
  }
  // A ray too steep to turn anywhere: its chords straight from the invariant, no integration.
  if (auto monotone = cast_monotone(origin, dir, max_length, spread, secondary, s0)) return *monotone;
  // Through local features rk45 steps at most half their scale (its error estimate cannot step over one).
  if (!legs_ && !regions_.empty()) trace_options.step = step_in_regions();
  // A pixel's ray: an error of sagitta_pixels of its footprint (spread * s) is invisible. Any
  // ray: the chords already stray up to the sagitta from the path, so the integrator need not
  // be closer to it than that.
  const double per_metre = options_.sagitta_pixels * spread;
  trace_options.tol = std::max({trace_options.tol, per_metre * (s0 + max_length), options_.sagitta});
  // That tol is the stray allowed at the path's end; between nodes (up to a chord apart) the
  // chords read the quintic, held to a quarter of the stray allowed where they are (1/16 of the
  // pixel's footprint by default; TraceOptions::between_nodes).
  trace_options.hold_between_nodes = true;
  trace_options.between_nodes = TraceOptions::GrowingTolerance{0.25 * options_.sagitta, 0.25 * per_metre, s0};
  double last_height = origin.y();
  try {
    trace(air, origin, dir, trace_options, [&](const RayNode<double>& a, const RayNode<double>& b) {
      if (segment_blocked(a, b, &end, std::max(options_.sagitta, per_metre * (s0 + a.s)))) return false;
      end.direction = b.v.normalized();
      end.length = b.s;
      end.end_point = b.x;
      last_height = b.x.y();
      if (const auto exit = escape_direction(b.x, b.v, max_length - b.s, spread)) {
        end.direction = exit->direction;
        end.end_point = exit->point;
        return false;
      }
      // Risen (or run) out of the air that bends it: the rest is one line.
      return !(secondary &&
               straight_rest(b.x, b.v, b.s, max_length - b.s, *trace_options.stop_height, spread, &end, s0));
    });
  } catch (const NumericalError&) {
    // A path rising above every object out of the field's modelled heights has left the air:
    // it sees the sky along its last direction. Anywhere else the error stands.
    if (end.hit || end.handoff || !(end.direction.y() > 0.0) || !(last_height > ceiling_)) throw;
  }
  return end;
}

std::optional<Vec3d> Caster::meets_plane(const Vec3d& origin, const Vec3d& dir, const Vec3d& point, const Vec3d& normal,
                                         double s_near) const {
  const double s_lo = 0.5 * s_near, s_hi = 1.5 * s_near + 1.0;
  const double offset = normal.dot(point);
  std::optional<Vec3d> best;
  double best_gap = std::numeric_limits<double>::infinity();
  auto consider = [&](const RayNode<double>& a, const RayNode<double>& b) {
    if (b.s < s_lo || a.s > s_hi) return;
    // Every segment: the roots of its quintic find a dip through the plane and out again, which
    // a test of the ends' sides skipped (first_plane_crossing rejects the others cheaply).
    const PathSegment<double> segment(a, b);
    const double u = first_plane_crossing(segment, normal, offset);
    if (!(u >= 0.0)) return;
    const double s = a.s + u * (b.s - a.s);
    if (std::abs(s - s_near) < best_gap) best_gap = std::abs(s - s_near), best = segment.position(u);
  };
  if (!field_) {
    const double along = normal.dot(dir);
    if (along == 0.0) return std::nullopt;
    const double t = (offset - normal.dot(origin)) / along;
    if (!(t >= s_lo && t <= s_hi)) return std::nullopt;
    return Vec3d(origin + t * dir);
  }
  if (table_ && origin == eye_ && !legs_) {
    // The neighbours' meeting points a tenth as far from their paths as a camera ray may stray
    // (they are half a pixel apart: the footprint within ~10 %).
    const TurnedTablePath path(*table_, eye_, dir, 0.1 * exact_tol_);
    // The crossing nearest s_near: from the segment holding s_near (found by bisection on the
    // nodes' arc lengths, which grow with k) outward both ways, each way until its segments lie
    // farther from s_near than the best crossing found (walking every node from the eye cost
    // the cold sea's sea pixels some hundred nodes per neighbour).
    const size_t count = path.plane.size();
    if (count < 2) return best;
    size_t lo = 1, hi = count - 1;  // the least j >= 1 with s_j >= s_near, else the last node
    while (lo < hi) {
      const size_t mid = lo + (hi - lo) / 2;
      if (path.node(mid).s < s_near) {
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    const RayNode<double> at_split = path.node(lo - 1);
    RayNode<double> a = at_split;
    for (size_t k = lo - 1; k + 1 < count && a.s <= s_hi && a.s - s_near < best_gap; ++k) {
      const RayNode<double> b = path.node(k + 1);
      consider(a, b);
      a = b;
    }
    RayNode<double> b = at_split;
    for (size_t k = lo - 1; k > 0 && b.s >= s_lo && s_near - b.s < best_gap; --k) {
      const RayNode<double> before = path.node(k - 1);
      consider(before, b);
      b = before;
    }
    return best;
  }
  TraceOptions trace_options = curved_trace_options(scene_, *field_, origin, options_, s_hi);
  if (!regions_.empty()) trace_options.step = step_in_regions();
  trace(*field_, origin, dir, trace_options, [&](const RayNode<double>& a, const RayNode<double>& b) {
    consider(a, b);
    return a.s <= s_hi;
  });
  return best;
}

std::optional<std::array<Vec3d, 2>> Caster::footprint(const Vec3d& origin, const PathEnd& end,
                                                      const std::array<std::array<Vec3d, 2>, 2>& neighbours) const {
  if (!end.hit) return std::nullopt;
  std::array<Vec3d, 2> axes;
  for (int k = 0; k < 2; ++k) {
    const auto p0 = meets_plane(origin, neighbours[k][0], end.hit->point, end.hit->normal, end.length);
    const auto p1 = meets_plane(origin, neighbours[k][1], end.hit->point, end.hit->normal, end.length);
    if (!p0 || !p1) return std::nullopt;
    axes[k] = *p1 - *p0;
  }
  return axes;
}

// The table's path for the ray's elevation, turned to its azimuth about the eye, walked along
// its entry's chord plan (or segment by segment where it is traced exactly).
PathEnd Caster::cast_table(const Vec3d& dir) const {
  PathEnd end;
  end.direction = dir;
  const TurnedTablePath path(*table_, eye_, dir, exact_tol_);
  const ElevationTable::LazyPath& plane = path.plane;
  const size_t entry = plane.template_entry();
  // Nothing left to hit once the rest of the path stays above everything at its azimuth.
  const double ceiling = std::min(ceiling_, azimuth_ceiling_.at(dir));
  if (entry == ElevationTable::LazyPath::kExact) {
    RayNode<double> a = path.node(0);
    for (size_t k = 0; k + 1 < plane.size(); ++k) {
      if (plane.lowest_from(k) > ceiling) break;
      const RayNode<double> b = path.node(k + 1);
      if (segment_blocked(a, b, &end)) return end;
      end.direction = b.v.normalized();
      end.length = b.s;
      a = b;
    }
  } else {
    // Chords between nodes' places; the nodes themselves (the field evaluated there) only where a
    // segment of the path is needed: a chord in pieces, a hit to refine.
    TurnedTablePath::Point a = path.point(0);
    for (const PlannedChord& chord : plans_[entry]) {
      if (plane.lowest_from(chord.first) > ceiling) break;
      const TurnedTablePath::Point b = path.point(chord.last);
      if (chord.pieces > 1) {
        const PathSegment<double> segment(path.node(chord.first), path.node(chord.last));
        if (pieces_blocked(segment, int(chord.pieces), &end)) return end;
      } else if (const Vec3d d = b.x - a.x; d.norm() > 0.0) {
        const double len = d.norm();
        if (chord_blocked(a.x, d / len, len, Handoff{a.x, a.direction, a.s}, &end)) {
          if (end.handoff) return end;
          // Refine on the segment of the path that crosses the hit's tangent plane: the first
          // whose nodes lie on both sides of it (the chord strays from the path, so the segment
          // under the chord's hit need not be that one), else the one under the chord's hit.
          // Returns that segment and the parameter on it.
          const RayNode<double> node_a = path.node(chord.first), node_b = path.node(chord.last);
          auto refine = [&](const Hit& hit, double s_hit) {
            auto side = [&](const RayNode<double>& node) { return hit.normal.dot(node.x - hit.point); };
            RayNode<double> from = node_a, to = chord.last == chord.first + 1 ? node_b : path.node(chord.first + 1);
            RayNode<double> under = from, under_to = to;
            bool crossing = false;
            for (size_t k = chord.first;; ++k) {
              if (from.s <= s_hit) under = from, under_to = to;
              if ((side(from) <= 0.0) != (side(to) <= 0.0)) {
                crossing = true;
                break;
              }
              if (k + 2 > chord.last) break;
              from = to;
              to = k + 2 == chord.last ? node_b : path.node(k + 2);
            }
            if (!crossing) from = under, to = under_to;
            const PathSegment<double> seg(from, to);
            const double u0 = seg.length() > 0.0 ? std::clamp((s_hit - from.s) / seg.length(), 0.0, 1.0) : 0.0;
            const double u = crossing ? refine_on_plane(seg, hit.normal, hit.point, u0, 0.0, 1.0)
                                      : refine_on_plane(seg, hit.normal, hit.point, u0, -0.5, 1.5);
            return std::make_pair(seg, u);
          };
          Hit hit = *end.hit;  // set: chord_blocked returned true without a handoff
          auto [seg, u] = refine(hit, a.s + (b.s - a.s) * std::min(hit.t / len, 1.0));
          for (int check = 0; check < kEarlierHitChecks; ++check) {
            const double s_end = seg.start() + u * seg.length();
            if (!(s_end > a.s)) break;
            const auto earlier = earlier_hit(a.x, seg.position(u), &end);
            if (!earlier) break;
            hit = earlier->hit;
            std::tie(seg, u) = refine(hit, a.s + (s_end - a.s) * earlier->fraction);
          }
          end_at(seg, u, hit, &end);
          return end;
        }
      }
      end.direction = b.direction;
      end.length = b.s;
      a = b;
    }
  }
  // The sky is seen along the path's last direction, or where it escapes (ElevationTableOptions::escape).
  if (const auto escape = plane.escape()) {
    end.direction = Vec3d(escape->cos_e * path.cx, escape->sin_e, escape->cos_e * path.cz);
    end.end_point = Vec3d(eye_.x() + escape->r * path.cx, escape->h, eye_.z() + escape->r * path.cz);
  } else if (plane.size() > 1) {
    const RayNode<double> last = path.node(plane.size() - 1);
    end.direction = last.v.normalized();
    end.end_point = last.x;
  }
  return end;
}

}  // namespace refracta
