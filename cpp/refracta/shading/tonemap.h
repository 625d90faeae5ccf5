// Tone mapping of linear HDR radiance to display values, and the sRGB transfer curve.
#pragma once

#include <string>

namespace refracta {

enum class Tonemap { kLinear, kFilm, kReinhard };
Tonemap parse_tonemap(const std::string& name);  // "linear", "film", "reinhard"

// x = exposure * radiance; linear: x, film: 1 - e^-x, Reinhard: x / (1 + x). Output clamped to [0,1].
float tonemap(float radiance, float exposure, Tonemap mode);
// sRGB opto-electronic transfer (IEC 61966-2-1).
float srgb_encode(float linear);

}  // namespace refracta
