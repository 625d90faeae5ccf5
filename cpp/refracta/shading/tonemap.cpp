// Tone mapping and sRGB.
#include "refracta/shading/tonemap.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

Tonemap parse_tonemap(const std::string& name) {
  if (name == "linear") return Tonemap::kLinear;
  if (name == "film") return Tonemap::kFilm;
  if (name == "reinhard") return Tonemap::kReinhard;
  throw_invalid("tonemap must be 'linear', 'film' or 'reinhard' (got '", name, "')");
}

float tonemap(float radiance, float exposure, Tonemap mode) {
  const float x = std::max(radiance * exposure, 0.0f);
  float y = x;
  if (mode == Tonemap::kFilm) y = 1.0f - std::exp(-x);
  if (mode == Tonemap::kReinhard) y = x / (1.0f + x);
  return std::clamp(y, 0.0f, 1.0f);
}

float srgb_encode(float c) {
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace refracta
