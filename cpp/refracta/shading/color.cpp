// Colours for RGB and spectral rendering (color.h). RGB path only so far: the spectral path
// (Jakob-Hanika upsampling, CIE tables) is being written.
#include "refracta/shading/color.h"

#include "refracta/core/error.h"

#include <cmath>
#include <stdexcept>

namespace refracta {

namespace {

void check_rgb(const Vec3d& rgb, const char* what, bool bounded) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0 || (bounded && rgb[i] > 1.0)) {
      throw_invalid(what, " must be finite and in ", bounded ? "[0, 1]" : "[0, inf)", " (got ", rgb[i], ")");
    }
  }
}

[[noreturn]] void spectral_missing() { throw std::logic_error("spectral colours are not available yet"); }

}  // namespace

Color Color::reflectance(const Vec3d& rgb) {
  check_rgb(rgb, "reflectance", true);
  Color c;
  c.kind_ = Kind::kReflectance;
  c.rgb_ = rgb;
  return c;
}

Color Color::unbounded(const Vec3d& rgb) {
  check_rgb(rgb, "value", false);
  Color c;
  c.kind_ = Kind::kUnbounded;
  c.rgb_ = rgb;
  return c;
}

Color Color::illuminant(const Vec3d& rgb) {
  check_rgb(rgb, "emission", false);
  Color c;
  c.kind_ = Kind::kIlluminant;
  c.rgb_ = rgb;
  return c;
}

Color Color::tabulated(const std::vector<double>&, const std::vector<double>&, Kind) { spectral_missing(); }
Color Color::blackbody(double, double) { spectral_missing(); }

Spectrum Color::sample(const SampledWavelengths& lambda) const {
  if (lambda.spectral) spectral_missing();
  return Spectrum(rgb_.x(), rgb_.y(), rgb_.z(), 0.0);
}

Spectrum reflectance_spectrum(const Vec3d& rgb, const SampledWavelengths& lambda) {
  if (lambda.spectral) spectral_missing();
  return Spectrum(rgb.x(), rgb.y(), rgb.z(), 0.0);
}

Vec3d to_linear_srgb(const Spectrum& radiance, const SampledWavelengths& lambda) {
  if (lambda.spectral) spectral_missing();
  return radiance.head<3>().matrix();
}

}  // namespace refracta
