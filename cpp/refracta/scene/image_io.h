// Reading and writing image files through OpenImageIO (the only file that includes it).
#pragma once

#include "refracta/core/image.h"

#include <string>
#include <vector>

namespace refracta {

// ValueError for a path holding a NUL byte: the C library would read it as the path's end and open
// another file ('a\0b.exr' wrote 'a'), where Python's open() refuses ("embedded null byte").
void check_path_text(const std::string& path);
// IoError unless `path` is a regular file ("no such image file", "not a regular file"): OIIO's
// readers spin on a FIFO or a device such as /dev/zero, so they are refused before opening.
void check_readable(const std::string& path);
// IoError when `path` is a PNG file that ends before its IEND chunk (a write or a download cut
// short); other files pass. libpng prints its own "libpng error: ..." to stderr for such a file,
// in a reader OpenImageIO gives no way to quiet, so the readers refuse it before OpenImageIO opens it.
void check_png_complete(const std::string& path);
// IoError if `path` exists and is not a regular file: opening a FIFO to write waits for a reader
// that may never come, so writers refuse it (and devices, folders) before opening.
void check_writable(const std::string& path);
// True for formats that keep linear floating point (EXR, HDR, PFM, TIFF).
bool is_float_format(const std::string& path);
// False for Radiance HDR, whose RGBE floats have no sign: its writer stores negative values
// (spectral renders hold some) as 0.
bool keeps_negative_values(const std::string& path);
// Writes pixels as they are: float formats keep them, others are quantised to 8 bits by OIIO
// (so encode them for display first). `colour_space`, if given, is stored as the file's colour
// space (OIIO's oiio:ColorSpace: "sRGB" gives a PNG its sRGB chunk, "linear" or
// "GammaCorrected<g>" its gAMA chunk). Throws IoError with OIIO's message.
void write_image(const std::string& path, const Image& image, const std::string& colour_space = "");
// Throws IoError (OIIO's message) unless OIIO has a writer for path's format (its extension):
// checked before work whose result goes to that file.
void check_image_format(const std::string& path);
// Any format OIIO reads, as float in the file's channel count. Throws IoError.
Image read_image(const std::string& path);
// How the file encodes colour, for decoding it to linear values (textures, environment maps,
// read_image(linear=True)): 1 for linear values (float files; 8- and 16-bit files whose header
// says linear, as write_image's gamma='linear' PNGs do), g for a power law v = c^(1/g) the header
// names (a PNG's gAMA chunk: gamma=2.2), 0 for sRGB (8- and 16-bit files by convention).
// Throws IoError.
double stored_gamma(const std::string& path);
// A float file (EXR: layers by channel name, e.g. "R", "G", "B", "distance.Y", "position.X") with
// one name per channel, the pixels as they are. Throws IoError, std::invalid_argument.
void write_image_channels(const std::string& path, const Image& image, const std::vector<std::string>& names);
// The channel names of an image file (OIIO's). Throws IoError.
std::vector<std::string> read_channel_names(const std::string& path);

}  // namespace refracta
