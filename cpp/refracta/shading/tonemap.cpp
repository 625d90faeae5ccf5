// Tone mapping, film response, Reinhard's photographic operator and transfer curves (tonemap.h).
#include "refracta/shading/tonemap.h"

#include "refracta/core/error.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace refracta {

namespace {

constexpr double kMaxScaled = 1e300;  // c L beyond this maps to white anyway; keeps products finite

// Display channels of a pixel: colour (3) or grey (1); the rest is alpha.
int colour_channels(int channels) { return channels >= 3 ? 3 : 1; }

double luminance(const float* p, int colour, double exposure, double* scaled) {
  for (int k = 0; k < colour; ++k) scaled[k] = std::min(std::max(double(p[k]), 0.0) * exposure, kMaxScaled);
  if (colour == 1) return scaled[0];
  // The Y row of linear sRGB -> XYZ, normalised to sum 1 so that a grey (v, v, v) has luminance v.
  static const Vec3d weights = [] {
    const Vec3d y(spectral::linear_srgb_to_xyz(Vec3d::UnitX()).y(), spectral::linear_srgb_to_xyz(Vec3d::UnitY()).y(),
                  spectral::linear_srgb_to_xyz(Vec3d::UnitZ()).y());
    return Vec3d(y / y.sum());
  }();
  return weights.x() * scaled[0] + weights.y() * scaled[1] + weights.z() * scaled[2];
}

double transfer(double l, const DisplaySettings& s) {
  l = std::clamp(l, 0.0, 1.0);
  return s.transfer == Transfer::kSrgb ? double(srgb_encode(float(l))) : std::pow(l, 1.0 / s.gamma);
}

}  // namespace

Tonemap parse_tonemap(const std::string& name) {
  if (name == "linear") return Tonemap::kLinear;
  if (name == "film") return Tonemap::kFilm;
  if (name == "reinhard") return Tonemap::kReinhard;
  throw_invalid("tonemap must be 'linear', 'film' or 'reinhard' (got '", name, "')");
}

void DisplaySettings::validate() const {
  std::vector<std::string> problems;
  if (!(exposure > 0.0) || !std::isfinite(exposure)) problems.push_back(concat("exposure must be > 0 and finite (got ", exposure, ")"));
  if (key && (!(*key > 0.0) || !std::isfinite(*key))) problems.push_back(concat("key must be > 0 and finite (got ", *key, ")"));
  if (white && (!(*white > 0.0) || std::isnan(*white))) problems.push_back(concat("white must be > 0 (got ", *white, ")"));
  if (transfer == Transfer::kGamma && !(gamma >= 1.0 && gamma <= 3.0)) problems.push_back(concat("gamma must be in [1, 3] (got ", gamma, ")"));
  if (problems.empty()) return;
  std::string message;
  for (const auto& p : problems) message += (message.empty() ? "" : "; ") + p;
  throw_invalid(message);
}

double log_average_luminance(const Image& image, double exposure) {
  const int colour = colour_channels(image.channels);
  const size_t count = size_t(image.width) * image.height;
  if (count == 0) return 0.0;
  double sum = 0.0, scaled[3];
  for (size_t i = 0; i < count; ++i) sum += std::log(kReinhardDelta + luminance(&image.pixels[i * image.channels], colour, exposure, scaled));
  return std::exp(sum / double(count));
}

void tonemap_image(Image& image, const DisplaySettings& s) {
  s.validate();
  const int colour = colour_channels(image.channels);
  const size_t count = size_t(image.width) * image.height;
  // Reinhard eq. 2: the scale a / Lw_bar taking the log-average to the key.
  double scale = 1.0;
  if (s.tonemap == Tonemap::kReinhard && s.key) scale = *s.key / log_average_luminance(image, s.exposure);
  const double inv_white2 = s.white ? 1.0 / (*s.white * *s.white) : 0.0;
  double scaled[3];
  for (size_t i = 0; i < count; ++i) {
    float* p = &image.pixels[i * image.channels];
    const double lw = luminance(p, colour, s.exposure, scaled);
    double out[3];
    switch (s.tonemap) {
      case Tonemap::kLinear:
        for (int k = 0; k < colour; ++k) out[k] = std::min(scaled[k], 1.0);
        break;
      case Tonemap::kFilm:
        for (int k = 0; k < colour; ++k) out[k] = -std::expm1(-scaled[k]);
        break;
      case Tonemap::kReinhard: {
        const double l = std::min(scale * lw, kMaxScaled);
        // Eq. 4 as L/(1+L) * (1 + L/Lwhite^2): no inf/inf for huge L.
        const double ld = std::min(l / (1.0 + l) * (1.0 + l * inv_white2), 1.0);
        const double ratio = lw > 0.0 ? ld / lw : 0.0;
        for (int k = 0; k < colour; ++k) out[k] = std::min(scaled[k] * ratio, 1.0);
        break;
      }
    }
    for (int k = 0; k < colour; ++k) p[k] = float(transfer(out[k], s));
  }
}

float tonemap(float radiance, float exposure, Tonemap mode) {
  const double x = std::min(std::max(double(radiance) * double(exposure), 0.0), kMaxScaled);
  double y = x;
  if (mode == Tonemap::kFilm) y = -std::expm1(-x);
  if (mode == Tonemap::kReinhard) y = x / (1.0 + x);
  return float(std::clamp(y, 0.0, 1.0));
}

float srgb_encode(float c) {
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

}  // namespace refracta
