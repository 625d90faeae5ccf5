// Tone mapping, film response, Reinhard's photographic operator and transfer curves (tonemap.h).
#include "refracta/shading/tonemap.h"

#include "refracta/core/error.h"
#include "refracta/scene/image_io.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

// Hill's ACES fit (tonemap.h): the RRT + ODT curve on the fit's working space.
double rrt_and_odt_fit(double v) { return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081); }
constexpr double kAcesBoost = 1.0 / 0.6;  // three.js: middle grey 0.18 -> ~0.5 after sRGB encoding

// ACES on a linear sRGB colour (colour == 3) or a grey (the matrices' rows sum to 1 within 1e-5).
void aces(const double* scaled, int colour, double* out) {
  static const double in[3][3] = {{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
  static const double back[3][3] = {{1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
  if (colour == 1) {
    out[0] = std::clamp(rrt_and_odt_fit(std::min(kAcesBoost * scaled[0], 1e150)), 0.0, 1.0);
    return;
  }
  double fitted[3];
  for (int r = 0; r < 3; ++r) {
    // Huge inputs saturate at the curve's limit 1 / 0.983729 (v^2 would overflow).
    const double v = std::min(kAcesBoost * (in[r][0] * scaled[0] + in[r][1] * scaled[1] + in[r][2] * scaled[2]), 1e150);
    fitted[r] = rrt_and_odt_fit(v);
  }
  for (int r = 0; r < 3; ++r) {
    out[r] = std::clamp(back[r][0] * fitted[0] + back[r][1] * fitted[1] + back[r][2] * fitted[2], 0.0, 1.0);
  }
}

// The white balance's presets: a CIE daylight illuminant's correlated temperature, or a
// Planckian one (tonemap.h).
struct WhiteBalancePreset {
  const char* name;
  double kelvin;
  bool daylight;
};
constexpr WhiteBalancePreset kWhiteBalancePresets[] = {
    {"daylight", 5503.0, true}, {"cloudy", 6504.0, true}, {"shade", 7504.0, true}, {"tungsten", 3200.0, false}};

const WhiteBalancePreset* find_preset(const std::string& name) {
  for (const auto& preset : kWhiteBalancePresets) {
    if (name == preset.name) return &preset;
  }
  return nullptr;
}

// The problem with a white balance, or "" when it is valid.
std::string white_balance_problem(const WhiteBalance& wb) {
  if (const auto* name = std::get_if<std::string>(&wb)) {
    if (*name == "none" || *name == "auto" || find_preset(*name)) return "";
    return concat("white_balance must be 'auto', 'none', 'daylight', 'cloudy', 'shade', 'tungsten', a colour "
                  "temperature [K] or an RGB white (got '", *name, "')");
  }
  if (const auto* kelvin = std::get_if<double>(&wb)) {
    if (*kelvin >= kMinWhiteBalanceKelvin && *kelvin <= kMaxWhiteBalanceKelvin) return "";
    return concat("white_balance must be a colour temperature in [", kMinWhiteBalanceKelvin, ", ",
                  kMaxWhiteBalanceKelvin, "] K (got ", *kelvin, ")");
  }
  // A light's colour, which may lie outside sRGB's gamut (a low sun's light has a negative linear
  // blue): its XYZ must be a colour, each component > 0.
  const auto& rgb = std::get<std::array<double, 3>>(wb);
  const Vec3d xyz = spectral::linear_srgb_to_xyz(Vec3d(rgb[0], rgb[1], rgb[2]));
  if (!std::isfinite(rgb[0] + rgb[1] + rgb[2]) || !(xyz.minCoeff() > 0.0) || !spectral::adaptable_white(xyz)) {
    return concat("white_balance as an RGB white must be finite, with X, Y and Z and its cone responses > 0 (a light's "
                  "colour; got (", rgb[0], ", ", rgb[1], ", ", rgb[2], "))");
  }
  return "";
}

// Grey world (tonemap.h): the mean linear RGB of the pixels, negative and non-finite values skipped.
Vec3d grey_world_white(const Image& image) {
  Vec3d sum = Vec3d::Zero();
  const size_t count = size_t(image.width) * image.height;
  for (size_t i = 0; i < count; ++i) {
    const float* p = &image.pixels[i * image.channels];
    for (int k = 0; k < 3; ++k) {
      if (std::isfinite(p[k]) && p[k] > 0.0f) sum[k] += p[k];
    }
  }
  return sum / double(std::max<size_t>(count, 1));
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
  if (name == "aces") return Tonemap::kAces;
  throw_invalid("tonemap must be 'linear', 'film', 'reinhard' or 'aces' (got '", name, "')");
}

namespace {
// Exposure values a camera meets with margin: a starlit night is about -6, sunlit snow 16; beyond
// +-50 the exposure 2^-EV over- or underflows what a pixel can show (1e300 gave a black image).
constexpr double kLargestEv100 = 50.0;
}  // namespace

double ev100_of(double f_number, double shutter_s, double iso) {
  std::vector<std::string> problems;
  auto positive = [&](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) problems.push_back(concat(name, " must be > 0 and finite (got ", v, ")"));
  };
  positive(f_number, "f_number");
  positive(shutter_s, "shutter");
  positive(iso, "iso");
  if (!problems.empty()) {
    std::string message;
    for (const auto& p : problems) message += (message.empty() ? "" : "; ") + p;
    throw_invalid(message);
  }
  const double ev100 = std::log2(f_number * f_number / shutter_s) - std::log2(iso / 100.0);
  if (!(std::abs(ev100) <= kLargestEv100)) {
    throw_invalid("f_number ", f_number, ", shutter ", shutter_s, " s and iso ", iso, " give EV100 ", ev100,
                  ", beyond +-", kLargestEv100, " (a starlit night is -6, sunlit snow 16)");
  }
  return ev100;
}

double exposure_of_ev100(double ev100, double luminous_efficacy) {
  if (!(std::abs(ev100) <= kLargestEv100)) throw_invalid("ev100 must be in [-", kLargestEv100, ", ", kLargestEv100, "] (got ", ev100, ")");
  if (!(luminous_efficacy > 0.0) || !std::isfinite(luminous_efficacy)) {
    throw_invalid("luminous_efficacy must be > 0 and finite (got ", luminous_efficacy, ")");
  }
  return luminous_efficacy / (1.2 * std::exp2(ev100));
}

void expose_linear(Image& image, const DisplaySettings& settings) {
  const double c = manual_exposure(settings);
  if (c == 1.0) return;
  const int colours = colour_channels(image.channels);  // alpha (2nd of 2, 4th of 4): a coverage, not light
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (int(i % size_t(image.channels)) < colours) image.pixels[i] *= float(c);
  }
  if (!std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); })) {
    throw_invalid("write_image: the image times the exposure (", c, ") overflows float32 (a value beyond ",
                  std::numeric_limits<float>::max(), "): lower the exposure");
  }
}

