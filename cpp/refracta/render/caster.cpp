// The curved caster (caster.h).
#include "refracta/render/caster.h"

#include "refracta/core/error.h"
#include "refracta/render/bouguer_branch.h"
#include "refracta/rays/trace.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

constexpr double kFar = 1e7;  // [m] straight rays end here (Embree's float range, see embree_scene.cpp)

// Point u in [lo, hi] of the segment on the plane through `on` with normal n (Newton).
double refine_on_plane(const PathSegment<double>& seg, const Vec3d& n, const Vec3d& on, double u, double lo,
                       double hi) {
  for (int it = 0; it < 8; ++it) {
    const double f = n.dot(seg.position(u) - on), df = n.dot(seg.velocity(u));
    if (df == 0.0) break;
    const double next = std::clamp(u - f / df, lo, hi);
    if (std::abs(next - u) < 1e-14) return next;
    u = next;
  }
  return u;
}

}  // namespace

TraceOptions curved_trace_options(const Scene& scene, const IndexField& field, const Vec3d& origin,
                                  const RenderOptions& options, double max_length, std::optional<double> ior_floor) {
  TraceOptions trace_options;
  trace_options.method = options.trace ? *options.trace
                                       : (field.height_only() ? TraceMethod::kStratified : TraceMethod::kRk45);
  trace_options.tol = options.tol;
  trace_options.max_length = max_length;
  trace_options.step = options.chord;
  // Nothing can be hit below the lowest geometry: end the path 1 m under it (or under the origin).
  trace_options.stop_height = std::min(scene.lowest(), origin.y()) - 1.0;
  trace_options.min_ior = ior_floor;
  return trace_options;
}

std::pair<double, double> render_heights(const Scene& scene, const Vec3d& eye, const RenderOptions& options) {
  return {std::min(scene.lowest(), eye.y()) - 1.0, std::max(scene.highest(), eye.y()) + options.max_length};
}

double render_ior_floor(const Scene& scene, const IndexField& field, const Vec3d& eye, const RenderOptions& options) {
  const auto [lo, hi] = render_heights(scene, eye, options);
  return lowest_ior_sampled(field, lo, hi);
}

bool hit_on_segment(const Scene& scene, const RayNode<double>& a, const RayNode<double>& b,
                    const RenderOptions& options, PathEnd* end) {
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
  const int by_sagitta = int(std::ceil(std::sqrt(deviation / options.sagitta)));
  const int chords = std::clamp(std::max(by_sagitta, int(std::ceil(seg.length() / options.chord))), 1, 1 << 20);
  for (int i = 0; i < chords; ++i) {
    const double u0 = double(i) / chords, u1 = double(i + 1) / chords;
    const Vec3d p0 = seg.position(u0), d = seg.position(u1) - p0;
    const double len = d.norm();
    if (len == 0.0) continue;
    // Each chord reaches slightly into the next so that no hit is lost at a joint.
    ++end->chords;
    const auto hit = scene.intersect(p0, d / len, len * (1.0 + 1e-6) + 1e-6);
    if (!hit) continue;
    const double du = u1 - u0;
    const double u = refine_on_plane(seg, hit->normal, hit->point, u0 + du * hit->t / len, u0 - 0.5 * du,
                                     std::min(u1 + 0.5 * du, 1.0));
    Hit refined = *hit;
    refined.point = seg.position(u);
    end->hit = refined;
    end->direction = seg.velocity(u).normalized();
    end->length = seg.start() + u * seg.length();
    return true;
  }
  return false;
}

Caster::Caster(const Scene& scene, const IndexField* field, const RenderOptions& options)
    : scene_(scene), field_(options.method == RenderMethod::kStraight ? nullptr : field), options_(options) {}

void Caster::use_table(const ElevationTable* table, const Vec3d& eye) {
  table_ = table;
  eye_ = eye;
}

double Caster::ior(const Vec3d& p) const {
  if (!field_) return 1.0;
  double n;
  Vec3d grad;
  field_->evaluate_checked(p, &n, &grad);
  return n;
}

PathEnd Caster::cast(const Vec3d& origin, const Vec3d& dir, double max_length) const {
  if (!field_) return cast_straight(origin, dir, max_length > 0.0 ? max_length : kFar);
  if (table_ && origin == eye_ && max_length <= 0.0) return cast_table(dir);
  return cast_traced(origin, dir, max_length > 0.0 ? max_length : options_.max_length);
}

bool Caster::occluded_straight(const Vec3d& origin, const Vec3d& dir, double distance) const {
  return distance > 0.0 && scene_.occluded(origin, dir, distance);
}

