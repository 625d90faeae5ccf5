// Display settings by name (display.h).
#include "refracta/shading/display.h"

#include "refracta/core/error.h"
#include "refracta/scene/image_io.h"

namespace refracta {

const char* tonemap_name(Tonemap tonemap) {
  switch (tonemap) {
    case Tonemap::kLinear: return "linear";
    case Tonemap::kFilm: return "film";
    case Tonemap::kReinhard: return "reinhard";
    case Tonemap::kAces: return "aces";
  }
  return "aces";
}

void set_gamma(DisplaySettings& settings, const GammaName& gamma) {
  if (const double* g = std::get_if<double>(&gamma)) {
    settings.transfer = Transfer::kGamma, settings.gamma = *g;
  } else if (const std::string& name = std::get<std::string>(gamma); name == "srgb") {
    settings.transfer = Transfer::kSrgb;
  } else if (name == "linear") {
    settings.transfer = Transfer::kGamma, settings.gamma = 1.0;
  } else {
    throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3] (got '", name, "')");
  }
}

GammaName gamma_name(const DisplaySettings& settings) {
  if (settings.transfer == Transfer::kSrgb) return std::string("srgb");
  return settings.gamma;
}

void write_display_image(const std::string& path, Image image, const DisplaySettings& settings) {
  if (is_float_format(path)) {
    expose_linear(image, settings);
    write_image(path, image);
    return;
  }
  tonemap_image(image, settings);
  std::string colour_space = "sRGB";
  if (settings.transfer == Transfer::kGamma) {
    colour_space = settings.gamma == 1.0 ? "linear" : concat("GammaCorrected", settings.gamma);
  }
  write_image(path, image, colour_space);
}

}  // namespace refracta
