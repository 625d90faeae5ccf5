// A colour as materials and lights hold it: linear sRGB for RGB rendering, and a spectrum for
// spectral rendering (shared/SHADING.md section 7). Reflectances are upsampled by Jakob &
// Hanika 2019 ("A Low-Dimensional Function Space for Efficient Spectral Upsampling", CGF 38(2)):
// s(lambda) = 1/2 + x / (2 sqrt(1 + x^2)), x = c0 lambda^2 + c1 lambda + c2; emission is
// RGB x the D65 illuminant (Mitsuba 3's convention) or a blackbody; a tabulated spectrum carries
// its own RGB. sample() gives the four values a path carries (core/spectrum.h).
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/spectrum.h"

#include <array>
#include <memory>
#include <vector>

namespace refracta {

class Color {
 public:
  enum class Kind {
    kReflectance,  // in [0, 1]: albedos, base colours
    kUnbounded,    // >= 0 without bound: indices of refraction, absorption k, scattering
    kIlluminant,   // emitted radiance: RGB x D65, so that (1, 1, 1) renders as sRGB white
  };

  Color() = default;  // black
  static Color reflectance(const Vec3d& rgb);  // throws std::invalid_argument outside [0, 1]
  static Color unbounded(const Vec3d& rgb);    // throws when negative or not finite
  static Color illuminant(const Vec3d& rgb);   // throws when negative or not finite
  static Color constant(double value, Kind kind) { return kind == Kind::kReflectance ? reflectance(Vec3d::Constant(value)) : kind == Kind::kIlluminant ? illuminant(Vec3d::Constant(value)) : unbounded(Vec3d::Constant(value)); }
  // A measured spectrum: values at increasing wavelengths [nm], linearly interpolated to 1 nm (0
  // outside). rgb(): reflectance/unbounded via XYZ under D65 (normalised by D65's Y), illuminant
  // via the spectrum's own XYZ (normalised by integral y).
  static Color tabulated(const std::vector<double>& lambda_nm, const std::vector<double>& values, Kind kind);
  // Planck's law at temperature [K], scaled so that its luminance Y is `luminance` (an illuminant).
  static Color blackbody(double temperature, double luminance = 1.0);

  // RGB rendering: (r, g, b, 0); spectral: the spectrum at lambda.lambda.
  Spectrum sample(const SampledWavelengths& lambda) const;
  // The spectrum at one wavelength [nm] (0 outside [kLambdaMin, kLambdaMax]). Illuminants:
  // rgb-fit x scale x spectral::d65_normalised (Y of (1, 1, 1) is 1); blackbody: Planck scaled
  // to the asked luminance.
  double evaluate(double lambda_nm) const;
  // Jakob-Hanika coefficients (normalised wavelength, spectral.h) and scale (unbounded/illuminant).
  const std::array<double, 3>& coefficients() const { return coefficients_; }
  double scale() const { return scale_; }
  bool is_tabulated() const { return bool(table_); }
  // Tabulated and blackbody colours: the spectrum at 1 nm steps from spectral::kTableMin (else null).
  const std::vector<double>* table() const { return table_.get(); }
  const Vec3d& rgb() const { return rgb_; }
  Kind kind() const { return kind_; }
  bool is_black() const { return rgb_.maxCoeff() <= 0.0 && !table_; }

 private:
  Kind kind_ = Kind::kReflectance;
  Vec3d rgb_ = Vec3d::Zero();
  std::array<double, 3> coefficients_{0.0, 0.0, -1e9};  // sigmoid polynomial (black)
  double scale_ = 1.0;                                   // unbounded / illuminant: max of the RGB
  std::shared_ptr<const std::vector<double>> table_;     // tabulated: 1 nm steps over [360, 830]
};

// Luminance Y of linear sRGB (IEC 61966-2-1 primaries, D65 white): the second row of the RGB -> XYZ
// matrix.
inline double linear_srgb_luminance(const Vec3d& rgb) {
  return 0.2126 * rgb.x() + 0.7152 * rgb.y() + 0.0722 * rgb.z();
}

// Light given by a spectrum outside the sRGB gamut (a negative channel) as RGB renders take it:
// the negative channels clipped (negative light would subtract) and the rest scaled to keep its
// luminance Y. Clipping alone made a 500-520 nm sun 34 % brighter than its spectrum, and a setting
// sun's (negative blue) light on a wall disagreed with the spectral render (a trial).
Vec3d clip_keeping_luminance(const Vec3d& rgb);

// A reflectance given as RGB at render time (a texel) to its spectral values at lambda; RGB
// rendering returns (r, g, b, 0). Fast: served from a precomputed coefficient table
// (spectral::rgb_to_spectrum_table, built once on first use, ~0.2 s); rgb clamped to [0, 1].
Spectrum reflectance_spectrum(const Vec3d& rgb, const SampledWavelengths& lambda);

// Spectral radiance samples to linear sRGB (CIE 1931 2-degree observer, D65 white, IEC
// 61966-2-1 matrix), the Monte Carlo estimate over the path's wavelengths:
// XYZ = (1/4) sum_i L_i cmf(lambda_i) / pdf_i / integral(y), terminated wavelengths (pdf 0)
// contributing nothing; RGB rendering returns the first three channels.
Vec3d to_linear_srgb(const Spectrum& radiance, const SampledWavelengths& lambda);

}  // namespace refracta
