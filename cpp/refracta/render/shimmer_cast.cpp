// Camera rays through a turbulent layer as deviations from the calm rays (shimmer_cast.h).
#include "refracta/render/shimmer_cast.h"

#include "refracta/core/error.h"
#include "refracta/media/turbulence_path.h"
#include "refracta/rays/trace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace refracta {

TurbulenceTrace parse_turbulence_trace(const std::string& name) {
  if (name == "strict") return TurbulenceTrace::kStrict;
  if (name == "perturbed") return TurbulenceTrace::kPerturbed;
  if (name == "auto") return TurbulenceTrace::kAuto;
  throw_invalid("turbulence_trace must be 'auto', 'strict' or 'perturbed' (got '", name, "')");
}

const char* turbulence_trace_name(TurbulenceTrace method) {
  switch (method) {
    case TurbulenceTrace::kStrict: return "strict";
    case TurbulenceTrace::kPerturbed: return "perturbed";
    case TurbulenceTrace::kAuto: return "auto";
  }
  return "auto";
}

namespace {

// The eye's table path for a direction's elevation, turned about the vertical through the eye to
// its azimuth (the caster's own walk does the same: a height-only field's paths differ by that turn).
struct EyePath {
  EyePath(const ElevationTable& table, const Vec3d& eye, const Vec3d& dir)
      : plane(table.lazy_path(std::asin(std::clamp(dir.y(), -1.0, 1.0)))), eye(eye) {
    const double horizontal = std::hypot(dir.x(), dir.z());
    cx = horizontal > 0 ? dir.x() / horizontal : 1.0;
    cz = horizontal > 0 ? dir.z() / horizontal : 0.0;
  }
  RayNode<double> node(size_t k) const {
    RayNode<double> out = plane.node(k);
    const double r = out.x.x(), vr = out.v.x(), gr = out.grad.x();
    out.x = Vec3d(eye.x() + r * cx, out.x.y(), eye.z() + r * cz);
    out.v = Vec3d(vr * cx, out.v.y(), vr * cz);
    out.grad = Vec3d(gr * cx, out.grad.y(), gr * cz);
    return out;
  }

  const ElevationTable::LazyPath plane;
  const Vec3d eye;
  double cx = 1.0, cz = 0.0;
};

}  // namespace

// The calm path of one camera ray traced exactly (stratified, to options' tol), in 3-D.
CalmPath::CalmPath(const IndexField& calm, const TraceOptions& options, const Vec3d& eye, const Vec3d& dir,
                   double length) {
  TraceOptions trace = options;
  trace.max_length = length;
  nodes_ = trace_path(calm, eye, dir, trace).nodes();
  lowest_.resize(nodes_.size());
  double low = std::numeric_limits<double>::infinity();
  for (size_t k = nodes_.size(); k-- > 0;) {
    low = std::min(low, nodes_[k].x.y());
    lowest_[k] = low;
  }
}