PathEnd Caster::cast_straight(const Vec3d& origin, const Vec3d& dir, double max_length) const {
  PathEnd end;
  end.direction = dir;
  end.hit = scene_.intersect(origin, dir, std::min(max_length, kFar));
  end.chords = 1;
  if (end.hit) end.length = end.hit->t;
  return end;
}

std::optional<Vec3d> Caster::escape_direction(const Vec3d& x, const Vec3d& v, double remaining) const {
  if (!field_->height_only() || !(x.y() > scene_.highest()) || !(v.y() > 0.0) || !(remaining > 0.0)) {
    return std::nullopt;
  }
  const Vec3d t = v.normalized();
  const double cos_e = std::hypot(t.x(), t.z());
  double n_x, dn, sin_x;
  field_->evaluate_height(x.y(), &n_x, &dn);
  const BouguerBranch branch(*field_, n_x * cos_e);
  // Below 0.57 deg of elevation the quadrature loses digits near a turn: trace instead.
  constexpr double kMinSine = 1e-2;
  if (!branch.at(x.y(), kMinSine, &n_x, &dn, &sin_x)) return std::nullopt;
  // The height where the path has run `remaining` metres (Newton on s(h) = remaining, ds/dh =
  // 1/sin e): the sky is seen along the direction there, as at the end of a traced path.
  double h = x.y() + remaining * t.y(), n, sin_h, run, length;
  for (int it = 0; it < 6; ++it) {
    if (!branch.at(h, kMinSine, &n, &dn, &sin_h)) return std::nullopt;  // the ray may turn below that height
    if (!branch.integrate(x.y(), h, kMinSine, &run, &length)) return std::nullopt;
    const double step = (remaining - length) * sin_h;
    h += step;
    if (std::abs(step) < 1e-6 * (1.0 + std::abs(h))) break;
  }
  if (!branch.at(h, kMinSine, &n, &dn, &sin_h)) return std::nullopt;
  const double cos_end = std::sqrt(std::max(0.0, 1.0 - sin_h * sin_h));
  const double scale = cos_e > 0.0 ? cos_end / cos_e : 0.0;
  return Vec3d(t.x() * scale, sin_h, t.z() * scale).normalized();
}

std::optional<PathEnd> Caster::cast_monotone(const Vec3d& origin, const Vec3d& dir, double max_length) const {
  // sin e >= 0.05 (2.9 deg) at every height the ray can reach: it cannot turn, and 1/sin e is smooth
  // enough for 8-point quadrature over metres of height.
  constexpr double kMinSine = 0.05;
  if (!ior_floor_ || !field_->height_only() || dir.y() == 0.0) return std::nullopt;
  const Vec3d t = dir.normalized();
  const double cos_e0 = std::hypot(t.x(), t.z());
  double n0, dn0;
  field_->evaluate_height(origin.y(), &n0, &dn0);
  const double beta = n0 * cos_e0;
  if (!(beta < *ior_floor_ * std::sqrt(1.0 - kMinSine * kMinSine))) return std::nullopt;
  const BouguerBranch branch(*field_, beta);
  const double up = t.y() > 0.0 ? 1.0 : -1.0;
  // Rising: up to the highest object, then out of the air; falling: down to the stop height.
  const double target = up > 0.0 ? scene_.highest() : std::min(scene_.lowest(), origin.y()) - 1.0;
  const Vec3d across = cos_e0 > 0.0 ? Vec3d(t.x() / cos_e0, 0.0, t.z() / cos_e0) : Vec3d(1.0, 0.0, 0.0);
  auto node_at = [&](double s, double run, double h, double n, double dn, double sin_e) {
    RayNode<double> node;
    node.s = s;
    node.x = Vec3d(origin.x() + run * across.x(), h, origin.z() + run * across.z());
    node.n = n;
    node.v = n * (std::sqrt(std::max(0.0, 1.0 - sin_e * sin_e)) * across + Vec3d(0.0, up * sin_e, 0.0));
    node.grad = Vec3d(0.0, dn, 0.0);
    return node;
  };
  // A chord of length L on a path of curvature k = |dn/dh| cos e / n strays k L^2 / 8 from it:
  // the height step that keeps that within the sagitta (the chord limit too).
  auto height_step = [&](double n, double dn, double sin_e) {
    const double curvature = std::abs(dn) * std::sqrt(std::max(0.0, 1.0 - sin_e * sin_e)) / n;
    const double by_sagitta = curvature > 0.0 ? std::sqrt(8.0 * options_.sagitta / curvature) : options_.chord;
    return sin_e * std::min(by_sagitta, options_.chord);
  };
  PathEnd end;
  end.direction = t;
  double h = origin.y(), s = 0.0, run = 0.0, n = n0, dn = dn0, sin_e = std::abs(t.y());
  RayNode<double> a = node_at(0.0, 0.0, h, n, dn, sin_e);
  a.v = n0 * t;
  while (up * (target - h) > 0.0) {
    double step = std::min(height_step(n, dn, sin_e), up * (target - h)), n_b, dn_b, sin_b, d_run, d_length;
    for (int shrink = 0;; ++shrink) {  // the curvature may grow along the step (falling into a hot layer)
      if (!branch.at(h + up * step, kMinSine, &n_b, &dn_b, &sin_b)) return std::nullopt;
      const double at_end = height_step(n_b, dn_b, sin_b);
      if (at_end >= step || shrink == 20) break;
      step = at_end;
    }
    if (!branch.integrate(h, h + up * step, kMinSine, &d_run, &d_length)) return std::nullopt;
    if (s + d_length > max_length) return std::nullopt;  // ends before leaving the objects' heights: trace it
    h += up * step, s += d_length, run += d_run, n = n_b, dn = dn_b, sin_e = sin_b;
    const RayNode<double> b = node_at(s, run, h, n, dn, sin_e);
    if (hit_on_segment(scene_, a, b, options_, &end)) return end;
    end.direction = b.v.normalized();
    end.length = s;
    a = b;
  }
  if (up < 0.0) return end;  // below everything: the path ends there, as a traced one at its stop height
  const auto exit = escape_direction(a.x + Vec3d(0.0, 1e-9 * (1.0 + std::abs(a.x.y())), 0.0), a.v, max_length - s);
  if (!exit) return std::nullopt;
  end.direction = *exit;
  return end;
}

