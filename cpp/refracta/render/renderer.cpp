// The straight and curved renderers and Blinn-Phong shading with sun shadows.
#include "refracta/render/renderer.h"

#include "refracta/core/error.h"
#include "refracta/core/rng.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/trace.h"
#include "refracta/render/tile_loop.h"
#include "refracta/shading/blinn_phong.h"

#include <atomic>
#include <cmath>

namespace refracta {

RenderMethod parse_render_method(const std::string& name) {
  if (name == "straight") return RenderMethod::kStraight;
  if (name == "curved") return RenderMethod::kCurved;
  if (name == "raster_march") return RenderMethod::kRasterMarch;
  throw_invalid("method must be 'straight', 'curved' or 'raster_march' (got '", name, "')");
}

void RenderOptions::validate() const {
  if (spp < 1) throw_invalid("spp must be >= 1 (got ", spp, ")");
  if (!(max_length > 0.0) || !std::isfinite(max_length)) throw_invalid("max_length must be > 0 (got ", max_length, ")");
  if (!(chord > 0.0) || !std::isfinite(chord)) throw_invalid("chord must be > 0 (got ", chord, ")");
  if (!(sagitta > 0.0) || !std::isfinite(sagitta)) throw_invalid("sagitta must be > 0 (got ", sagitta, ")");
  if (!(tol > 0.0) || !std::isfinite(tol)) throw_invalid("tol must be > 0 (got ", tol, ")");
  if (tile < 1) throw_invalid("tile must be >= 1 (got ", tile, ")");
  if (integrator == TraceMethod::kRk4) throw_invalid("integrator must be 'rk45' or 'stratified' for rendering");
  if (march == TraceMethod::kStratified) throw_invalid("march must be 'rk4' or 'rk45'");
  if (!(step > 0.0) || !std::isfinite(step)) throw_invalid("step must be > 0 (got ", step, ")");
  if (max_steps < 1) throw_invalid("max_steps must be >= 1 (got ", max_steps, ")");
  if (!(guard_band >= 0.0 && guard_band <= 2.0)) throw_invalid("guard_band must be in [0, 2] (got ", guard_band, ")");
}

namespace {

constexpr double kFar = 1e7;  // [m] straight rays end here

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

namespace {

TraceOptions curved_trace_options(const Scene& scene, const IndexField& field, const Vec3d& origin,
                                  const RenderOptions& options) {
  TraceOptions trace_options;
  trace_options.method = options.integrator ? *options.integrator
                                            : (field.height_only() ? TraceMethod::kStratified : TraceMethod::kRk45);
  trace_options.tol = options.tol;
  trace_options.max_length = options.max_length;
  trace_options.step = options.chord;
  // Nothing can be hit below the lowest geometry: end the path 1 m under it (or under the eye).
  trace_options.stop_height = std::min(scene.lowest(), origin.y()) - 1.0;
  return trace_options;
}

}  // namespace

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

PathEnd follow_path(const Scene& scene, const IndexField* field, const Vec3d& origin, const Vec3d& dir,
                    const RenderOptions& options) {
  PathEnd end;
  end.direction = dir.normalized();
  if (!field || options.method == RenderMethod::kStraight) {
    end.hit = scene.intersect(origin, end.direction, kFar);
    end.chords = 1;
    if (end.hit) end.length = end.hit->t;
    return end;
  }
  const TraceOptions trace_options = curved_trace_options(scene, *field, origin, options);
  trace(*field, origin, end.direction, trace_options, [&](const RayNode<double>& a, const RayNode<double>& b) {
    if (hit_on_segment(scene, a, b, options, &end)) return false;
    end.direction = b.v.normalized();
    end.length = b.s;
    return true;
  });
  return end;
}

double sun_occlusion(const Scene& scene, const Hit& hit, const Vec3d& wi) {
  const Vec3d p = hit.point + hit.normal * (1e-5 + 2e-6 * hit.point.cwiseAbs().maxCoeff());
  return scene.occluded(p, wi, kFar) ? 1.0 : 0.0;
}

double spot_occlusion(const Scene& scene, const Hit& hit, const SpotLight& light) {
  const Vec3d p = hit.point + hit.normal * (1e-5 + 2e-6 * hit.point.cwiseAbs().maxCoeff());
  auto blocked = [&](const Vec3d& target) {
    const Vec3d to = target - p;
    const double d = to.norm();
    return d > 0.0 && scene.occluded(p, to / d, d * (1.0 - 1e-7)) ? 1.0 : 0.0;
  };
  if (light.radius <= 0.0) return blocked(light.position);
  // 8 x 8 stratified points of the disc (concentric by sqrt of the radial stratum).
  const Vec3d a = std::abs(light.direction.y()) < 0.9 ? Vec3d::UnitY() : Vec3d::UnitX();
  const Vec3d t1 = light.direction.cross(a).normalized(), t2 = light.direction.cross(t1);
  constexpr int kStrata = 8;
  double sum = 0.0;
  for (int i = 0; i < kStrata; ++i) {
    for (int j = 0; j < kStrata; ++j) {
      const double r = light.radius * std::sqrt((i + 0.5) / kStrata), phi = 2.0 * kPi * (j + 0.5 * (i % 2)) / kStrata;
      sum += blocked(light.position + r * (std::cos(phi) * t1 + std::sin(phi) * t2));
    }
  }
  return sum / (kStrata * kStrata);
}

Vec3d shade(const Scene& scene, const Lighting& lighting, const PathEnd& end, Rng& rng, bool jitter,
            double pixel_angle, const SunShadow* sun_shadow, const SpotShadow* spot_shadow) {
  // The pixel's cone: its width grows with the path length (refraction's own spreading of the
  // cone along a curved path is neglected).
  const double footprint = pixel_angle * end.length;
  if (!end.hit) return lighting.sky.radiance(end.direction, pixel_angle);
  const Hit& hit = *end.hit;
  Material material = scene.material(hit.geometry);
  material.kd = scene.albedo(hit, end.direction, footprint);
  const Vec3d wo = -end.direction;
  Vec3d radiance = material.kd.cwiseProduct(lighting.sky.mean_radiance());  // unoccluded sky, Lambert
  const Sun& sun = lighting.sun;
  if (sun.radiance.maxCoeff() > 0.0) {
    Vec3d wi = sun.direction;
    if (jitter) {  // a uniform point of the sun's disc: soft shadow edges converge with spp
      const double r = 0.5 * degrees_to_radians(sun.angular_diameter) * std::sqrt(rng.uniform());
      const double phi = 2.0 * kPi * rng.uniform();
      const Vec3d a = std::abs(wi.y()) < 0.9 ? Vec3d(0, 1, 0) : Vec3d(1, 0, 0);
      const Vec3d t1 = wi.cross(a).normalized(), t2 = wi.cross(t1);
      wi = (wi + r * std::cos(phi) * t1 + r * std::sin(phi) * t2).normalized();
    }
    const double cos_i = hit.normal.dot(wi);
    if (cos_i > 0.0) {
      const double shadow = !lighting.shadows ? 0.0 : sun_shadow ? (*sun_shadow)(hit, wi) : sun_occlusion(scene, hit, wi);
      radiance += blinn_phong(material, hit.normal, wo, wi).cwiseProduct(sun.irradiance()) * (cos_i * (1.0 - shadow));
    }
  }
  for (size_t k = 0; k < lighting.spots.size(); ++k) {
    const SpotLight& spot = lighting.spots[k];
    if (!spot.covers(hit.point)) continue;
    const Vec3d to_light = spot.position - hit.point;
    const double d2 = to_light.squaredNorm();
    const Vec3d wi = to_light / std::sqrt(d2);
    const double cos_i = hit.normal.dot(wi);
    if (cos_i <= 0.0) continue;
    const double shadow =
        !lighting.shadows ? 0.0 : spot_shadow ? (*spot_shadow)(hit, k) : spot_occlusion(scene, hit, spot);
    radiance += blinn_phong(material, hit.normal, wo, wi).cwiseProduct(spot.intensity) * (cos_i * (1.0 - shadow) / d2);
  }
  return radiance;
}

namespace {

// The elevations [rad] the camera's pixels look along, with a margin of two pixels.
std::pair<double, double> elevation_range(const Camera& camera) {
  double lo = kPi, hi = -kPi;
  const int steps = 64;
  for (int i = 0; i <= steps; ++i) {
    for (int j = 0; j <= steps; ++j) {
      const Vec3d d = camera.direction(camera.width() * double(i) / steps, camera.height() * double(j) / steps);
      const double e = std::asin(std::clamp(d.y(), -1.0, 1.0));
      lo = std::min(lo, e), hi = std::max(hi, e);
    }
  }
  const double margin = 2.0 * camera.pixel_angle() * std::max(1.0, double(camera.width()) / camera.height());
  return {std::max(lo - margin, -0.5 * kPi), std::min(hi + margin, 0.5 * kPi)};
}

// The path of a camera ray served by the table: the table's path for its elevation, turned to
// its azimuth about the eye.
PathEnd follow_table_path(const Scene& scene, const ElevationTable& table, const Vec3d& eye, const Vec3d& dir,
                          const RenderOptions& options) {
  PathEnd end;
  end.direction = dir;
  const double e = std::asin(std::clamp(dir.y(), -1.0, 1.0));
  const double horizontal = std::hypot(dir.x(), dir.z());
  const double cx = horizontal > 0 ? dir.x() / horizontal : 1.0, cz = horizontal > 0 ? dir.z() / horizontal : 0.0;
  const ElevationTable::LazyPath plane = table.lazy_path(e);
  auto turned = [&](const RayNode<double>& n) {
    RayNode<double> out = n;
    out.x = Vec3d(eye.x() + n.x.x() * cx, n.x.y(), eye.z() + n.x.x() * cz);
    out.v = Vec3d(n.v.x() * cx, n.v.y(), n.v.x() * cz);
    return out;
  };
  RayNode<double> a = turned(plane.node(0));
  for (size_t k = 0; k + 1 < plane.size(); ++k) {
    // Nothing left to hit once the rest of the path stays above every object.
    if (plane.lowest_from(k) > scene.highest()) break;
    const RayNode<double> b = turned(plane.node(k + 1));
    if (hit_on_segment(scene, a, b, options, &end)) return end;
    end.direction = b.v.normalized();
    end.length = b.s;
    a = b;
  }
  // The sky is seen along the path's last direction.
  if (plane.size() > 1) end.direction = turned(plane.node(plane.size() - 1)).v.normalized();
  return end;
}

}  // namespace

Image render(const Scene& scene, const Lighting& lighting, const Camera& camera, const FieldPtr& field,
             const RenderOptions& options, WorkControl& control, RenderStats* stats) {
  options.validate();
  scene.commit();
  if (options.method == RenderMethod::kRasterMarch) {
    return render_raster_march(scene, lighting, camera, field, options, control, stats);
  }
  std::atomic<int64_t> chords{0};
  std::unique_ptr<ElevationTable> table;
  if (field && field->height_only() && options.method == RenderMethod::kCurved && options.use_table &&
      (!options.integrator || *options.integrator == TraceMethod::kStratified)) {
    ElevationTableOptions table_options;
    table_options.eye_height = camera.position().y();
    std::tie(table_options.min_elevation, table_options.max_elevation) = elevation_range(camera);
    table_options.tol = options.tol;
    // A quarter of a pixel's angle per metre of path: errors well below what a pixel resolves.
    table_options.angular_tol = 0.25 * camera.pixel_angle();
    // More exact traces than a quarter of the pixels would not pay: trace the rest per pixel.
    table_options.max_rays = std::max<int64_t>(int64_t(camera.width()) * camera.height() / 4, 2 * table_options.initial_rays);
    table_options.trace = curved_trace_options(scene, *field, camera.position(), options);
    table = std::make_unique<ElevationTable>(field, table_options, control);
    control.done = 0;
  }
  const int strata = int(std::ceil(std::sqrt(double(options.spp))));
  // Each sample's cone covers its share of the pixel.
  const double pixel_angle = camera.pixel_angle() / strata;
  Image image = render_tiles(camera.width(), camera.height(), options.tile, control, [&](int x, int y) {
    Rng rng(options.seed, uint64_t(y) * uint64_t(camera.width()) + uint64_t(x));
    Vec3d sum = Vec3d::Zero();
    for (int s = 0; s < options.spp; ++s) {
      double du = 0.5, dv = 0.5;
      if (options.spp > 1) {  // stratified jitter over a strata x strata grid
        du = ((s % strata) + rng.uniform()) / strata;
        dv = (((s / strata) % strata) + rng.uniform()) / strata;
      }
      const Vec3d dir = camera.direction(x + du, y + dv);
      const PathEnd end = table ? follow_table_path(scene, *table, camera.position(), dir, options)
                                : follow_path(scene, field.get(), camera.position(), dir, options);
      sum += shade(scene, lighting, end, rng, options.spp > 1, options.texture_filter ? pixel_angle : 0.0);
      chords.fetch_add(end.chords, std::memory_order_relaxed);
    }
    return Vec3d(sum / options.spp);
  });
  if (stats) {
    stats->samples = int64_t(camera.width()) * camera.height() * options.spp;
    stats->chords = chords.load();
  }
  return image;
}

}  // namespace refracta
