// Python bindings of image files and the display pipeline (scene/image_io.h, shading/display.h):
// what refracta.io wraps.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/options_binding.h"

#include "refracta/scene/image_io.h"
#include "refracta/shading/display.h"

#include <algorithm>
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

// io.write_image (display.h's write_display_image), warning first of the settings a float file leaves unused.
void write_display_image_warning(const std::string& path, Image image, const DisplaySettings& settings) {
  if (is_float_format(path)) {
    if (const auto unused = display_only_fields_set(settings); !unused.empty()) {
      std::string names;
      for (const std::string& name : unused) names += (names.empty() ? "" : ", ") + name;
      // Without the path: Python shows a warning once per place and text, not once per frame written.
      const std::string message = "write_image: a float format is written linear: " + names +
                                  " shape only displayed images (PNG, JPEG) and are not applied";
      if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) != 0) throw py::error_already_set();
    }
    const auto negative = keeps_negative_values(path) ? 0 : std::count_if(image.pixels.begin(), image.pixels.end(),
                                                                           [](float v) { return v < 0.0f; });
    if (negative > 0) {
      const std::string message = "write_image: Radiance HDR stores no negative values: " + std::to_string(negative) +
                                  " written as 0 (EXR, TIFF and PFM keep them)";
      if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) != 0) throw py::error_already_set();
    }
  }
  py::gil_scoped_release release;
  write_display_image(path, std::move(image), settings);
}

}  // namespace

void bind_display_settings(py::module_& m) {
  using S = DisplaySettings;
  py::class_<S> cls(m, "DisplaySettings", DOC(refracta, DisplaySettings));
  def_options_common<S>(cls, "DisplaySettings");
  cls.def_readwrite("exposure", &S::exposure, DOC(refracta, DisplaySettings, exposure))
      .def_readwrite("ev100", &S::ev100, DOC(refracta, DisplaySettings, ev100))
      .def_readwrite("iso", &S::iso, DOC(refracta, DisplaySettings, iso))
      .def_readwrite("shutter", &S::shutter, DOC(refracta, DisplaySettings, shutter))
      .def_readwrite("f_number", &S::f_number, DOC(refracta, DisplaySettings, f_number))
      .def_readwrite("luminous_efficacy", &S::luminous_efficacy, DOC(refracta, DisplaySettings, luminous_efficacy))
      .def_readwrite("key", &S::key, DOC(refracta, DisplaySettings, key))
      .def_readwrite("white", &S::white, DOC(refracta, DisplaySettings, white));
  def_enum_property(cls, "tonemap", &S::tonemap, tonemap_name, parse_tonemap,
                    "'aces' (filmic), 'reinhard', 'film' (1 - e^(-cL)) or 'linear' (min(cL, 1))")
      .def_property("gamma", &gamma_name, &set_gamma, "the transfer curve: 'srgb', 'linear' or a gamma g in [1, 3]")
      .def_property(
          "white_balance",
          [](const S& s) -> py::object {
            if (const auto* rgb = std::get_if<std::array<double, 3>>(&s.white_balance)) {
              return py::make_tuple((*rgb)[0], (*rgb)[1], (*rgb)[2]);
            }
            return py::cast(s.white_balance);
          },
          [](S& s, const WhiteBalance& white_balance) { s.white_balance = white_balance; },
          "the light shown white: 'none' (the render's D65 white), 'auto' (grey world), 'daylight' (D55), 'cloudy' "
          "(D65), 'shade' (D75), 'tungsten' (3200 K), a colour temperature [K] in [1000, 40000] (Planckian) or an RGB "
          "white (r, g, b) in linear sRGB with X, Y, Z and its cone responses > 0; Bradford adaptation to D65");
}

void bind_image_io(py::module_& m) {
  bind_display_settings(m);
  m.def("_check_image_format", &check_image_format, py::arg("path"),
        "IoError unless an image of path's format (its extension) can be written.");
  m.def("_check_writable", &check_writable, py::arg("path"), DOC(refracta, check_writable));
  m.def("_is_float_format", &is_float_format, py::arg("path"), "Whether write_image keeps path's format linear.");
  m.def(
      "_write_image",
      [](const py::object& path, const py::object& image, const DisplaySettings& display) {
        write_display_image_warning(file_system_path(path), to_image(image, "image"), display);
      },
      py::arg("path"), py::arg("image"), py::arg("display"), "Write an image as refracta.io.write_image.");
  m.def(
      "_display",
      [](const py::object& image, const DisplaySettings& display) {
        Image pixels = to_image(image, "image");
        tonemap_image(pixels, display);
        return image_to_float32(std::move(pixels));
      },
      py::arg("image"), py::arg("display"), "Display values of an image (refracta.io.to_display).");
  m.def(
      "_display_exposure",
      [](const py::object& image, const DisplaySettings& display) {
        bool metered_nothing = false;
        const double exposure = display_exposure(to_image(image, "image"), display, &metered_nothing);
        return std::make_tuple(exposure, metered_nothing);
      },
      py::arg("image"), py::arg("display"),
      "(c, metered_nothing): the exposure c the display settings give this image (io.exposure_of), and whether\n"
      "automatic exposure found no light to meter.");
  m.def(
      "_white_balance_matrix",
      [](const py::object& image, const DisplaySettings& display) {
        return matrix_to_array(white_balance_matrix(to_image(image, "image"), display));
      },
      py::arg("image"), py::arg("display"), "The white balance's linear sRGB matrix for this image (io.white_balance_of).");
  m.def("_ev100", &ev100_of, py::arg("f_number"), py::arg("shutter"), py::arg("iso") = kDefaultIso,
        "EV100 = log2(N^2 / t) - log2(ISO / 100) of a camera's f-number, shutter time [s] and ISO.");
  m.def(
      "_read_image",
      [](const py::object& file, bool linear) {
        const std::string path = file_system_path(file);
        Image image;
        {
          py::gil_scoped_release release;  // a 4096 x 2048 EXR reads for 1 s (a trial)
          image = linear ? read_linear_image(path) : read_image(path);
        }
        return image_to_float32(std::move(image));
      },
      py::arg("path"), py::arg("linear"));
  m.def(
      "_write_image_channels",
      [](const std::string& path, const py::object& image, const std::vector<std::string>& names) {
        const Image pixels = to_image(image, "image", /*raw=*/true);
        py::gil_scoped_release release;
        write_image_channels(path, pixels, names);
      },
      py::arg("path"), py::arg("image"), py::arg("names"),
      "Write (H, W, C) float pixels as they are to a float file (EXR) with one name per channel (io.write_layers).");
  m.def("_channel_names", &read_channel_names, py::arg("path"), "The channel names of an image file (OIIO's).");
}

}  // namespace refracta
