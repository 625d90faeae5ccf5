// Image files through OpenImageIO.
#include "refracta/scene/image_io.h"

#include "refracta/core/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

namespace refracta {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The kind of file at `path` (not_found when nothing is there); IoError naming `doing` and the
// system's reason when it cannot be told (a name too long, a folder without permission).
std::filesystem::file_type file_type_at(const std::string& path, const char* doing) {
  check_path_text(path);
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error && status.type() != std::filesystem::file_type::not_found) {
    throw IoError(concat("cannot ", doing, " '", path, "': ", error.message()));
  }
  return status.type();
}

}  // namespace

void check_path_text(const std::string& path) {
  const size_t nul = path.find('\0');
  if (nul != std::string::npos) {
    throw_invalid("path '", path.substr(0, nul), "\\0", path.substr(nul + 1), "' holds a NUL byte (character ", nul,
                  "): no file is named so");
  }
}

void check_readable(const std::string& path) {
  const std::filesystem::file_type type = file_type_at(path, "read");
  if (type == std::filesystem::file_type::not_found) throw MissingFile(concat("no such image file: '", path, "'"));
  if (type != std::filesystem::file_type::regular) throw IoError(concat("cannot read '", path, "': not a regular file"));
}

// Chunks: 4-byte big-endian length, 4-byte type, data, 4-byte CRC (PNG specification, 5.3).
void check_png_complete(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8];
  if (!file.read(reinterpret_cast<char*>(head), 8) || !std::equal(head, head + 8, signature)) return;  // no PNG
  const std::uintmax_t size = std::filesystem::file_size(path);
  std::uintmax_t at = 8;
  while (true) {
    if (!file.read(reinterpret_cast<char*>(head), 8)) break;
    const std::uintmax_t length = (std::uintmax_t(head[0]) << 24) | (head[1] << 16) | (head[2] << 8) | head[3];
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    at += 12 + length;
    if (at > size) {
      throw IoError(concat("cannot read '", path, "' (damaged or truncated?): it ends inside its ", type, " chunk, ",
                           at - size, " bytes short"));
    }
    if (type == "IEND") return;
    file.seekg(std::streamoff(length + 4), std::ios::cur);
  }
  throw IoError(concat("cannot read '", path, "' (damaged or truncated?): it ends before its IEND chunk"));
}

void check_writable(const std::string& path) {
  const std::filesystem::file_type type = file_type_at(path, "write");
  if (type != std::filesystem::file_type::not_found && type != std::filesystem::file_type::regular) {
    throw IoError(concat("cannot write '", path, "': not a regular file"));
  }
}

bool is_float_format(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".tif" || ext == ".tiff";
}

bool keeps_negative_values(const std::string& path) { return extension(path) != ".hdr"; }

void check_image_format(const std::string& path) {
  if (!OIIO::ImageOutput::create(path)) throw IoError(concat("cannot write '", path, "': ", OIIO::geterror()));
}

namespace {

// OpenJPEG's default of 6 resolution levels needs 2^5 pixels a side: OIIO 2.4 wrote a smaller
// image as a 77-byte header and reported success.
constexpr int kSmallestJpeg2000Side = 32;

// `image` without its alpha (the last of 2 or 4 channels).
Image without_alpha(const Image& image) {
  Image out(image.width, image.height, image.channels - 1);
  const size_t count = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < count; ++i) {
    std::copy_n(&image.pixels[i * image.channels], out.channels, &out.pixels[i * out.channels]);
  }
  return out;
}

// OIIO 2.4's WebP writer divides the colour by alpha (in a 2.2-gamma approximation of linear
// light) whatever oiio:UnassociatedAlpha says, taking its input as premultiplied: a straight 0.5
// grey at alpha 0.5 was stored as white. Multiplying by alpha^(1/2.2) first undoes that.
Image premultiplied_for_webp(Image image) {
  constexpr double kWriterGamma = 2.2;
  const size_t count = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < count; ++i) {
    float* p = &image.pixels[i * image.channels];
    const float scale = float(std::pow(std::clamp(double(p[3]), 0.0, 1.0), 1.0 / kWriterGamma));
    for (int c = 0; c < 3; ++c) p[c] *= scale;
  }
  return image;
}

}  // namespace

void write_image(const std::string& path, const Image& given, const std::string& colour_space) {
  if (given.width < 1 || given.height < 1) throw_invalid("write_image: the image is empty");
  check_writable(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw IoError(concat("cannot write '", path, "': ", OIIO::geterror()));
  const std::string format_name = out->format_name();
  if (format_name == "jpeg2000" && std::min(given.width, given.height) < kSmallestJpeg2000Side) {
    throw_invalid("write_image: JPEG 2000 needs at least ", kSmallestJpeg2000Side, " pixels a side (got ", given.width,
                  " x ", given.height, "): write a PNG or an EXR");
  }
  // Alpha goes where the format keeps it: a format without (JPEG) gets the colour alone (its
  // writer stored a grey image's alpha as a second colour channel: green).
  const bool alpha = given.channels == 2 || given.channels == 4;
  std::optional<Image> adapted;
  if (alpha && !out->supports("alpha")) adapted = without_alpha(given);
  if (given.channels == 4 && format_name == "webp") adapted = premultiplied_for_webp(given);
  const Image& image = adapted ? *adapted : given;
  const OIIO::TypeDesc format = is_float_format(path) ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(image.width, image.height, image.channels, format);
  // Colours are not premultiplied by alpha (to_display's are what a PNG stores): OIIO would divide
  // them by it for formats that store straight alpha (a 0.5-alpha pixel's 231 became 255).
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!colour_space.empty()) spec.attribute("oiio:ColorSpace", colour_space);
  if (!out->open(path, spec)) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  if (!out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  }
  if (!out->close()) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
}

