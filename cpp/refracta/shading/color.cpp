// Colours for RGB and spectral rendering (color.h): Jakob-Hanika upsampling of reflectances,
// RGB x D65 emission, tabulated spectra and black bodies, and the spectral -> sRGB estimate.
// The colour science (CIE tables, fits, the coefficient table) lives in spectral.h/.cpp.
//
// The texture table (spectral::rgb_to_spectrum_table): 32 nodes per axis, fits on a 5 nm
// quadrature, 2 Gauss-Newton polish steps per lookup. Measured with
// refracta.spectrum._measure_table (20000 uniform random colours in [0, 1]^3, round trip = max
// |RGB(spectrum(rgb)) - rgb| with the 1 nm CIE integral; build time on 2 shared cores):
//   res 32, no polish:   build 0.17 s, max 3.5e-3, mean 8.5e-4, lookup 0.1 us
//   res 64, no polish:   build 1.7 s,  max 7.6e-4, mean 2.1e-4
//   res 16, 2 steps:     build 0.03 s, max 2.3e-3 (a poor start near white)
//   res 24, 2 steps:     build 0.08 s, max 7.9e-5
//   res 32, 1 step:      build 0.17 s, max 1.1e-3, mean 4e-6, lookup 0.7 us
//   res 32, 2 steps:     build 0.17 s, max 7.0e-5, mean 1.9e-6, lookup 1.3 us   <- chosen
//   res 32, 2 steps at 1 nm: build 0.65 s, max 5.4e-5, lookup 3 us
// Interpolated coefficients alone miss 1e-3 below res ~64 (whose build exceeds 1 s): the
// coefficients grow like 1/sqrt(distance) to the gamut's walls. Two polish steps at 5 nm cost
// ~1.3 us per lookup and bring the error 14x under the 1e-3 target.
#include "refracta/shading/color.h"

#include "refracta/core/error.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

void check_rgb(const Vec3d& rgb, const char* what, bool bounded) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0 || (bounded && rgb[i] > 1.0)) {
      throw_invalid(what, " must be finite and in ", bounded ? "[0, 1]" : "[0, inf)", " (got ", rgb[i], ")");
    }
  }
}

constexpr std::array<double, 3> kBlack{0.0, 0.0, -std::numeric_limits<double>::infinity()};

// pbrt-v4 RGBUnboundedSpectrum: scale = 2 max(rgb), the fit of rgb / scale (largest component 1/2,
// well inside the sigmoid's range).
void fit_scaled(const Vec3d& rgb, std::array<double, 3>* coefficients, double* scale) {
  const double m = rgb.maxCoeff();
  if (m <= 0.0) {
    *coefficients = kBlack, *scale = 0.0;
    return;
  }
  *scale = 2.0 * m;
  *coefficients = spectral::fit_reflectance_robust(rgb / *scale).c;
}

double lerp_1nm(const std::vector<double>& table, double lambda_nm) {
  if (!(lambda_nm >= spectral::kTableMin && lambda_nm <= spectral::kTableMax)) return 0.0;
  const double x = lambda_nm - spectral::kTableMin;
  const int i = std::min(int(x), spectral::kTableSamples - 2);
  const double t = x - i;
  return table[i] * (1.0 - t) + table[i + 1] * t;
}

}  // namespace

Color Color::reflectance(const Vec3d& rgb) {
  check_rgb(rgb, "reflectance", true);
  Color c;
  c.kind_ = Kind::kReflectance;
  c.rgb_ = rgb;
  c.coefficients_ = rgb.maxCoeff() <= 0.0 ? kBlack : spectral::fit_reflectance_robust(rgb).c;
  return c;
}

Color Color::unbounded(const Vec3d& rgb) {
  check_rgb(rgb, "value", false);
  Color c;
  c.kind_ = Kind::kUnbounded;
  c.rgb_ = rgb;
  fit_scaled(rgb, &c.coefficients_, &c.scale_);
  return c;
}