double manual_exposure(const DisplaySettings& s) {
  s.validate();
  // K turns EV100 into an exposure; used without one (automatic, or exposure=) it was ignored
  // silently. Refused where the settings are used, not where built: a preset may carry K for the
  // EV100 each call gives.
  if (s.luminous_efficacy != kLuminousEfficacy && !s.ev100 && !s.shutter) {
    throw_invalid("display settings: luminous_efficacy (the luminance [cd/m^2] of a value of 1) applies to a photographic exposure: give "
                  "ev100, or shutter and f_number, or no luminous_efficacy");
  }
  if (s.exposure) return *s.exposure;
  if (s.ev100) return exposure_of_ev100(*s.ev100, s.luminous_efficacy);
  if (s.shutter) {
    return exposure_of_ev100(ev100_of(*s.f_number, *s.shutter, s.iso.value_or(kDefaultIso)), s.luminous_efficacy);
  }
  return 1.0;
}

std::vector<std::string> display_only_fields_set(const DisplaySettings& s) {
  const DisplaySettings defaults;
  std::vector<std::string> set;
  if (s.tonemap != defaults.tonemap) set.emplace_back("tonemap");
  if (s.key) set.emplace_back("key");
  if (s.white) set.emplace_back("white");
  if (s.transfer != defaults.transfer || (s.transfer == Transfer::kGamma && s.gamma != defaults.gamma)) {
    set.emplace_back("gamma");
  }
  if (s.white_balance != defaults.white_balance) set.emplace_back("white_balance");
  return set;
}

bool has_light(const Image& image) {
  const int colour = colour_channels(image.channels);
  double scaled[3];
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    if (luminance(&image.pixels[i * image.channels], colour, 1.0, scaled) > 0.0) return true;
  }
  return false;
}

