// Film and tone mapping of linear HDR radiance to display values (shared/SHADING.md section 8):
// linear l = min(c L, 1), film response l = 1 - e^(-c L), Reinhard et al. 2002 ("Photographic
// Tone Reproduction for Digital Images", SIGGRAPH), a filmic ACES curve, and the transfer curve
// (sRGB or a gamma). Output stays linear in float files (EXR); this is for 8-bit display.
//
// The exposure c, in this order (display_exposure):
// - manual: `exposure` (c itself), or photographic units: EV100, or a camera's ISO S, shutter
//   time t [s] and f-number N with EV100 = log2(N^2 / t) - log2(S / 100), turned into
//   c = K / (1.2 x 2^EV100): the saturation-based sensitivity of ISO 12232 (L_max = 78 / (S q)
//   x N^2 / t [cd/m^2], q = 0.65, so the luminance L_max = 1.2 x 2^EV100 at ISO 100 maps to 1),
//   as in Lagarde & de Rousiers 2014, "Moving Frostbite to Physically Based Rendering 3.0",
//   SIGGRAPH course, sec. 4.5, eq. 51-53. K [cd/m^2 per image unit] turns the image's values
//   into luminance: 683 lm/W (kLuminousEfficacy) for radiance in W m^-2 sr^-1 whose Y is the
//   photometrically weighted radiance -- refracta.examples' unit (the physical sky times
//   106.857 nm, examples.RADIANCE_SCALE); a sunlit example is then well exposed near sunny 16
//   (hot road at its 640 x 320: EV100 13.9 by the automatic exposure, sunny 16 is 14.6).
// - automatic (no manual setting, or a `key` given): the log-average luminance of the image goes
//   to the key a (Reinhard et al. 2002, eq. 1-2: c = a / Lw_bar, middle grey a = 0.18 by default,
//   kAutoKey), metered on the image itself: a manual exposure given with a key has no effect.
//
// White balance (white_balance; before the exposure's scale and the tone curve, as a camera
// balances its raw image): the light named as white is adapted to the display's white (D65, the
// sRGB white) by the Bradford transform in XYZ (spectral::bradford_adaptation), so that a grey lit
// by it shows neutral with its luminance kept. Named by
// - a colour temperature [K] in [kMinWhiteBalanceKelvin, kMaxWhiteBalanceKelvin]: Planck's
//   radiator at it (the Planckian locus, spectral::planckian_white);
// - a preset as cameras name them: 'daylight' CIE D55 (5503 K on the CIE daylight locus, the
//   photographic daylight standard), 'cloudy' D65 (6504 K on the daylight locus: within 0.09 % of the render's own white),
//   'shade' D75 (7504 K), 'tungsten' a 3200 K Planckian radiator (studio tungsten lamps);
// - an RGB white (linear sRGB, its X, Y, Z > 0; a channel may be negative, as a low sun's blue): the colour
//   of the light, e.g. a grey card's pixel;
// - 'auto': grey world (Buchsbaum 1980, "A spatial processor model for object colour
//   perception", J. Franklin Inst. 310): the mean linear RGB of the image's pixels (negative and
//   non-finite values skipped) is taken as the light's colour; a black image is left as it is;
// - 'none' (the default): no balance, the render's own D65 white (as 'cloudy', to 0.09 %).
// The exposure meters the image before the balance (a camera's meter reads the raw light); the
// balance keeps a white's luminance. Grey images (1-2 channels) are not balanced. Float files are
// written unbalanced (io.write_image).
//
// ACES (Tonemap::kAces): the ACES reference rendering and sRGB output transforms (RRT + ODT) as
// fitted by Stephen Hill (BakingLab, ACES.hlsl, 2016): linear sRGB -> the fit's input matrix ->
// (v (v + 0.0245786) - 0.000090537) / (v (0.983729 v + 0.4329510) + 0.238081) per channel -> its
// output matrix, clamped; the input first scaled by 1 / 0.6 (three.js's ACESFilmicToneMapping) so
// that middle grey 0.18 displays near 0.5 after the sRGB curve, as Reinhard's does. OpenColorIO
// with an ACES config would be the reference, but the OpenImageIO here (2.4 over OCIO 2.1) has
// no config with ACES (only its built-in linear/sRGB/Rec709 spaces) and OCIO 2.1 has no
// built-in ACES config (those came with 2.2).
#pragma once