Color Color::illuminant(const Vec3d& rgb) {
  check_rgb(rgb, "emission", false);
  Color c;
  c.kind_ = Kind::kIlluminant;
  c.rgb_ = rgb;
  fit_scaled(rgb, &c.coefficients_, &c.scale_);
  return c;
}

Color Color::tabulated(const std::vector<double>& lambda_nm, const std::vector<double>& values, Kind kind) {
  if (lambda_nm.size() != values.size() || lambda_nm.empty()) {
    throw_invalid("tabulated: wavelengths and values must have the same, non-zero length (got ", lambda_nm.size(),
                  " and ", values.size(), ")");
  }
  for (size_t i = 0; i < lambda_nm.size(); ++i) {
    if (!std::isfinite(lambda_nm[i]) || !(lambda_nm[i] > 0.0) || (i > 0 && !(lambda_nm[i] > lambda_nm[i - 1]))) {
      throw_invalid("tabulated: wavelengths must be finite, > 0 nm and increasing (got ", lambda_nm[i], " at ", i, ")");
    }
    // An illuminant at most kMaxRadiance, as an RGB one (a sun of 1e300 per nm rendered inf).
    const double most = kind == Kind::kReflectance ? 1.0 : kMaxRadiance;
    if (!std::isfinite(values[i]) || values[i] < 0.0 || values[i] > most) {
      throw_invalid("tabulated: values must be finite and in [0, ", most, "] (got ", values[i], " at ", lambda_nm[i],
                    " nm)");
    }
  }
  if (lambda_nm.back() <= spectral::kTableMin || lambda_nm.front() >= spectral::kTableMax) {  // touching: black too
    throw_invalid("tabulated: wavelengths ", lambda_nm.front(), "-", lambda_nm.back(), " nm lie outside the rendered ",
                  spectral::kTableMin, "-", spectral::kTableMax, " nm: the spectrum would be black");
  }
  // Resample to the 1 nm grid: linear between samples, 0 outside them (one sample: a spike of
  // zero width, i.e. black, unless it falls on the grid).
  auto table = std::make_shared<std::vector<double>>(spectral::kTableSamples, 0.0);
  for (int i = 0; i < spectral::kTableSamples; ++i) {
    const double l = spectral::kTableMin + i;
    if (l < lambda_nm.front() || l > lambda_nm.back()) continue;
    const size_t k = size_t(std::upper_bound(lambda_nm.begin(), lambda_nm.end(), l) - lambda_nm.begin());
    if (k >= lambda_nm.size()) {
      (*table)[i] = values.back();
    } else {
      const double t = (l - lambda_nm[k - 1]) / (lambda_nm[k] - lambda_nm[k - 1]);
      (*table)[i] = values[k - 1] * (1.0 - t) + values[k] * t;
    }
  }
  if (std::all_of(table->begin(), table->end(), [](double v) { return v == 0.0; }) &&
      std::any_of(values.begin(), values.end(), [](double v) { return v > 0.0; })) {
    bool inside = false;  // light at a sample within the rendered range, yet none on its grid
    for (size_t i = 0; i < values.size(); ++i) {
      const bool rendered = lambda_nm[i] >= spectral::kTableMin && lambda_nm[i] <= spectral::kTableMax;
      inside = inside || (values[i] > 0.0 && rendered);
    }
    if (inside) {
      throw_invalid("tabulated: the spectrum's light lies between the 1 nm grid's wavelengths (samples at ",
                    lambda_nm.front(), "-", lambda_nm.back(), " nm): it would be black; give samples on whole nm, ",
                    "or a band at least 1 nm wide");
    }
    throw_invalid("tabulated: the spectrum's light lies outside the rendered ", spectral::kTableMin, "-",
                  spectral::kTableMax, " nm: the spectrum would be black");
  }
  Color c;
  c.kind_ = kind;
  // Reflectance-like (reflectance, unbounded) under D65; emission as radiance.
  const Vec3d xyz = kind == Kind::kIlluminant ? spectral::xyz_of_radiance(*table) : spectral::xyz_of_reflectance(*table);
  c.rgb_ = spectral::xyz_to_linear_srgb(xyz);
  c.table_ = table;
  return c;
}