double display_exposure(const Image& image, const DisplaySettings& s, bool* metered_nothing) {
  if (metered_nothing) *metered_nothing = false;
  const double manual = manual_exposure(s);
  const bool is_manual = s.exposure || s.ev100 || s.shutter;
  if (is_manual && !s.key) return manual;
  // An image without light meters nothing: a / delta (180 000) was no exposure for frames that
  // share it (io.exposure_of warns).
  if (!has_light(image)) {
    if (metered_nothing) *metered_nothing = true;
    return manual;
  }
  // Automatic: a / Lw_bar, metered on the image itself, so that a manual exposure given with a key
  // has no say (metered after it, the delta of the black pixels, set in its scaled units, left a
  // half-black image's exposure 22x higher under exposure=1000: a trial).
  return s.key.value_or(kAutoKey) / log_average_luminance(image);
}

void DisplaySettings::validate() const {
  Problems problems("display settings");
  problems.check(!exposure || (*exposure > 0.0 && std::isfinite(*exposure)), "exposure must be > 0 and finite (got ",
                 exposure.value_or(0.0), ")");
  problems.check(!ev100 || std::abs(*ev100) <= kLargestEv100, "ev100 must be in [-", kLargestEv100, ", ",
                 kLargestEv100, "] (got ", ev100.value_or(0.0), ")");
  auto positive = [&](const std::optional<double>& v, const char* name) {
    problems.check(!v || (*v > 0.0 && std::isfinite(*v)), name, " must be > 0 and finite (got ", v.value_or(0.0), ")");
  };
  positive(iso, "iso");
  positive(shutter, "shutter");
  positive(f_number, "f_number");
  positive(luminous_efficacy, "luminous_efficacy");
  problems.check(!(iso || shutter || f_number) || (shutter && f_number),
                 "a camera's exposure needs both shutter [s] and f_number (iso defaults to 100)");
  problems.check(int(exposure.has_value()) + int(ev100.has_value()) + int(shutter || f_number || iso) <= 1,
                 "give one manual exposure: exposure, ev100, or shutter and f_number (with iso)");
  problems.check(!key || (*key > 0.0 && std::isfinite(*key)), "key must be > 0 and finite (got ", key.value_or(0.0), ")");
  problems.check(!white || *white > 0.0, "white must be > 0 (got ", white.value_or(0.0), ")");
  problems.check(!white || tonemap == Tonemap::kReinhard,
                 "white (Reinhard's L_white) applies to tonemap='reinhard' only: give tonemap='reinhard' or no white");
  const std::string wb_problem = white_balance_problem(white_balance);
  problems.check(wb_problem.empty(), wb_problem);
  problems.check(transfer != Transfer::kGamma || (gamma >= 1.0 && gamma <= 3.0), "gamma must be in [1, 3] (got ", gamma, ")");
  problems.throw_if_any();
}

Eigen::Matrix3d white_balance_matrix(const Image& image, const DisplaySettings& s) {
  s.validate();
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  if (colour_channels(image.channels) != 3) return identity;
  // The light's white in XYZ (any Y: the adaptation is scaled to keep the white's luminance).
  Vec3d light;
  if (const auto* name = std::get_if<std::string>(&s.white_balance)) {
    if (*name == "none") return identity;
    if (*name == "auto") {
      const Vec3d mean = grey_world_white(image);
      if (!(mean.minCoeff() > 0.0)) return identity;  // black, or a channel without light: nothing to balance by
      light = spectral::linear_srgb_to_xyz(mean);
    } else {
      const WhiteBalancePreset& preset = *find_preset(*name);
      light = preset.daylight ? spectral::daylight_white(preset.kelvin) : spectral::planckian_white(preset.kelvin);
    }
  } else if (const auto* kelvin = std::get_if<double>(&s.white_balance)) {
    light = spectral::planckian_white(*kelvin);
  } else {
    const auto& rgb = std::get<std::array<double, 3>>(s.white_balance);
    light = spectral::linear_srgb_to_xyz(Vec3d(rgb[0], rgb[1], rgb[2]));
  }
  const Vec3d display_white = spectral::linear_srgb_to_xyz(Vec3d::Ones());
  Eigen::Matrix3d to_xyz, to_rgb;
  for (int k = 0; k < 3; ++k) {
    to_xyz.col(k) = spectral::linear_srgb_to_xyz(Vec3d::Unit(k));
    to_rgb.col(k) = spectral::xyz_to_linear_srgb(Vec3d::Unit(k));
  }
  return to_rgb * spectral::bradford_adaptation(light / light.y() * display_white.y(), display_white) * to_xyz;
}