#include "refracta/core/image.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace refracta {

enum class Tonemap { kLinear, kFilm, kReinhard, kAces };
Tonemap parse_tonemap(const std::string& name);  // "linear", "film", "reinhard", "aces"

constexpr double kAutoKey = 0.18;  // automatic exposure's key: middle grey (Reinhard et al. 2002)
constexpr double kDefaultIso = 100.0;  // ISO when shutter and f-number are given without one
// Luminance [cd/m^2] per W m^-2 sr^-1 of photometrically weighted radiance: the SI definition of
// the candela (683 lm/W at 540 THz) applied to Y.
constexpr double kLuminousEfficacy = 683.0;

// The white balance's colour temperatures [K]: a candle's flame (~1850 K) to a clear blue sky's
// light (~27000 K) lie inside; beyond, Planck's radiator hardly changes colour (within 0.01 in x of
// the locus' limit above 40000 K) or gives no blue at all below 1000 K.
constexpr double kMinWhiteBalanceKelvin = 1000.0;
constexpr double kMaxWhiteBalanceKelvin = 40000.0;
// A white balance as users name it (tonemap.h): a preset or 'auto'/'none', a colour temperature
// [K], or an RGB white (linear sRGB).
using WhiteBalance = std::variant<std::string, double, std::array<double, 3>>;

// The transfer curve after tone mapping: the IEC 61966-2-1 sRGB curve, or p = l^(1/gamma).
enum class Transfer { kSrgb, kGamma };

// How refracta.io turns linear radiance into display values (shading/tonemap.h; the formulas: the
// refracta.io module). Exposure: automatic (no manual field set: the image's log-average luminance
// goes to `key`), or manual, at most one of `exposure`, `ev100`, or `shutter` with `f_number` (and
// `iso`); a `key` given overrides a manual exposure. The white balance `white_balance` (none by
// default), then the tone curve `tonemap` and the transfer curve `gamma`. validate() lists every
// bad field.
struct DisplaySettings {
  // Manual exposure, at most one of: exposure; ev100; a camera's shutter and f_number (with iso,
  // default kDefaultIso). None of them: automatic.
  std::optional<double> exposure;  // c > 0 multiplying the radiance (manual); None: not this way
  std::optional<double> ev100;     // manual exposure as EV100: c = K / (1.2 x 2^EV100); None: not this way
  std::optional<double> iso;       // a camera's ISO with shutter and f_number; None: ISO 100 (kDefaultIso)
  std::optional<double> shutter;   // [s] a camera's shutter time (with f_number); None: not this way
  std::optional<double> f_number;  // a camera's f-number N (with shutter)
  // K: luminance [cd/m^2] of an image value of 1 (EV100 and camera settings only): 683 lm/W for
  // radiance in W/(m^2 sr).
  double luminous_efficacy = kLuminousEfficacy;
  // The default: ACES, a photographic film curve (io.py says why, with figures).
  Tonemap tonemap = Tonemap::kAces;
  // Automatic exposure's key a (eq. 2: c = a / Lw_bar, Lw_bar = exp(mean ln(delta + Lw)) over the
  // image, delta = kReinhardDelta times the mean luminance: exactly scale-free); given, it
  // overrides any manual exposure; none: kAutoKey (0.18) when there is no manual exposure, else none.
  std::optional<double> key;
  // Reinhard: L_white of eq. 4, Ld = min(1, L (1 + L / L_white^2) / (1 + L)), the smallest scaled
  // luminance mapped to display luminance 1 (in the colour's own hue: Ld / Lw scales its
  // channels); none: infinite, Ld = L / (1 + L) (eq. 3). Reinhard's only (other tone curves
  // refuse it).
  std::optional<double> white;
  Transfer transfer = Transfer::kSrgb;
  double gamma = 2.2;  // Transfer::kGamma: g in [1, 3] (1: linear output)
  // The light shown white (before exposure and tone curve; the formulas above): 'none' (the
  // default: the render's own D65 white, today's images unchanged), 'auto' (grey world), a preset
  // ('daylight', 'cloudy', 'shade', 'tungsten'), a colour temperature [K] or an RGB white.
  WhiteBalance white_balance = std::string("none");

