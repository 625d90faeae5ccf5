// Image files through OpenImageIO.
#include "refracta/scene/image_io.h"

#include "refracta/core/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace refracta {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_float_format(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".tif" || ext == ".tiff";
}

void write_image(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1) throw_invalid("write_image: the image is empty");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw IoError(concat("cannot write '", path, "': ", OIIO::geterror()));
  const OIIO::TypeDesc format = is_float_format(path) ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(image.width, image.height, image.channels, format);
  if (!out->open(path, spec)) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  if (!out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw IoError(concat("cannot write '", path, "': ", out->geterror()));
  }
  if (!out->close()) throw IoError(concat("cannot write '", path, "': ", out->geterror()));
}

Image read_image(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(concat("no such image file: '", path, "'"));
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw IoError(concat("cannot read '", path, "': ", OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  Image image(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw IoError(concat("cannot read '", path, "': ", in->geterror()));
  }
  in->close();
  return image;
}

}  // namespace refracta
