// Closed-form columns and the RGB of node spectra (air_optics.h).
#include "refracta/shading/air_optics.h"

#include "refracta/shading/spectral.h"

#include <vector>

namespace refracta::air_optics {

namespace {

// The mean of e^(-h/H) over heights linear from h0 to h1: e^(-h0/H) (1 - e^(-x)) / x, x = (h1 - h0)/H.
double mean_exponential(double h0, double h1, double scale_height) {
  const double x = (h1 - h0) / scale_height;
  const double factor = std::abs(x) < 1e-6 ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
  return std::exp(-h0 / scale_height) * factor;
}

// The integral of the ozone tent over heights from 0 to h [m].
double tent_integral(double h) {
  const double lo = kOzonePeak - kOzoneHalfWidth, hi = kOzonePeak + kOzoneHalfWidth;
  const double x = std::clamp(h, lo, hi);
  if (x <= kOzonePeak) return 0.5 * (x - lo) * (x - lo) / kOzoneHalfWidth;
  return 0.5 * kOzoneHalfWidth + (x - kOzonePeak) - 0.5 * (x - kOzonePeak) * (x - kOzonePeak) / kOzoneHalfWidth;
}

}  // namespace

Column column_along(double h0, double h1, double length) {
  Column c;
  c.r = length * mean_exponential(h0, h1, kRayleighHeight);
  c.m = length * mean_exponential(h0, h1, kMieHeight);
  c.o = std::abs(h1 - h0) < 1e-3 ? length * densities(0.5 * (h0 + h1)).o
                                 : length * (tent_integral(h1) - tent_integral(h0)) / (h1 - h0);
  return c;
}

Vec3d rgb_of_nodes(const double* values) {
  std::vector<double> fine(spectral::kTableSamples);
  for (int i = 0; i < spectral::kTableSamples; ++i) fine[i] = lerp_nodes(values, spectral::kTableMin + i);
  return spectral::xyz_to_linear_srgb(spectral::xyz_of_radiance(fine));
}

}  // namespace refracta::air_optics
