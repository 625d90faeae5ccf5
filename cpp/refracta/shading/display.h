// Display settings as users name them (io.write_image, io.to_display, io.exposure_of): the tone
// curve and transfer by name, the exposure fields as given. DisplaySettings (tonemap.h) is what
// the pipeline runs on; this turns the names into it.
#pragma once

#include "refracta/shading/tonemap.h"

#include <optional>
#include <string>
#include <variant>

namespace refracta {

struct DisplayNames {
  // Unset: DisplaySettings' own defaults (automatic exposure, luminous efficacy 683).
  std::optional<double> exposure, ev100, iso, shutter, f_number, key, white, luminous_efficacy;
  std::optional<std::string> tonemap;  // "aces", "reinhard", "linear", "film"; unset: DisplaySettings' curve
  // "srgb" (the IEC 61966-2-1 curve), "linear" (gamma 1) or a gamma g in [1, 3] (p = l^(1/g)).
  std::variant<std::string, double> gamma = std::string("srgb");
};

// Validated settings (std::invalid_argument listing every problem).
DisplaySettings display_settings(const DisplayNames& names);

}  // namespace refracta