  // Throws std::invalid_argument listing every invalid field.
  void validate() const;
};

constexpr double kReinhardDelta = 1e-6;  // Reinhard's small value keeping ln finite on black pixels

// EV100 of a camera's settings: log2(N^2 / t) - log2(S / 100) (throws for values <= 0 or NaN).
double ev100_of(double f_number, double shutter_s, double iso = kDefaultIso);
// The exposure c of EV100: K / (1.2 x 2^EV100) (Lagarde & de Rousiers 2014, eq. 51-53), K the
// luminance [cd/m^2] of an image value of 1.
double exposure_of_ev100(double ev100, double luminous_efficacy = kLuminousEfficacy);
// The manual exposure c of the settings (1 when they give none; float files use it).
double manual_exposure(const DisplaySettings& settings);
// The names of the fields that only shape a displayed image (tonemap, key, white, gamma,
// white_balance) set away from their defaults: what a float file, written linear, leaves unused.
std::vector<std::string> display_only_fields_set(const DisplaySettings& settings);
// A float file's pixels (written linear): the image times the manual exposure (none: 1; never
// automatic), alpha (the last of 2 or 4 channels: a coverage, not light) untouched. Throws
// std::invalid_argument where that overflows float32.
void expose_linear(Image& image, const DisplaySettings& settings);
// The exposure c the settings give this image (manual, or automatic from its log-average; an image
// without light -- no pixel of positive luminance -- gets the manual one, 1 unless given, and
// `metered_nothing`, if given, says so).
double display_exposure(const Image& image, const DisplaySettings& settings, bool* metered_nothing = nullptr);
// Whether some pixel has a positive luminance (negative channels count as 0).
bool has_light(const Image& image);

// The white balance's matrix B (linear sRGB -> linear sRGB, rgb' = B rgb) for this image ('auto'
// reads it; other settings do not): xyz_to_rgb x Bradford(light's white -> D65) x rgb_to_xyz, the
// identity for 'none' and for grey images.
Eigen::Matrix3d white_balance_matrix(const Image& image, const DisplaySettings& settings);

// The log-average luminance Lw_bar = exp(mean ln(delta + Lw)) of the image (delta:
// kReinhardDelta x min(1, the mean luminance), or kReinhardDelta for a black image; luminance:
// Y of linear sRGB, 0.2126 R + 0.7152 G + 0.0722 B normalised to sum 1; 1-2 channels: the first).
double log_average_luminance(const Image& image);

// Tone map and encode a whole image in place (the 4th channel of RGBA and the 2nd of grey+alpha
// untouched). Linear and film map each channel; Reinhard maps the luminance Lw to Ld and scales
// the colour by Ld / Lw (hue kept), each channel then clamped to [0, 1]. Computed in double with
// c L clamped to 1e300 first: finite input never gives NaN or inf, whatever the exposure.
void tonemap_image(Image& image, const DisplaySettings& settings);

// One value: x = exposure * radiance; linear: x, film: 1 - e^-x, Reinhard: x / (1 + x) (no
// log-average), ACES: Hill's fit of a grey x; clamped to [0, 1].
float tonemap(float radiance, float exposure, Tonemap mode);
// sRGB opto-electronic transfer (IEC 61966-2-1) of a linear value in [0, 1], and its inverse.
float srgb_encode(float linear);
double srgb_decode(double encoded);

// An image file's linear values (OIIO reads any format): 8- and 16-bit files decoded by the
// transfer their header names (stored_gamma: a PNG's gAMA chunk, "linear"), else from sRGB, the
// convention for textures and environment maps; alpha (the 2nd of 2 channels, the 4th of 4) as
// stored; float files as they are. Throws IoError.
Image read_linear_image(const std::string& path);

}  // namespace refracta
