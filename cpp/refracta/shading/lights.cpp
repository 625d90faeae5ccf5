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

Vec3d Sky::radiance(const Vec3d& dir) const {
  const double t = std::clamp(dir.y() / dir.norm(), 0.0, 1.0);
  return (1.0 - t) * horizon + t * zenith;
}

// Integral of L(t) cos over the hemisphere / pi with t = cos(theta): 2 int_0^1 L(t) t dt.
Vec3d Sky::mean_radiance() const { return horizon / 3.0 + zenith * (2.0 / 3.0); }

void Sky::validate() const {
  if (!is_finite(horizon) || horizon.minCoeff() < 0.0) throw_invalid("sky horizon radiance must be finite and >= 0");
  if (!is_finite(zenith) || zenith.minCoeff() < 0.0) throw_invalid("sky zenith radiance must be finite and >= 0");
}

}  // namespace refracta