namespace {

// A point of the turbulent path: position, unit tangent, arc length.
struct PathPoint {
  Vec3d x, t;
  double s;
};

// Where the cubic Hermite path between p and q crosses the plane through `on` with `normal`, as a
// fraction of the way (bisection: the ends lie on either side).
double plane_crossing(const PathPoint& p, const PathPoint& q, const Vec3d& normal, const Vec3d& on) {
  const double h = q.s - p.s;
  auto side = [&](double u) {
    const double u2 = u * u, u3 = u2 * u;
    const Vec3d x = (2 * u3 - 3 * u2 + 1) * p.x + (u3 - 2 * u2 + u) * h * p.t + (-2 * u3 + 3 * u2) * q.x +
                    (u3 - u2) * h * q.t;
    return normal.dot(x - on);
  };
  double lo = 0.0, hi = 1.0;
  const bool below = side(lo) <= 0.0;
  for (int it = 0; it < 40; ++it) {  // 2^-40 of a step: far below any tolerance
    const double mid = 0.5 * (lo + hi);
    ((side(mid) <= 0.0) == below ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

ShimmerCaster::ShimmerCaster(const Scene& scene, FieldPtr calm, FieldPtr layered,
                             std::shared_ptr<const Turbulence> turbulence, const ElevationTable* table,
                             const Vec3d& eye, double pixel_angle, const RenderOptions& options)
    : scene_(scene),
      calm_field_(std::move(calm)),
      layered_(std::move(layered)),
      spotted_(!calm_field_->height_only()),
      turbulence_(std::move(turbulence)),
      table_(table),
      eye_(eye),
      options_(options),
      calm_(scene, calm_field_.get(), options),
      top_(turbulence_->region().top),
      step_(options.turbulence_step * turbulence_->grid->spacing()),
      // The calm air tabulated from the ground to a little above the layer (a deviated ray's
      // heights); hot spots' air is evaluated where the ray is, and needs no table.
      stepper_(*turbulence_, *layered_, 0.0, spotted_ ? 0.0 : top_ + 0.05, spotted_ ? calm_field_.get() : nullptr) {
  // A step per cell through up to max_length of layer: past 1e8 steps (seconds a ray) the step is
  // too small for the path (turbulence_step 0.01 of 1 um cells overflowed an int step count).
  if (!(options.max_length / step_ <= 1e8)) {
    throw_invalid("turbulence_trace 'perturbed': steps of ", step_, " m (turbulence_step ", options.turbulence_step,
                  " x the turbulence's ", turbulence_->grid->spacing(), " m cells) over max_length ", options.max_length,
                  " m would be more than 1e8: raise turbulence_step or lower max_length");
  }
  if (spotted_) calm_.use_layered(layered_.get());
  calm_.use_table(table, eye, pixel_angle);
  calm_.set_secondary_spread(pixel_angle);  // as the renderer's caster (shadow and bounce rays' tolerance)
  stretch_steps_ = std::isfinite(turbulence_->depth);
  trace_options_ = table->options().trace;
  // The calm paths: stratified through layered air, rk45 through hot spots' (the strict trace's
  // integrator for them), both to the render's tol.
  trace_options_.trace = spotted_ ? TraceMethod::kRk45 : TraceMethod::kStratified;
  trace_options_.tol = options.tol;
}

namespace {

// Whether the render asks for the perturbed trace through turbulent air at all ('perturbed' or 'auto').
bool asks_perturbed(const IndexField* field, const RenderOptions& options) {
  return options.turbulence_trace != TurbulenceTrace::kStrict && field && field->turbulence();
}

// perturbed_trace_refusal's reasons that the field and options give, for a render that asks
// (ShimmerCaster::make has no camera; without the table it is null there all the same).
const char* air_refusal(const IndexField& field, const RenderOptions& options) {
  if (options.method != RenderMethod::kCurved) return "it follows curved rays (method 'curved')";
  if (options.spectral) return "it serves RGB renders (spectral renders trace each wavelength strictly)";
  const FieldPtr calm = field.with_turbulence(nullptr);
  if (!calm->height_only() && !calm->height_only_part()) {
    return "it needs calm air that depends on height only, or hot spots over such air (not a custom field)";
  }
  if (!options.use_table || (options.trace && *options.trace != TraceMethod::kStratified)) {
    return "it follows the eye table's calm paths (table=True, trace None or 'stratified')";
  }
  return nullptr;
}

}  // namespace

namespace {

// Why the perturbed trace cannot serve a render that asks for it ('perturbed' or 'auto'); empty: it can.
std::string refusal(const IndexField& field, const RenderOptions& options, const Camera& camera) {
  if (const char* why = air_refusal(field, options)) return why;
  if (camera.aperture_diameter() > 0.0) return "it follows rays from the eye (a pinhole camera, no aperture)";
  if (std::isfinite(field.earth_radius()) && options.max_length > kTableLongestPath) {
    return concat("over a spherical Earth it follows paths up to max_length = ", kTableLongestPath, " m (got ",
                  options.max_length, ")");
  }
  return "";
}

}  // namespace

std::string perturbed_trace_refusal(const IndexField* field, const RenderOptions& options, const Camera& camera) {
  if (options.turbulence_trace != TurbulenceTrace::kPerturbed || !asks_perturbed(field, options)) return "";
  return refusal(*field, options, camera);
}

bool perturbed_trace_serves(const IndexField* field, const RenderOptions& options, const Camera& camera) {
  return asks_perturbed(field, options) && refusal(*field, options, camera).empty();
}

std::unique_ptr<ShimmerCaster> ShimmerCaster::make(const Scene& scene, const IndexField& field, const FieldPtr& layered,
                                                   const ElevationTable* table, const Vec3d& eye, double pixel_angle,
                                                   const std::optional<IorFloors>& floors,
                                                   const RenderOptions& options) {
  if (!asks_perturbed(&field, options) || air_refusal(field, options) || !table || !layered ||
      !layered->height_only()) {
    return nullptr;
  }
  std::shared_ptr<const Turbulence> turbulence = field.turbulence();
  FieldPtr calm = field.with_turbulence(nullptr);
  if (calm->height_only()) calm = layered;  // (tabulated)
  auto caster = std::make_unique<ShimmerCaster>(scene, std::move(calm), layered, std::move(turbulence), table, eye,
                                                pixel_angle, options);
  if (floors) caster->calm_.set_ior_floors(*floors);
  return caster;
}

PathEnd ShimmerCaster::cast(const Caster& strict, const Vec3d& origin, const Vec3d& dir, double spread,
                            bool* perturbed) const {
  if (perturbed) *perturbed = false;
  if (origin != eye_) return strict.cast(origin, dir, 0.0, spread);
  if (spotted_) {  // hot spots bend the calm paths away from the table's: each traced whole
    CalmPath exact;
    try {
      exact = CalmPath(*calm_field_, trace_options_, eye_, dir, options_.max_length);
    } catch (const NumericalError&) {
      return strict.cast(origin, dir, 0.0, spread);
    }
    return walk(strict, exact, false, origin, dir, spread, perturbed);
  }
  const EyePath path(*table_, eye_, dir);
  const size_t count = path.plane.size();
  // The first segment of the calm path that may dip into the layer (its nodes, less the most a
  // path of that curvature bulges below its chord, at or under the layer's top).
  size_t first = count;
  auto dips = [&](const RayNode<double>& a, const RayNode<double>& b) {
    const double len = b.s - a.s;
    const double bulge = 0.125 * std::max(a.curvature().norm(), b.curvature().norm()) * len * len;
    return std::min(a.x.y(), b.x.y()) - bulge <= top_;
  };
  if (count >= 2) {
    RayNode<double> a = path.node(0);
    for (size_t k = 0; k + 1 < count && path.plane.lowest_from(k) <= top_; ++k) {
      const RayNode<double> b = path.node(k + 1);
      if (dips(a, b)) {
        first = k;
        break;
      }
      a = b;
    }
  }
  // Never in the layer: the calm path is the turbulent one.
  if (first == count) return calm_.cast(origin, dir, 0.0, spread);
  // The calm path itself traced exactly (to the render's tol) as far as the table's path leaves
  // the layer for good, and a metre on: the table's path is only as close to it as the pixel's
  // footprint allows (a quarter pixel per metre, 10 cm at 300 m for 48 pixels across the hot
  // road), while in the layer the calm air's n changes over centimetres and the turbulence's own
  // deviation is millimetres; following the table's path, the fast image differed from the
  // strict one mostly by that (bench_realism.py shimmer_fast).
  double through = options_.max_length;
  for (size_t k = first + 1; k < count; ++k) {
    if (path.plane.lowest_from(k) > top_) {
      through = std::min(through, path.plane.node(k).s + 1.0);
      break;
    }
  }
  CalmPath exact;
  try {
    exact = CalmPath(*layered_, trace_options_, eye_, dir, through);
  } catch (const NumericalError&) {
    return strict.cast(origin, dir, 0.0, spread);
  }
  return walk(strict, exact, through < options_.max_length, origin, dir, spread, perturbed);
}

double ShimmerCaster::envelope_stretch(const RayNode<double>& a, const RayNode<double>& b) const {
  if (!stretch_steps_) return 1.0;
  // The segment's lowest point: its ends less the most a path of that curvature bulges below them.
  const double len = b.s - a.s;
  const double bulge = 0.125 * std::max(a.curvature().norm(), b.curvature().norm()) * len * len;
  const double low = std::min(a.x.y(), b.x.y()) - bulge;
  const double envelope = std::exp(-std::max(low, 0.0) / turbulence_->depth);
  return std::clamp(std::exp2(std::floor(std::log2(kFullStepEnvelope / envelope))), 1.0, kLongestStepStretch);
}

PathEnd ShimmerCaster::walk(const Caster& strict, const CalmPath& path, bool truncated, const Vec3d& origin,
                            const Vec3d& dir, double spread, bool* perturbed) const {
  const size_t count = path.size();
  auto dips = [&](const RayNode<double>& a, const RayNode<double>& b) {
    const double len = b.s - a.s;
    const double bulge = 0.125 * std::max(a.curvature().norm(), b.curvature().norm()) * len * len;
    return std::min(a.x.y(), b.x.y()) - bulge <= top_;
  };
  size_t first = count;
  for (size_t k = 0; k + 1 < count; ++k) {
    if (dips(path.node(k), path.node(k + 1))) {
      first = k;
      break;
    }
  }
  if (first == count) return calm_.cast(origin, dir, 0.0, spread);
  // The ends of the perturbed walk (not the strict fallbacks) say so through `perturbed`.
  auto walked = [perturbed](PathEnd e) {
    if (perturbed) *perturbed = true;
    return e;
  };

  PathEnd end;
  end.direction = dir;
  // Chords along the turbulent path, each within the pixel's tolerance of it (Caster::cast's),
  // but within `sagitta` in the layer: there a grazing ray passes the road by millimetres, and the
  // strict trace's chords are its rk45 steps (at most half the layer's scale, 0.2 m, bent by the
  // tolerance of its error control); at the pixel's tolerance (11 cm at 300 m for 48 pixels across
  // the hot road) the chord over a mirage ray's vertex passed above the road where the path meets it.
  // In the layer a tenth of it: a mirage path's chords lie above the path (it curves up), and at
  // `sagitta` itself a vertex 0.3 mm into a road's 2 mm edge line passed over it unseen (an eye
  // 0.3 m up under a hot spot: 2 of 96 pixels saw sky where the strict trace meets the road).
  const double in_layer = std::max(kLayerSagittaFraction * options_.sagitta, RenderOptions::kSmallestSagitta);
  const double per_metre = options_.sagitta_pixels * spread;
  auto tolerance = [&](const PathPoint& from) {
    return from.x.y() < top_ ? in_layer : std::max(options_.sagitta, per_metre * from.s);
  };
  std::vector<PathPoint> run;  // the points since the current chord's start
  run.reserve(64);
  // Tests the chord from run[0] to run[last]; on a hit, ends the path where the turbulent path
  // crosses the hit's tangent plane (between the points of the run), and returns true.
  auto test = [&](size_t last) {
    const PathPoint& a = run.front();
    const Vec3d d = run[last].x - a.x;
    const double len = d.norm();
    if (!(len > 0.0)) return false;
    ++end.chords;
    const auto hit = scene_.intersect(a.x, d / len, len * (1.0 + 1e-6) + 1e-6);
    if (!hit) return false;
    Hit refined = *hit;
    auto side = [&](const PathPoint& p) { return hit->normal.dot(p.x - hit->point) <= 0.0; };
    const double f = std::min(hit->t / len, 1.0);
    end.direction = ((1.0 - f) * a.t + f * run[last].t).normalized();
    end.length = a.s + f * (run[last].s - a.s);
    for (size_t i = 0; i < last; ++i) {
      if (side(run[i]) != side(run[i + 1])) {
        const double u = plane_crossing(run[i], run[i + 1], hit->normal, hit->point);
        const PathPoint& p = run[i];
        const PathPoint& q = run[i + 1];
        const double h = q.s - p.s, u2 = u * u, u3 = u2 * u;
        refined.point = (2 * u3 - 3 * u2 + 1) * p.x + (u3 - 2 * u2 + u) * h * p.t + (-2 * u3 + 3 * u2) * q.x +
                        (u3 - u2) * h * q.t;
        end.direction = ((1.0 - u) * p.t + u * q.t).normalized();
        end.length = p.s + u * h;
        break;
      }
    }
    end.hit = refined;
    return true;
  };
  // Adds a point; tests the chords it closes (the longest run of points whose chord keeps within
  // the tolerance: a quarter of its length times its ends' turn, twice a circular arc's sagitta).
  auto add = [&](const PathPoint& p) {
    run.push_back(p);
    while (run.size() >= 2) {
      const PathPoint& a = run.front();
      const double len = (p.x - a.x).norm();
      if (0.25 * len * (p.t - a.t).norm() <= tolerance(a) && len <= options_.chord) return false;
      const size_t last = run.size() > 2 ? run.size() - 2 : 1;
      if (test(last)) return true;
      run.erase(run.begin(), run.begin() + std::ptrdiff_t(last));
      if (run.size() == 1) return false;
    }
    return false;
  };

  RayNode<double> a = path.node(0);
  run.push_back({a.x, a.v.normalized(), a.s});
  // Before the layer: the calm path's nodes.
  for (size_t k = 0; k < first; ++k) {
    const RayNode<double>& b = path.node(k + 1);
    if (add({b.x, b.v.normalized(), b.s})) return end;  // before the layer: not perturbed
    a = b;
  }
  RayDeviation deviation;
  PathPoint at = run.back();
  try {
    for (size_t k = first; k + 1 < count; ++k) {
      if (k > first && path.lowest_from(k) > top_) {
        // Above the layer for good: the calm air from the deviated state.
        if (run.size() >= 2 && test(run.size() - 1)) return walked(end);
        const double remaining = options_.max_length - at.s;
        if (!(remaining > 0.0)) break;
        PathEnd rest = calm_.cast(at.x, at.t, remaining, spread);
        rest.length += at.s;
        rest.chords += end.chords;
        return walked(rest);
      }
      const RayNode<double>& b = path.node(k + 1);
      const PathSegment<double> segment(a, b);
      const double len = b.s - a.s;
      // Through the layer a step per cell; between dips one step (the calm gradient's change at
      // the deviated height is negligible there, and constant forces Verlet integrates exactly).
      const int steps = dips(a, b) ? std::max(1, int(std::ceil(len / (step_ * envelope_stretch(a, b))))) : 1;
      CalmPoint from;
      from.x = a.x;
      from.t = a.v.normalized();
      for (int i = 0; i < steps; ++i) {
        const double um = (i + 0.5) / steps, u1 = double(i + 1) / steps;
        const CalmPoint mid = stepper_.calm_point(segment.position(um), segment.velocity(um).normalized());
        CalmPoint to;
        to.x = segment.position(u1);
        to.t = segment.velocity(u1).normalized();
        from.n = to.n = mid.n;
        stepper_.advance(from, mid, to, len / steps, &deviation);
        const Vec3d turned = deviation.tangent(to);
        // The small-perturbation criterion (shimmer_cast.h): otherwise the strict trace.
        if (!((turned - to.t).norm() <= kLargeDeviation) || !is_finite(deviation.dx)) {
          return strict.cast(origin, dir, 0.0, spread);
        }
        at = {to.x + deviation.dx, turned, a.s + u1 * len};
        if (add(at)) return walked(end);
        from = to;
      }
      a = b;
    }
  } catch (const NumericalError&) {
    // The deviated ray left the calm air's modelled heights: the strict trace says what it sees.
    return strict.cast(origin, dir, 0.0, spread);
  }
  if (run.size() >= 2 && test(run.size() - 1)) return walked(end);
  if (truncated) {  // the exact calm path stopped short: the calm air from the deviated state
    const double remaining = options_.max_length - at.s;
    if (remaining > 0.0) {
      PathEnd rest = calm_.cast(at.x, at.t, remaining, spread);
      rest.length += at.s;
      rest.chords += end.chords;
      return walked(rest);
    }
  }
  end.direction = layered_->sky_direction(at.x, at.t);
  end.end_point = at.x;
  end.length = at.s;
  return walked(end);
}

}  // namespace refracta
