// The curved caster (caster.h).
#include "refracta/render/caster.h"

#include "refracta/core/error.h"
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
                                  const RenderOptions& options, double max_length) {
  TraceOptions trace_options;
  trace_options.method = options.trace ? *options.trace
                                       : (field.height_only() ? TraceMethod::kStratified : TraceMethod::kRk45);
  trace_options.tol = options.tol;
  trace_options.max_length = max_length;
  trace_options.step = options.chord;
  // Nothing can be hit below the lowest geometry: end the path 1 m under it (or under the origin).
  trace_options.stop_height = std::min(scene.lowest(), origin.y()) - 1.0;
  return trace_options;
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
  double n_x, dn;
  field_->evaluate_height(x.y(), &n_x, &dn);
  const double beta = n_x * cos_e;  // Bouguer's invariant n(h) cos e
  // sin e at height h from the invariant; 0 where the ray would turn (or past the modelled air).
  auto sin_at = [&](double h) {
    double n;
    try {
      field_->evaluate_height(h, &n, &dn);
    } catch (const std::exception&) {
      return 0.0;
    }
    const double c = beta / n;
    return c < 1.0 ? std::sqrt(1.0 - c * c) : 0.0;
  };
  // Path length from x.y() up to h: integral of dh / sin e (8-point Gauss-Legendre; sin e is
  // smooth and bounded away from 0 on a path that does not turn).
  static constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  constexpr double kMinSine = 1e-2;  // below 0.57 deg the quadrature loses digits near a turn: trace instead
  auto length_to = [&](double h, bool* ok) {
    const double mid = 0.5 * (x.y() + h), half = 0.5 * (h - x.y());
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (double sign : {-1.0, 1.0}) {
        const double s = sin_at(mid + sign * half * kNodes[i]);
        if (s < kMinSine) *ok = false;
        sum += kWeights[i] / std::max(s, kMinSine);
      }
    }
    return half * sum;
  };
  // The height where the path has run `remaining` metres (Newton on s(h) = remaining, ds/dh = 1/sin e):
  // the sky is seen along the direction there, as at the end of a traced path.
  double h = x.y() + remaining * t.y();
  bool ok = sin_at(x.y()) >= kMinSine;
  for (int it = 0; it < 6 && ok; ++it) {
    const double s = sin_at(h);
    if (s < kMinSine) return std::nullopt;  // the ray may turn below that height: trace it
    const double step = (remaining - length_to(h, &ok)) * s;
    h += step;
    if (std::abs(step) < 1e-6 * (1.0 + std::abs(h))) break;
  }
  const double sin_end = sin_at(h);
  if (!ok || sin_end < kMinSine) return std::nullopt;
  const double cos_end = std::sqrt(std::max(0.0, 1.0 - sin_end * sin_end));
  const double scale = cos_e > 0.0 ? cos_end / cos_e : 0.0;
  return Vec3d(t.x() * scale, sin_end, t.z() * scale).normalized();
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
  const TraceOptions trace_options = curved_trace_options(scene_, *field_, origin, options_, max_length);
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
