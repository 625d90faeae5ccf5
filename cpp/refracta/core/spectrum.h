// The quantity light transport carries: four values per path. In RGB rendering they are linear
// sRGB (r, g, b) and a fourth, unused, channel; in spectral rendering they are the values at four
// hero wavelengths (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling", EGSR). One
// integrator serves both (as pbrt-v4's SampledSpectrum / SampledWavelengths).
#pragma once

#include <Eigen/Core>

#include "refracta/core/error.h"

namespace refracta {

using Spectrum = Eigen::Array4d;

constexpr int kSpectrumSamples = 4;
constexpr double kLambdaMin = 360.0;  // [nm] the sampled range of spectral rendering
constexpr double kLambdaMax = 830.0;  // [nm]
// The largest radiance (or radiance scale) a light may be given: images are float32 (3.4e38 at
// most) and an estimator sums and weights its samples, so a larger one fills pixels with inf.
constexpr double kMaxRadiance = 1e30;

// lambda_nm itself; throws (ValueError) naming `what` unless it lies in the rendered range.
inline double checked_wavelength(double lambda_nm, const char* what) {
  if (!(lambda_nm >= kLambdaMin && lambda_nm <= kLambdaMax)) {
    throw_invalid(what, " must be in [", kLambdaMin, ", ", kLambdaMax, "] nm (got ", lambda_nm, ")");
  }
  return lambda_nm;
}

struct SampledWavelengths {
  bool spectral = false;
  Eigen::Array4d lambda = Eigen::Array4d::Zero();  // [nm], spectral only
  Eigen::Array4d pdf = Eigen::Array4d::Ones();     // [1/nm] per wavelength; 0 once terminated

  // RGB rendering: the four channels are (r, g, b, unused).
  static SampledWavelengths rgb() { return {}; }
  // The hero wavelength from u uniform in [kLambdaMin, kLambdaMax], the others rotated by a
  // quarter of the range each (wrapping around), every one with pdf 1/(max - min).
  static SampledWavelengths sample_uniform(double u) {
    SampledWavelengths w;
    w.spectral = true;
    const double range = kLambdaMax - kLambdaMin;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      double l = kLambdaMin + range * u + i * range / kSpectrumSamples;
      if (l > kLambdaMax) l -= range;
      w.lambda[i] = l;
    }
    w.pdf.setConstant(1.0 / range);
    return w;
  }
  double hero() const { return lambda[0]; }
  // Keep only the hero wavelength (a dispersive interface or dispersive air: the path is the
  // hero's alone). Its estimate is then weighted by the number of wavelengths it stands for.
  void terminate_secondary() {
    if (!spectral || secondary_terminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) pdf[i] = 0.0;
    pdf[0] /= kSpectrumSamples;
  }
  bool secondary_terminated() const { return spectral && pdf[1] == 0.0; }
};

}  // namespace refracta
