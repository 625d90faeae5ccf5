#include "refracta/render/picking.h"

#include "refracta/core/error.h"
#include "refracta/media/curved_earth.h"
#include "refracta/media/fields.h"
#include "refracta/render/caster.h"

#include <cmath>
#include <memory>
#include <vector>

namespace refracta {

FieldPtr straight_air(const IndexField* field) {
  if (!field || !std::isfinite(field->earth_radius())) return nullptr;
  return std::make_shared<const CurvedEarth>(std::make_shared<const LinearSquaredProfile>(NoConfig{}, std::vector<double>{1.0, 0.0}),
                                             field->earth_radius());
}

std::optional<Vec3d> picked_point(const Scene& scene, const Camera& camera, const FieldPtr& field, double u, double v,
                                  std::optional<double> max_length) {
  const Vec3d& eye = camera.position();
  const Vec3d dir = camera.pixel_direction(u, v);  // first: it names non-finite u and v
  // Off the image the pinhole's ray is extrapolated: v = 1e9 picked the camera's foot (a trial).
  if (!(u >= 0.0 && u <= camera.width() && v >= 0.0 && v <= camera.height())) {
    throw_invalid("pick: pixel (", u, ", ", v, ") lies outside the camera's ", camera.width(), " x ", camera.height(),
                  " image (u in [0, ", camera.width(), "], v in [0, ", camera.height(), "])");
  }
  const double reach = kSceneReach - eye.cwiseAbs().maxCoeff();
  const double length = max_length.value_or(reach);
  if (!(length > 0.0 && length <= reach)) {
    throw_invalid("pick: max_length must be > 0 and keep the ray within ", kSceneReach,
                  " m of the origin, where scene coordinates end (at most ", reach, " m from this camera; got ", length,
                  ")");
  }
  if (!field) {
    const auto hit = scene.intersect(eye, dir, length);
    return hit ? std::optional(hit->point) : std::nullopt;
  }
  RenderOptions options;
  options.method = RenderMethod::kCurved;
  options.max_length = length;
  options.validate();
  const Caster caster(scene, field.get(), options);
  const PathEnd end = caster.cast(eye, dir);
  return end.hit ? std::optional(end.hit->point) : std::nullopt;
}

std::vector<Vec3d> projected_over_sphere(const Camera& camera, double earth_radius, std::vector<Vec3d> points) {
  // CurvedEarth's own floor: below it e^(y/R) overflows (a radius of 1e-300 gave NaN pixels).
  if (!(earth_radius >= CurvedEarth::kMinRadius)) {
    throw_invalid("project: earth_radius must be at least ", CurvedEarth::kMinRadius, " m, or inf (got ", earth_radius,
                  ")");
  }
  if (std::isinf(earth_radius)) return camera.project(std::move(points));
  const Vec3d& eye = camera.position();
  const Vec3d eye_true = CurvedEarth::sphere_point(eye, earth_radius);
  for (Vec3d& p : points) {
    // The point along the eye's flat-frame direction of its true one, as far as it truly is.
    const Vec3d d = CurvedEarth::sphere_point(p, earth_radius) - eye_true;
    p = eye + CurvedEarth::turned(eye, d, earth_radius, false);
  }
  return camera.project(std::move(points));
}

}  // namespace refracta
