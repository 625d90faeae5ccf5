// Display settings by name (display.h).
#include "refracta/shading/display.h"

#include "refracta/core/error.h"

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

}  // namespace refracta