double log_average_luminance(const Image& image) {
  const int colour = colour_channels(image.channels);
  const size_t count = size_t(image.width) * image.height;
  if (count == 0) return 0.0;
  double sum = 0.0, scaled[3];
  // delta in the image's own units (Reinhard's constant times the mean luminance), so the exposure
  // scales exactly with the light's units: a constant delta outweighed every pixel of a scene
  // scaled by 1e-9 (it came out black), and, capped at 1, moved the exposure of an image with 5 %
  // black pixels by 1.3x between units of 1 and 683 (two trials).
  for (size_t i = 0; i < count; ++i) sum += luminance(&image.pixels[i * image.channels], colour, 1.0, scaled);
  const double mean = sum / double(count);
  const double delta = kReinhardDelta * (mean > 0.0 ? mean : 1.0);
  sum = 0.0;
  for (size_t i = 0; i < count; ++i) sum += std::log(delta + luminance(&image.pixels[i * image.channels], colour, 1.0, scaled));
  return std::exp(sum / double(count));
}

void tonemap_image(Image& image, const DisplaySettings& s) {
  s.validate();
  const int colour = colour_channels(image.channels);
  const size_t count = size_t(image.width) * image.height;
  // The exposure c, manual or automatic (Reinhard eq. 2: the scale a / Lw_bar taking the
  // log-average to the key).
  const double exposure = display_exposure(image, s);
  // The white balance (before the exposure's scale, as a camera balances its raw image).
  const Eigen::Matrix3d balance = white_balance_matrix(image, s);
  const bool balanced = !balance.isIdentity(0.0);
  const double inv_white2 = s.white ? 1.0 / (*s.white * *s.white) : 0.0;
  double scaled[3];
  for (size_t i = 0; i < count; ++i) {
    float* p = &image.pixels[i * image.channels];
    if (balanced) {
      const Vec3d rgb = balance * Vec3d(p[0], p[1], p[2]);
      for (int k = 0; k < 3; ++k) p[k] = float(rgb[k]);
    }
    const double lw = luminance(p, colour, exposure, scaled);
    double out[3];
    switch (s.tonemap) {
      case Tonemap::kLinear:
        for (int k = 0; k < colour; ++k) out[k] = std::min(scaled[k], 1.0);
        break;
      case Tonemap::kFilm:
        for (int k = 0; k < colour; ++k) out[k] = -std::expm1(-scaled[k]);
        break;
      case Tonemap::kReinhard: {
        const double l = std::min(lw, kMaxScaled);
        // Eq. 4 as L/(1+L) * (1 + L/Lwhite^2): no inf/inf for huge L.
        const double ld = std::min(l / (1.0 + l) * (1.0 + l * inv_white2), 1.0);
        const double ratio = lw > 0.0 ? ld / lw : 0.0;
        for (int k = 0; k < colour; ++k) out[k] = std::min(scaled[k] * ratio, 1.0);
        break;
      }
      case Tonemap::kAces:
        aces(scaled, colour, out);
        break;
    }
    for (int k = 0; k < colour; ++k) p[k] = float(transfer(out[k], s));
  }
}

float tonemap(float radiance, float exposure, Tonemap mode) {
  const double x = std::min(std::max(double(radiance) * double(exposure), 0.0), kMaxScaled);
  double y = x;
  if (mode == Tonemap::kFilm) y = -std::expm1(-x);
  if (mode == Tonemap::kReinhard) y = x / (1.0 + x);
  if (mode == Tonemap::kAces) aces(&x, 1, &y);
  return float(std::clamp(y, 0.0, 1.0));
}

float srgb_encode(float c) {
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

Image read_linear_image(const std::string& path) {
  Image image = read_image(path);
  const double gamma = stored_gamma(path);
  if (gamma == 1.0) return image;
  const int colours = colour_channels(image.channels);  // alpha (2nd of 2, 4th of 4) as stored
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    float& v = image.pixels[i];
    if (int(i % size_t(image.channels)) < colours) v = float(gamma > 0.0 ? std::pow(double(v), gamma) : srgb_decode(v));
  }
  return image;
}

}  // namespace refracta
