// Small helpers shared by the light implementations (point_light.h ... light_sampler.h):
// checks of constructor input that name the parameter, and the luminance used by power().
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/shading/color.h"

#include <cmath>

namespace refracta {
namespace detail {

// power() of every light is the luminance Y of its RGB power.
inline double luminance(const Vec3d& rgb) { return linear_srgb_luminance(rgb); }

inline void check_point(const Vec3d& p, const char* what) {
  if (!is_finite(p)) throw_invalid(what, " must be finite (got (", p.x(), ", ", p.y(), ", ", p.z(), "))");
}

// A direction given by the user: finite and non-zero; returned normalised.
inline Vec3d check_direction(const Vec3d& d, const char* what) {
  check_point(d, what);
  if (!(d.cwiseAbs().maxCoeff() > 0.0)) {
    throw_invalid(what, " must be a non-zero vector (got (", d.x(), ", ", d.y(), ", ", d.z(), "))");
  }
  return d.stableNormalized();  // scaled first: components of 1e200 or 1e-300 do not overflow or vanish
}

inline double check_non_negative(double v, const char* what) {
  if (!std::isfinite(v) || v < 0.0) throw_invalid(what, " must be finite and >= 0 (got ", v, ")");
  return v;
}

inline double check_positive(double v, const char* what) {
  if (!std::isfinite(v) || !(v > 0.0)) throw_invalid(what, " must be finite and > 0 (got ", v, ")");
  return v;
}

// An emitted quantity (radiance, intensity) as RGB: finite and >= 0 per channel.
inline Vec3d check_rgb(const Vec3d& rgb, const char* what) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0) {
      throw_invalid(what, " must be finite and >= 0 per channel (got (", rgb.x(), ", ", rgb.y(), ", ", rgb.z(), "))");
    }
  }
  return rgb;
}

// A Color a light emits: an illuminant (RGB x D65 in spectral rendering) with a valid RGB. A
// tabulated spectrum (checked >= 0 when made) may lie outside the sRGB gamut -- a low sun's
// extinguished light has negative blue -- and RGB rendering clips it (Color::sample).
inline const Color& check_emission(const Color& c, const char* what) {
  if (c.kind() != Color::Kind::kIlluminant) throw_invalid(what, " must be an illuminant Color (Color::illuminant, blackbody or a tabulated illuminant)");
  if (!c.is_tabulated()) check_rgb(c.rgb(), what);
  return c;
}

// 1 - cos(angle between unit vectors a and b), accurate for small angles: |a - b|^2 / 2.
inline double one_minus_cos(const Vec3d& a, const Vec3d& b) { return 0.5 * (a - b).squaredNorm(); }

}  // namespace detail
}  // namespace refracta