Color Color::blackbody(double temperature, double luminance) {
  spectral::checked_temperature(temperature, "blackbody: temperature");
  if (!(luminance >= 0.0) || !std::isfinite(luminance)) throw_invalid("blackbody: luminance must be >= 0 (got ", luminance, ")");
  std::vector<double> values(spectral::kTableSamples);
  for (int i = 0; i < spectral::kTableSamples; ++i) values[i] = spectral::planck(spectral::kTableMin + i, temperature);
  const double y = spectral::xyz_of_radiance(values).y();
  if (!(y > 0.0)) throw_invalid("blackbody: temperature ", temperature, " K emits nothing visible");
  for (double& v : values) v *= luminance / y;
  Color c;
  c.kind_ = Kind::kIlluminant;
  c.table_ = std::make_shared<std::vector<double>>(std::move(values));
  c.rgb_ = spectral::xyz_to_linear_srgb(spectral::xyz_of_radiance(*c.table_));
  return c;
}

double Color::evaluate(double lambda_nm) const {
  if (table_) return lerp_1nm(*table_, lambda_nm);
  if (!(lambda_nm >= spectral::kTableMin && lambda_nm <= spectral::kTableMax)) return 0.0;
  const double s = spectral::sigmoid_polynomial(coefficients_, lambda_nm);
  switch (kind_) {
    case Kind::kReflectance: return s;
    case Kind::kUnbounded: return scale_ * s;
    case Kind::kIlluminant: return scale_ * s * spectral::d65_normalised(lambda_nm);
  }
  return 0.0;
}

Spectrum Color::sample(const SampledWavelengths& lambda) const {
  if (!lambda.spectral) {
    const Vec3d rgb = table_ ? clip_keeping_luminance(rgb_) : rgb_;
    return Spectrum(rgb.x(), rgb.y(), rgb.z(), 0.0);
  }
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = evaluate(lambda.lambda[i]);
  return s;
}

Vec3d clip_keeping_luminance(const Vec3d& rgb) {
  if (rgb.minCoeff() >= 0.0) return rgb;
  const Vec3d clipped = rgb.cwiseMax(0.0);
  const double y = linear_srgb_luminance(rgb), y_clipped = linear_srgb_luminance(clipped);
  // Clipping only adds luminance: the scale is at most 1 (0 where the light had none to keep).
  return y_clipped > 0.0 ? Vec3d(clipped * (std::max(y, 0.0) / y_clipped)) : clipped;
}

Spectrum reflectance_spectrum(const Vec3d& rgb, const SampledWavelengths& lambda) {
  if (!lambda.spectral) return Spectrum(rgb.x(), rgb.y(), rgb.z(), 0.0);
  const spectral::Coefficients c = spectral::rgb_to_spectrum_table().coefficients(rgb);
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = spectral::sigmoid_polynomial(c, lambda.lambda[i]);
  return s;
}

Vec3d to_linear_srgb(const Spectrum& radiance, const SampledWavelengths& lambda) {
  if (!lambda.spectral) return radiance.head<3>().matrix();
  Vec3d xyz = Vec3d::Zero();
  for (int i = 0; i < kSpectrumSamples; ++i) {
    if (!(lambda.pdf[i] > 0.0)) continue;  // a terminated wavelength
    xyz += radiance[i] / lambda.pdf[i] * spectral::cie_xyz(lambda.lambda[i]);
  }
  xyz /= kSpectrumSamples * spectral::cie_y_integral();
  return spectral::xyz_to_linear_srgb(xyz);
}

}  // namespace refracta
