// Astronomical refraction by tracing through the flattened spherical atmosphere (astronomical_refraction.h).
#include "refracta/rays/astronomical_refraction.h"

#include "refracta/core/error.h"
#include "refracta/media/curved_earth.h"
#include "refracta/rays/trace.h"

#include <cmath>
#include <optional>

namespace refracta {

void AstronomicalRefractionOptions::validate() const {
  Problems problems("astronomical_refraction");
  problems.check(std::isfinite(eye_height) && eye_height >= 0.0 && eye_height < kSceneReach, "eye_height must be >= 0 m and below ",
                 kSceneReach, " m (got ", eye_height, ")");
  // Air ends within 1 000 km; the trace's length grows with the top (4 x it): at most where scene
  // coordinates end.
  problems.check(!top || (std::isfinite(*top) && *top <= kSceneReach), "top must be at most ", kSceneReach,
                 " m and finite (got ", top.value_or(0.0), ")");
  problems.check(earth_radius > 0.0 && std::isfinite(earth_radius), "earth_radius must be finite and > 0 m (got ", earth_radius, ")");
  problems.check(tol > 0.0 && std::isfinite(tol), "tol must be > 0 m and finite (got ", tol, ")");
  problems.throw_if_any();
}

double astronomical_refraction(const FieldPtr& field, double apparent_elevation,
                               const AstronomicalRefractionOptions& options) {
  options.validate();
  if (!field) throw_invalid("astronomical_refraction: field must be a field (got None)");
  if (std::isfinite(field->earth_radius())) {
    throw_invalid("astronomical_refraction: give the air itself (true heights), not a CurvedEarth: the Earth's "
                  "curvature is applied here (earth_radius)");
  }
  if (!field->height_only()) throw_invalid("astronomical_refraction: the field must depend on height only (", field->type_name(), ")");
  if (!std::isfinite(apparent_elevation) || std::abs(apparent_elevation) > 0.5 * kPi) {
    throw_invalid("astronomical_refraction: apparent elevation must be in [-90, 90] deg (got ",
                  radians_to_degrees(apparent_elevation), " deg)");
  }
  double top = options.top ? *options.top : field->uniform_above();
  // An eye above the air (a spacecraft watching a star set through the limb): n is uniform from
  // the field's top up to the eye, so the ray may end as it climbs back to the eye's height.
  if (!options.top && std::isfinite(top) && top <= options.eye_height) top = options.eye_height + 1.0;
  if (!std::isfinite(top)) {
    throw_invalid("astronomical_refraction: ", field->type_name(), " is not uniform above any height; give top [m]");
  }
  if (!(top > options.eye_height)) {
    throw_invalid("astronomical_refraction: the top of the air (", top, " m) must lie above the eye (", options.eye_height, " m)");
  }
  if (apparent_elevation == 0.5 * kPi) return 0.0;  // straight up: no bending
  const CurvedEarth earth(field, options.earth_radius);
  const double y_eye = earth.flat_height(options.eye_height), y_top = earth.flat_height(top);

  TraceOptions trace_options;
  trace_options.trace = TraceMethod::kStratified;
  trace_options.tol = options.tol;
  // The longest way out: tangent to the ground to the top's sphere and a little more.
  const double r_top = options.earth_radius + top;
  trace_options.max_length = 2.0 * std::sqrt(r_top * r_top - options.earth_radius * options.earth_radius) + 4.0 * top;
  if (options.tol < kMinRelativeTol * trace_options.max_length) {  // named by what the caller gave, not the trace's options
    throw_invalid("astronomical_refraction: tol must be at least ", kMinRelativeTol * trace_options.max_length, " m for earth_radius ",
                  options.earth_radius, " m and top ", top, options.top ? " m" : " m (the default)", " (a path of up to ", trace_options.max_length,
                  " m out of the air; positions round off at 1e-15 of it): raise tol (got ", options.tol, ")");
  }
  // The ground, a micrometre down: a ray launched level from it must not stop at once.
  trace_options.stop_height = -1e-6;
  const Vec3d direction(std::cos(apparent_elevation), std::sin(apparent_elevation), 0.0);
  std::optional<Vec3d> exit_point, exit_direction;
  const TraceEnd<double> end = trace(earth, Vec3d(0.0, y_eye, 0.0), direction, trace_options,
                                     [&](const RayNode<double>& a, const RayNode<double>& b) {
                                       if (b.x.y() < y_top) return true;
                                       const PathSegment<double> segment(a, b);
                                       double lo = 0.0, hi = 1.0;  // a below the top, b at or above it
                                       for (int it = 0; it < 100 && hi - lo > 1e-16; ++it) {
                                         const double mid = 0.5 * (lo + hi);
                                         (segment.position(mid).y() < y_top ? lo : hi) = mid;
                                       }
                                       exit_point = segment.position(hi);
                                       exit_direction = segment.velocity(hi).normalized();
                                       return false;
                                     });
  if (!exit_point) {
    if (end.stop == TraceStop::kStopHeight) {
      throw_invalid("astronomical_refraction: the ray at apparent elevation ", radians_to_degrees(apparent_elevation),
                    " deg meets the ground before it leaves the air (raise eye_height or the elevation)");
    }
    throw_numerical("astronomical_refraction: the ray did not reach the top of the air (", top, " m) within ",
                    trace_options.max_length, " m of path (it is ducted)");
  }
  const double central_angle = exit_point->x() / options.earth_radius;
  const double elevation_at_top = std::asin(std::clamp(exit_direction->y(), -1.0, 1.0));
  // The starlight came from the vacuum beyond the top, where the field stays at n_top (a sounding
  // levels off there at n - 1 ~ 3e-5, 10 % of the ground's): entering the air at the top's radius
  // keeps n r cos e, so in vacuum cos e = n_top cos e_top (PhysicalAtmosphere's 86 km: n - 1 ~ 1e-8).
  double n_top, dn_top;
  field->evaluate_height(top, &n_top, &dn_top);
  const double cos_in_vacuum = n_top * std::cos(elevation_at_top);
  if (cos_in_vacuum > 1.0) {  // totally reflected where n drops to 1: no star is seen along it
    throw_numerical("astronomical_refraction: the ray reaches the top of the air (", top, " m) ",
                    radians_to_degrees(elevation_at_top), " deg above the horizon, too flat to leave it: where n drops from ",
                    n_top, " to 1 it is reflected back (n cos e = ", cos_in_vacuum,
                    " > 1); give a higher top, where n - 1 is smaller");
  }
  const double elevation_in_vacuum = std::acos(cos_in_vacuum);
  return apparent_elevation - (elevation_in_vacuum - central_angle);
}

std::vector<double> astronomical_refraction(const FieldPtr& field, const std::vector<double>& apparent_elevations,
                                            const AstronomicalRefractionOptions& options, WorkControl& control) {
  options.validate();
  std::vector<double> out(apparent_elevations.size());
  parallel_for_each(int64_t(out.size()), 1, control, [&](int64_t i) {
    out[size_t(i)] = astronomical_refraction(field, apparent_elevations[size_t(i)], options);
  });
  return out;
}

}  // namespace refracta
