// Display settings as users name them (io.write_image, io.to_display, io.exposure_of, the bound
// refracta.DisplaySettings): the tone curve and the transfer curve by name.
#pragma once

#include "refracta/shading/tonemap.h"

#include <optional>
#include <string>
#include <variant>

namespace refracta {

const char* tonemap_name(Tonemap tonemap);  // "linear", "film", "reinhard", "aces" (parse_tonemap's)

// The transfer curve: "srgb" (the IEC 61966-2-1 curve), "linear" (gamma 1) or a gamma g in [1, 3]
// (p = l^(1/g)); read back as "srgb" or g.
using GammaName = std::variant<std::string, double>;
void set_gamma(DisplaySettings& settings, const GammaName& gamma);  // std::invalid_argument for another name
GammaName gamma_name(const DisplaySettings& settings);

}  // namespace refracta
