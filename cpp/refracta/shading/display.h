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

// io.write_image: a float format (is_float_format) gets the image linear times the manual
// exposure (expose_linear; display_only_fields_set names the settings it leaves unused), any
// other the image tone mapped and encoded (tonemap_image), tagged with its transfer curve's
// colour space (sRGB, linear or a gamma) so that viewers that read it need not assume one.
// Throws IoError, std::invalid_argument.
void write_display_image(const std::string& path, Image image, const DisplaySettings& settings);

}  // namespace refracta
