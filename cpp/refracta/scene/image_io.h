// Reading and writing image files through OpenImageIO (the only file that includes it).
#pragma once

#include "refracta/core/image.h"

#include <string>

namespace refracta {

// True for formats that keep linear floating point (EXR, HDR, PFM, TIFF).
bool is_float_format(const std::string& path);
// Writes pixels as they are: float formats keep them, others are quantised to 8 bits by OIIO
// (so encode them for display first). Throws IoError with OIIO's message.
void write_image(const std::string& path, const Image& image);
// Any format OIIO reads, as float in the file's channel count. Throws IoError.
Image read_image(const std::string& path);

}  // namespace refracta
