// Python bindings of image files and the display pipeline (scene/image_io.h, shading/display.h):
// what refracta.io wraps.
#include "refracta/bindings/bind_scene.h"

#include "refracta/scene/image_io.h"
#include "refracta/shading/display.h"

#include <optional>
#include <string>

namespace refracta {

py::array_t<float> image_to_float32(const Image& image) {
  py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

py::array_t<float> image_to_float32(Image&& image) {
  // The pixels move into the array's owner: a 4K frame is not held twice.
  auto* pixels = new std::vector<float>(std::move(image.pixels));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)},
                            pixels->data(), owner);
}

namespace {

using Number = std::optional<double>;

// gamma: 'srgb', 'linear' or a number (None: 'srgb').
std::variant<std::string, double> to_gamma(const py::object& gamma) {
  if (gamma.is_none()) return std::string("srgb");
  if (py::isinstance<py::str>(gamma)) return py::cast<std::string>(gamma);
  try {
    return py::cast<double>(gamma);
  } catch (const py::cast_error&) {
    throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3]");
  }
}

// The display keywords every function below takes after the image, in this order.
DisplayNames display_names(Number exposure, std::optional<std::string> tonemap, const py::object& gamma, Number key,
                           Number white, Number ev100, Number iso, Number shutter, Number f_number,
                           Number luminous_efficacy) {
  DisplayNames names;
  names.exposure = exposure, names.tonemap = std::move(tonemap), names.gamma = to_gamma(gamma);
  names.key = key, names.white = white, names.ev100 = ev100;
  names.iso = iso, names.shutter = shutter, names.f_number = f_number, names.luminous_efficacy = luminous_efficacy;
  return names;
}

// Writes `image` to `path`: float formats linear times the manual exposure (1 without one; never
// automatic), the others tone mapped and encoded for display.
void write_display_image(const std::string& path, Image image, const DisplaySettings& settings) {
  if (is_float_format(path)) {
    const double c = manual_exposure(settings);
    for (float& v : image.pixels) v *= float(c);
  } else {
    tonemap_image(image, settings);
  }
  py::gil_scoped_release release;
  write_image(path, image);
}

}  // namespace

void bind_image_io(py::module_& m) {
  // The display keywords (io.py passes them through; None: DisplaySettings' default).
  const auto kw = [](const char* name) { return py::arg(name) = py::none(); };
  m.def(
      "_write_image",
      [](const std::string& path, const py::object& image, Number exposure, std::optional<std::string> tonemap,
         const py::object& gamma, Number key, Number white, Number ev100, Number iso, Number shutter, Number f_number,
         Number luminous_efficacy) {
        const DisplayNames names = display_names(exposure, std::move(tonemap), gamma, key, white, ev100, iso, shutter,
                                                 f_number, luminous_efficacy);
        write_display_image(path, to_image(image, "image"), display_settings(names));
      },
      py::arg("path"), py::arg("image"), py::kw_only(), kw("exposure"), kw("tonemap"), kw("gamma"), kw("key"),
      kw("white"), kw("ev100"), kw("iso"), kw("shutter"), kw("f_number"), kw("luminous_efficacy"));
  m.def(
      "_display",
      [](const py::object& image, Number exposure, std::optional<std::string> tonemap, const py::object& gamma, Number key,
         Number white, Number ev100, Number iso, Number shutter, Number f_number, Number luminous_efficacy) {
        Image pixels = to_image(image, "image");
        tonemap_image(pixels, display_settings(display_names(exposure, std::move(tonemap), gamma, key, white, ev100, iso,
                                                             shutter, f_number, luminous_efficacy)));
        return image_to_float32(std::move(pixels));
      },
      py::arg("image"), py::kw_only(), kw("exposure"), kw("tonemap"), kw("gamma"), kw("key"), kw("white"), kw("ev100"),
      kw("iso"), kw("shutter"), kw("f_number"), kw("luminous_efficacy"));
  m.def(
      "_display_exposure",
      [](const py::object& image, Number exposure, Number key, Number ev100, Number iso, Number shutter,
         Number f_number, Number luminous_efficacy) {
        const DisplayNames names = display_names(exposure, std::nullopt, py::none(), key, std::nullopt, ev100, iso,
                                                 shutter, f_number, luminous_efficacy);
        return display_exposure(to_image(image, "image"), display_settings(names));
      },
      py::arg("image"), py::kw_only(), kw("exposure"), kw("key"), kw("ev100"), kw("iso"), kw("shutter"),
      kw("f_number"), kw("luminous_efficacy"), "The exposure c the display settings give this image (io.exposure_of).");
  m.def("_ev100", &ev100_of, py::arg("f_number"), py::arg("shutter"), py::arg("iso") = kDefaultIso,
        "EV100 = log2(N^2 / t) - log2(ISO / 100) of a camera's f-number, shutter time [s] and ISO.");
  m.def("_read_image", [](const std::string& path) { return image_to_float32(read_image(path)); }, py::arg("path"));
  m.def(
      "_write_image_channels",
      [](const std::string& path, const py::object& image, const std::vector<std::string>& names) {
        // Any channel count, inf and NaN kept (readouts: no hit is inf distance, a NaN position).
        using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
        FloatArray array;
        try {
          array = py::cast<FloatArray>(image);
        } catch (const py::cast_error&) {
          throw_invalid("image must be a float array of shape (H, W, C)");
        }
        if (array.ndim() != 3 || array.shape(0) < 1 || array.shape(1) < 1 || array.shape(2) < 1) {
          throw_invalid("image must have shape (H, W, C) (got ", array.ndim(), " dimensions)");
        }
        Image pixels(int(array.shape(1)), int(array.shape(0)), int(array.shape(2)));
        std::copy(array.data(), array.data() + array.size(), pixels.pixels.begin());
        py::gil_scoped_release release;
        write_image_channels(path, pixels, names);
      },
      py::arg("path"), py::arg("image"), py::arg("names"),
      "Write (H, W, C) float pixels as they are to a float file (EXR) with one name per channel (io.write_layers).");
  m.def("_channel_names", &read_channel_names, py::arg("path"), "The channel names of an image file (OIIO's).");
}

}  // namespace refracta
