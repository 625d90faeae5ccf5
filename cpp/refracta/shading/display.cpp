// Display settings from names (display.h).
#include "refracta/shading/display.h"

#include "refracta/core/error.h"

namespace refracta {

DisplaySettings display_settings(const DisplayNames& names) {
  DisplaySettings settings;
  settings.exposure = names.exposure, settings.ev100 = names.ev100;
  settings.iso = names.iso, settings.shutter = names.shutter, settings.f_number = names.f_number;
  if (names.luminous_efficacy) settings.luminous_efficacy = *names.luminous_efficacy;
  if (names.tonemap) settings.tonemap = parse_tonemap(*names.tonemap);
  settings.key = names.key, settings.white = names.white;
  if (const double* gamma = std::get_if<double>(&names.gamma)) {
    settings.transfer = Transfer::kGamma, settings.gamma = *gamma;
  } else if (const std::string& name = std::get<std::string>(names.gamma); name == "srgb") {
    settings.transfer = Transfer::kSrgb;
  } else if (name == "linear") {
    settings.transfer = Transfer::kGamma, settings.gamma = 1.0;
  } else {
    throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3] (got '", name, "')");
  }
  settings.validate();
  return settings;
}

}  // namespace refracta
