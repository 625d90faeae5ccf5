// Sun and sky.
#include "refracta/shading/lights.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

Vec3d Sun::irradiance() const {
  const double radius = 0.5 * degrees_to_radians(angular_diameter);
  const double solid_angle = 2.0 * kPi * (1.0 - std::cos(radius));
  return radiance * solid_angle;
}

void Sun::validate() {
  if (!is_finite(direction) || direction.norm() == 0.0) throw_invalid("sun direction must be finite and non-zero");
  direction.normalize();
  if (!is_finite(radiance) || radiance.minCoeff() < 0.0) throw_invalid("sun radiance must be finite and >= 0");
  if (!(angular_diameter > 0.0 && angular_diameter < 90.0)) {
    throw_invalid("sun angular_diameter must be in (0, 90) deg (got ", angular_diameter, ")");
  }
}

Vec3d Sky::radiance(const Vec3d& dir, double footprint) const {
  if (environment >= 0) return scale * textures->environment(environment, dir.normalized(), footprint);
  const double t = std::clamp(dir.y() / dir.norm(), 0.0, 1.0);
  return (1.0 - t) * horizon + t * zenith;
}

void Sky::validate() {
  if (!is_finite(horizon) || horizon.minCoeff() < 0.0) throw_invalid("sky horizon radiance must be finite and >= 0");
  if (!is_finite(zenith) || zenith.minCoeff() < 0.0) throw_invalid("sky zenith radiance must be finite and >= 0");
  if (!(scale >= 0.0) || !std::isfinite(scale)) throw_invalid("sky scale must be >= 0 (got ", scale, ")");
  if (environment >= 0 && !textures) throw_invalid("sky: an environment map needs its textures");
  if (environment < 0) {
    // Integral of L(t) cos over the hemisphere / pi with t = cos(theta): 2 int_0^1 L(t) t dt.
    mean_ = horizon / 3.0 + zenith * (2.0 / 3.0);
    return;
  }
  // (1/pi) int L cos dw by the midpoint rule on (t = cos theta, phi), the map filtered over a cell.
  constexpr int kRings = 32, kSegments = 64;
  Vec3d sum = Vec3d::Zero();
  for (int i = 0; i < kRings; ++i) {
    const double t = (i + 0.5) / kRings, r = std::sqrt(1.0 - t * t);
    for (int j = 0; j < kSegments; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / kSegments;
      sum += radiance(Vec3d(r * std::cos(phi), t, r * std::sin(phi)), 2.0 * kPi / kSegments) * t;
    }
  }
  mean_ = sum * (2.0 / (kRings * kSegments));  // (1/pi) * 2 pi * (1/kRings) * (1/kSegments) * sum
}

bool SpotLight::covers(const Vec3d& point) const {
  const Vec3d to_point = point - position;
  const double d = to_point.norm();
  return d > 0.0 && to_point.dot(direction) >= d * std::cos(0.5 * degrees_to_radians(angle));
}

void SpotLight::validate() {
  if (!is_finite(position)) throw_invalid("spot light position must be finite");
  if (!is_finite(direction) || direction.norm() == 0.0) throw_invalid("spot light direction must be finite and non-zero");
  direction.normalize();
  if (!(angle > 0.0 && angle <= 170.0)) throw_invalid("spot light angle must be in (0, 170] deg (got ", angle, ")");
  if (!is_finite(intensity) || intensity.minCoeff() < 0.0) throw_invalid("spot light intensity must be finite and >= 0");
  if (!(radius >= 0.0) || !std::isfinite(radius)) throw_invalid("spot light radius must be >= 0 (got ", radius, ")");
}

}  // namespace refracta