void write_image_channels(const std::string& path, const Image& image, const std::vector<std::string>& names) {
  if (image.width < 1 || image.height < 1) throw_invalid("write_image_channels: the image is empty");
  if (int(names.size()) != image.channels) {
    throw_invalid("write_image_channels: ", names.size(), " channel names for ", image.channels, " channels");
  }
  if (!is_float_format(path)) throw_invalid("write_layers: '", path, "' must be a float format (.exr)");
  // OpenEXR keeps at most 255 bytes of a channel's name: it cut longer ones, and two layers whose
  // names began alike became one channel. A name given twice would be one channel too.
  constexpr size_t kLongestChannelName = 255;
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (name.empty() || name.size() > kLongestChannelName) {
      throw_invalid("write_layers: a channel name must hold 1 to ", kLongestChannelName, " bytes, as EXR stores it (got ",
                    name.size(), ": '", name.substr(0, 40), name.size() > 40 ? "...'" : "'", ")");
    }
    if (!seen.insert(name).second) throw_invalid("write_layers: channel name '", name, "' given twice");
  }
  check_writable(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw IoError(concat("cannot write '", path, "': ", OIIO::geterror()));
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = -1;  // no channel is alpha: readouts are not premultiplied by anything
  if (!out->open(path, spec)) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  if (!out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  }
  if (!out->close()) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
}

std::vector<std::string> read_channel_names(const std::string& path) {
  check_readable(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw IoError(concat("cannot read '", path, "': ", OIIO::geterror()));
  std::vector<std::string> names = in->spec().channelnames;
  in->close();
  return names;
}

namespace {

// A reader's message of a file that ended before its pixels did: libjpeg's premature end, a TIFF
// strip read short, PNG's and OpenEXR's end of file.
bool reports_truncation(const std::string& message) {
  for (const char* sign : {"Premature end", "Read error", "failed reading", "end of file", "End of file"}) {
    if (message.find(sign) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

Image read_image(const std::string& path) {
  check_readable(path);
  check_png_complete(path);
  // Values as stored: a PNG's colours straight, not premultiplied by its alpha (write_image's).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw IoError(concat("cannot read '", path, "': ", OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) {
    throw IoError(concat("cannot read '", path, "': its header gives ", spec.width, " x ", spec.height, " pixels of ",
                         spec.nchannels, " channels"));
  }
  try {  // a header claiming a huge image (a damaged or hostile file) is refused before allocating
    check_image_memory(spec.width, spec.height, 4.0 * spec.nchannels, concat("read_image '", path, "'").c_str());
  } catch (const std::invalid_argument& error) {
    throw IoError(error.what());
  }
  Image image(spec.width, spec.height, spec.nchannels);
  // A truncated JPEG or TIFF reads "successfully", its missing rows grey or black, and reports
  // the damage only as an error message: refused as well. (OIIO reports libjpeg's warnings as
  // errors too -- "unknown JFIF revision number", "extraneous bytes before marker" on files any
  // viewer shows -- so only the messages of a file that ended early refuse it.)
  const bool read = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data());
  const std::string trouble = in->has_error() ? in->geterror() : std::string();
  if (!read || reports_truncation(trouble)) {
    throw IoError(concat("cannot read '", path, "' (damaged or truncated?): ", trouble));
  }
  // OIIO 2.4's WebP reader multiplies the colour by alpha whatever oiio:UnassociatedAlpha asks
  // (0.5 grey at alpha 0.5 read 0.25): divided back, as every other format reads straight.
  if (std::string(in->format_name()) == "webp" && image.channels == 4) {
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
      const float a = image.pixels[i + 3];
      if (!(a > 0.0f)) continue;  // no colour to recover under alpha 0
      for (int c = 0; c < 3; ++c) image.pixels[i + c] = std::min(image.pixels[i + c] / a, 1.0f);
    }
  }
  in->close();
  return image;
}

double stored_gamma(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw IoError(concat("cannot read '", path, "': ", OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  const OIIO::TypeDesc::BASETYPE stored = OIIO::TypeDesc::BASETYPE(spec.format.basetype);
  if (stored != OIIO::TypeDesc::UINT8 && stored != OIIO::TypeDesc::UINT16) return 1.0;
  // OIIO names a PNG's gAMA chunk (a TGA's gamma) "GammaCorrected<g>" or "Gamma<g>" with oiio:Gamma
  // g, and a gAMA of 1 "linear"; the sRGB chunk, or no word at all, leaves the convention.
  std::string space = spec.get_string_attribute("oiio:ColorSpace");
  std::transform(space.begin(), space.end(), space.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (space == "linear") return 1.0;
  const double gamma = spec.get_float_attribute("oiio:Gamma", 0.0);
  if (space.rfind("gamma", 0) == 0 && gamma > 0.0 && std::isfinite(gamma)) return gamma;
  return 0.0;
}

}  // namespace refracta