PathEnd Caster::cast_traced(const Vec3d& origin, const Vec3d& dir, double max_length) const {
  PathEnd end;
  end.direction = dir;
  // A rising ray above every object that cannot turn never comes back: the invariant gives the
  // direction it leaves along, without tracing.
  if (const auto exit = escape_direction(origin, dir, max_length)) {
    end.direction = *exit;
    return end;
  }
  // A ray too steep to turn anywhere: its chords straight from the invariant, no integration.
  if (auto monotone = cast_monotone(origin, dir, max_length)) return *monotone;
  const TraceOptions trace_options = curved_trace_options(scene_, *field_, origin, options_, max_length, ior_floor_);
  double last_height = origin.y();
  try {
    trace(*field_, origin, dir, trace_options, [&](const RayNode<double>& a, const RayNode<double>& b) {
      if (hit_on_segment(scene_, a, b, options_, &end)) return false;
      end.direction = b.v.normalized();
      end.length = b.s;
      last_height = b.x.y();
      if (const auto exit = escape_direction(b.x, b.v, max_length - b.s)) {
        end.direction = *exit;
        return false;
      }
      return true;
    });
  } catch (const NumericalError&) {
    // A path rising above every object out of the field's modelled heights has left the air:
    // it sees the sky along its last direction. Anywhere else the error stands.
    if (end.hit || !(end.direction.y() > 0.0) || !(last_height > scene_.highest())) throw;
  }
  return end;
}

// The table's path for the ray's elevation, turned to its azimuth about the eye.
PathEnd Caster::cast_table(const Vec3d& dir) const {
  PathEnd end;
  end.direction = dir;
  const double e = std::asin(std::clamp(dir.y(), -1.0, 1.0));
  const double horizontal = std::hypot(dir.x(), dir.z());
  const double cx = horizontal > 0 ? dir.x() / horizontal : 1.0, cz = horizontal > 0 ? dir.z() / horizontal : 0.0;
  const ElevationTable::LazyPath plane = table_->lazy_path(e);
  auto turned = [&](const RayNode<double>& n) {
    RayNode<double> out = n;
    out.x = Vec3d(eye_.x() + n.x.x() * cx, n.x.y(), eye_.z() + n.x.x() * cz);
    out.v = Vec3d(n.v.x() * cx, n.v.y(), n.v.x() * cz);
    return out;
  };
  RayNode<double> a = turned(plane.node(0));
  for (size_t k = 0; k + 1 < plane.size(); ++k) {
    // Nothing left to hit once the rest of the path stays above every object.
    if (plane.lowest_from(k) > scene_.highest()) break;
    const RayNode<double> b = turned(plane.node(k + 1));
    if (hit_on_segment(scene_, a, b, options_, &end)) return end;
    end.direction = b.v.normalized();
    end.length = b.s;
    a = b;
  }
  // The sky is seen along the path's last direction.
  if (plane.size() > 1) end.direction = turned(plane.node(plane.size() - 1)).v.normalized();
  return end;
}

}  // namespace refracta
