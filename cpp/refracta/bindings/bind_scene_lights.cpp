// Python bindings of a scene's lights (render/render_scene.h): the sun, the skies
// (shading/sky_presets.h), environments and added lights.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/render/scene_building.h"

#include "refracta/shading/constant_environment.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/sky_presets.h"

#include <cmath>
#include <optional>

namespace refracta {

namespace {

using SceneClass = py::class_<RenderScene, std::shared_ptr<RenderScene>>;

// The sun's colour: an RGB radiance, or with wavelengths (M,) [nm] a spectrum (M,) [W/(m^2 sr nm)].
Color sun_colour(const py::object& radiance, const py::object& wavelengths) {
  if (wavelengths.is_none()) return to_illuminant(radiance, "radiance");
  return Color::tabulated(to_values(wavelengths, "wavelengths"), to_values(radiance, "radiance"), Color::Kind::kIlluminant);
}

// The physical sky's table, built with Ctrl-C able to stop it (1-3 s over oneTBB, with multiple scattering).
std::shared_ptr<PhysicalSkyLight> build_sky_interruptibly(const PhysicalSkySettings& settings) {
  return interruptible_result(py::none(), [&](WorkControl&) { return std::make_shared<PhysicalSkyLight>(settings); });
}

// set_environment's source: a map file, an image array of radiance, or an RGB radiance.
LightPtr environment_of(const py::object& source, const py::object& rotation, double scale) {
  if (!(scale >= 0.0 && std::isfinite(scale))) throw_invalid("set_environment: scale must be finite and >= 0 (got ", scale, ")");
  // Reading a map and building its sampling distribution take a second for 4096 x 2048: without the GIL.
  if (py::isinstance<py::str>(source) || py::isinstance<py::bytes>(source) || py::hasattr(source, "__fspath__")) {
    const std::string path = file_system_path(source);
    const Eigen::Matrix3d turn = to_rotation(rotation, "rotation");
    py::gil_scoped_release release;
    return environment_from_file(path, scale, turn);
  }
  if (py::isinstance<py::array>(source) && py::cast<py::array>(source).ndim() >= 2) {
    const auto array = py::cast<py::array>(source);
    if (array.ndim() > 3 || (array.ndim() == 3 && array.shape(2) != 1 && array.shape(2) != 3 && array.shape(2) != 4)) {
      throw_invalid("set_environment: an image must be an (H, W) or (H, W, 1, 3 or 4) array of linear radiance (grey, "
                    "RGB; alpha ignored) (got shape ", std::string(py::str(py::getattr(array, "shape"))), ")");
    }
    require_float_radiance(source, "set_environment: an image array");
    Image image = to_image(source, "image");
    const Eigen::Matrix3d turn = to_rotation(rotation, "rotation");
    py::gil_scoped_release release;
    return std::make_shared<EnvironmentLight>(std::move(image), scale, turn);
  }
  // Checked as a map's is: a uniform sky looks the same turned any way, but a bad matrix is a mistake.
  EnvironmentLight::check_rotation(to_rotation(rotation, "rotation"), "set_environment: rotation");
  const Vec3d radiance = to_illuminant(source, "set_environment: radiance").rgb();  // named, >= 0 per channel
  return std::make_shared<ConstantEnvironment>(Color::illuminant(radiance * scale));
}

void bind_sun_and_sky(SceneClass& scene) {
  const SunDisc sun;  // the disc's defaults
  scene
      .def("set_sun",
           [](RenderScene& s, const py::object& direction, const py::object& radiance, double angular_diameter,
              double limb_darkening, const py::object& wavelengths) {
             set_sun(s, to_point(direction, "direction"), sun_colour(radiance, wavelengths), {angular_diameter, limb_darkening});
           },
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = sun.angular_diameter,
           py::arg("limb_darkening") = sun.limb_darkening, py::arg("wavelengths") = py::none(), DOC(refracta, set_sun))
      .def("set_sky",
           [](RenderScene& s, const py::object& horizon, const py::object& zenith, std::optional<FilePath> environment,
              double scale) {
             // A trial's set_sky('env.exr') read the path as a colour ("must hold real numbers").
             if (py::isinstance<py::str>(horizon) || py::hasattr(horizon, "__fspath__")) {
               throw_invalid("set_sky: horizon is a colour; give an environment map file as environment= (got '",
                             py::str(horizon).cast<std::string>(), "')");
             }
             set_sky(s, to_optional_rgb(horizon, "horizon"), to_optional_rgb(zenith, "zenith"),
                     environment ? std::optional(environment->string()) : std::nullopt, scale);
           },
           py::arg("horizon") = py::none(), py::arg("zenith") = py::none(), py::arg("environment") = py::none(),
           py::arg("scale") = 1.0, DOC(refracta, set_sky))
      .def("set_physical_sky",
           [](RenderScene& s, const py::object& sun_direction, std::optional<double> aerosol, double ozone_du, double ground_albedo,
              double sun_angular_diameter, double limb_darkening, double scale, double altitude,
              const std::string& below_horizon, bool aerial_perspective, const std::optional<double>& visibility) {
             const PhysicalSkySettings settings = physical_sky_settings(to_point(sun_direction, "sun_direction"), aerosol,
                                                                        ozone_du, ground_albedo, altitude, below_horizon, visibility);
             if (const auto caveat = fog_caveat(settings)) warn("Scene.set_physical_sky: " + *caveat);
             const SunDisc sun{sun_angular_diameter, limb_darkening};
             set_physical_sky(s, settings, sun, scale, aerial_perspective, &build_sky_interruptibly);
           },
           py::arg("sun_direction"), py::arg("aerosol") = py::none(),
           py::arg("ozone_du") = PhysicalSkySettings{}.ozone_du, py::arg("ground_albedo") = PhysicalSkySettings{}.ground_albedo,
           py::arg("sun_angular_diameter") = sun.angular_diameter, py::arg("limb_darkening") = sun.limb_darkening,
           py::kw_only(), py::arg("scale") = 1.0, py::arg("altitude") = PhysicalSkySettings{}.altitude,
           py::arg("below_horizon") = "horizon", py::arg("aerial_perspective").noconvert() = true, py::arg("visibility") = py::none(),
           DOC(refracta, set_physical_sky))
      .def_property_readonly(
          "aerial_perspective",
          [](const RenderScene& s) { return s.aerial_perspective() ? py::cast(s.aerial_perspective_ptr()) : py::none(); },
          "The scene's refracta.spectrum.AerialPerspective (set_physical_sky(aerial_perspective=True)), or None.")
      .def(
          "set_aerial_perspective",
          [](RenderScene& s, bool enabled) { enabled ? s.enable_aerial_perspective() : s.disable_aerial_perspective(); },
          py::arg("enabled").noconvert(),
          "Turn aerial perspective on (from the scene's physical sky; ValueError without one) or off, keeping the sky.")
      .def("set_environment",
           [](RenderScene& s, const py::object& source, const py::object& rotation, double scale) {
             s.set_sky(environment_of(source, rotation, scale));
           },
           py::arg("source"), py::arg("rotation") = py::none(), py::arg("scale") = 1.0,
           "The environment (replacing any sky): an RGB radiance (a constant environment), an equirectangular\n"
           "map file (EXR/HDR through OpenImageIO as linear radiance; an 8- or 16-bit PNG/JPEG decoded from\n"
           "sRGB, as textures are) or a float array of linear radiance, (H, W) grey or (H, W, 1, 3 or 4; alpha\n"
           "ignored), times `scale`, turned by `rotation` (degrees about y, or a 3 x 3 matrix). Orientation:\n"
           "refracta.lights.EnvironmentLight.");
}

}  // namespace

void bind_scene_lights(SceneClass& scene) {
  bind_sun_and_sky(scene);
  scene
      .def("add_light",
           [](RenderScene& s, const std::shared_ptr<Light>& light) { return s.add_light(light); }, py::arg("light"),
           "Add a refracta.lights light (not area lights: their geometry takes emission=). Returns its index.")
      .def(
          "add_light", [](RenderScene& s, const std::shared_ptr<PhysicalSkyLight>& sky) { return s.add_light(sky); },
          py::arg("light"), "Add a refracta.spectrum.PhysicalSky (as Scene.lights gives it). Returns its index.")
      .def("add_point_light",
           [](RenderScene& s, const py::object& position, const py::object& intensity) {
             return add_point_light(s, to_point(position, "position"), to_illuminant(intensity, "intensity"));
           },
           py::arg("position"), py::arg("intensity"), DOC(refracta, add_point_light))
      .def("add_spot_light",
           [](RenderScene& s, const py::object& position, const py::object& direction, double angle,
              const py::object& intensity, double radius, std::optional<double> inner_angle) {
             return add_spot_light(s, to_point(position, "position"), to_point(direction, "direction"), angle,
                                   to_illuminant(intensity, "intensity"), radius, inner_angle);
           },
           py::arg("position"), py::arg("direction"), py::arg("angle") = 60.0,
           py::arg("intensity") = py::make_tuple(100.0, 100.0, 100.0), py::arg("radius") = 0.0, py::kw_only(),
           py::arg("inner_angle") = py::none(), DOC(refracta, add_spot_light))
      .def_property_readonly(
          "lights", [](const RenderScene& s) { return s.lights(); },
          "The scene's lights. add_light puts its non-area lights into another scene; the air's own light is "
          "the scene's, not a light's: there, set_aerial_perspective(True) turns it on from its physical sky.");
}

}  // namespace refracta
