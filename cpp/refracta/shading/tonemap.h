// Film and tone mapping of linear HDR radiance to display values (shared/SHADING.md section 8):
// linear l = min(c L, 1), film response l = 1 - e^(-c L), Reinhard et al. 2002 ("Photographic
// Tone Reproduction for Digital Images", SIGGRAPH) and the transfer curve (sRGB or a gamma).
// c is the exposure. Output stays linear in float files (EXR); this is for 8-bit display.
#pragma once

#include "refracta/core/image.h"

#include <optional>
#include <string>

namespace refracta {

enum class Tonemap { kLinear, kFilm, kReinhard };
Tonemap parse_tonemap(const std::string& name);  // "linear", "film", "reinhard"

// The transfer curve after tone mapping: the IEC 61966-2-1 sRGB curve, or p = l^(1/gamma).
enum class Transfer { kSrgb, kGamma };

struct DisplaySettings {
  double exposure = 1.0;              // c > 0, multiplies the radiance first
  Tonemap tonemap = Tonemap::kLinear;
  // Reinhard: the key a (eq. 2: L = (a / Lw_bar) Lw, Lw_bar = exp(mean ln(delta + Lw)) over the
  // image, delta = kReinhardDelta); none: no log-average scaling, L = c Lw (the exposure sets the
  // scale, as before this operator existed). Reinhard's middle grey is a = 0.18.
  std::optional<double> key;
  // Reinhard: L_white of eq. 4, Ld = L (1 + L / L_white^2) / (1 + L), the smallest scaled
  // luminance mapped to white; none: infinite, Ld = L / (1 + L) (eq. 3).
  std::optional<double> white;
  Transfer transfer = Transfer::kSrgb;
  double gamma = 2.2;  // Transfer::kGamma: g in [1, 3] (1: linear output)

  // Throws std::invalid_argument listing every invalid field.
  void validate() const;
};

constexpr double kReinhardDelta = 1e-6;  // Reinhard's small value keeping ln finite on black pixels

// The log-average luminance Lw_bar = exp(mean ln(delta + Lw)) of c x the image (luminance:
// Y of linear sRGB, 0.2126 R + 0.7152 G + 0.0722 B normalised to sum 1; 1-2 channels: the first).
double log_average_luminance(const Image& image, double exposure);

// Tone map and encode a whole image in place (the 4th channel of RGBA and the 2nd of grey+alpha
// untouched). Linear and film map each channel; Reinhard maps the luminance Lw to Ld and scales
// the colour by Ld / Lw (hue kept), each channel then clamped to [0, 1]. Computed in double with
// c L clamped to 1e300 first: finite input never gives NaN or inf, whatever the exposure.
void tonemap_image(Image& image, const DisplaySettings& settings);

// One value: x = exposure * radiance; linear: x, film: 1 - e^-x, Reinhard: x / (1 + x) (no
// log-average); clamped to [0, 1].
float tonemap(float radiance, float exposure, Tonemap mode);
// sRGB opto-electronic transfer (IEC 61966-2-1) of a linear value in [0, 1], and its inverse.
float srgb_encode(float linear);
double srgb_decode(double encoded);

}  // namespace refracta
