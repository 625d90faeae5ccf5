// Python bindings of a scene's lights (render/render_scene.h): the sun, the skies
// (shading/sky_presets.h), environments and added lights.
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/render/scene_building.h"

#include "refracta/shading/constant_environment.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/point_light.h"
#include "refracta/shading/sky_presets.h"
#include "refracta/shading/sun_light.h"

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
  if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
    return environment_from_file(py::cast<FilePath>(source).string(), scale, to_rotation(rotation, "rotation"));
  }
  if (py::isinstance<py::array>(source) && py::cast<py::array>(source).ndim() >= 2) {
    const auto array = py::cast<py::array>(source);
    if (array.ndim() > 3 || (array.ndim() == 3 && array.shape(2) != 1 && array.shape(2) != 3 && array.shape(2) != 4)) {
      throw_invalid("set_environment: an image must be an (H, W) or (H, W, 1, 3 or 4) array of linear radiance (grey, "
                    "RGB; alpha ignored) (got shape ", std::string(py::str(py::getattr(array, "shape"))), ")");
    }
    require_float_radiance(source, "set_environment: an image array");
    return std::make_shared<EnvironmentLight>(to_image(source, "image"), scale, to_rotation(rotation, "rotation"));
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
             s.set_sun(std::make_shared<SunLight>(to_point(direction, "direction"), sun_colour(radiance, wavelengths),
                                                  angular_diameter, limb_darkening));
           },
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = sun.angular_diameter,
           py::arg("limb_darkening") = sun.limb_darkening, py::arg("wavelengths") = py::none(),
           "The sun (replacing any): direction toward it, disc radiance [W/(m^2 sr), RGB], angular diameter [deg],\n"
           "limb darkening u (I(mu) = 1 - u (1 - mu)). Seen through the air along curved rays.\n"
           "With wavelengths (M,) [nm, increasing], radiance is a spectrum (M,) [W/(m^2 sr nm)] instead (e.g.\n"
           "refracta.spectrum.PhysicalSky(...).sun_radiance(wavelengths): the sun through the air's extinction).")
      .def("set_sky",
           [](RenderScene& s, const py::object& horizon, const py::object& zenith, std::optional<FilePath> environment,
              double scale) {
             if (environment && !(horizon.is_none() && zenith.is_none())) {
               throw_invalid("set_sky: give horizon and zenith, or environment, not both (the map is the whole sky)");
             }
             if (environment) return s.set_sky(environment_from_file(environment->string(), scale));
             const Vec3d h = horizon.is_none() ? kDefaultSkyColour : to_rgb(horizon, "horizon");
             s.set_sky(gradient_sky(h, zenith.is_none() ? h : to_rgb(zenith, "zenith"), scale));
           },
           py::arg("horizon") = py::none(), py::arg("zenith") = py::none(), py::arg("environment") = py::none(),
           py::arg("scale") = 1.0,
           "A sky (replacing any environment): radiance toward the horizon (and below) and straight up, linear in\n"
           "the sine of the elevation (zenith default: the horizon's, a constant sky), or an equirectangular\n"
           "environment map file (refracta.lights.EnvironmentLight's orientation), times `scale`.")
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
           "The physical sky (replacing every environment, sky and sun): refracta.spectrum.PhysicalSky's\n"
           "single scattering (Nishita et al. 1993) plus Hillaire 2020's multiple scattering, for the sun\n"
           "toward `sun_direction` (normalised, y up),\n"
           "`aerosol` (Mie density scale; None: 1, a clear sky), `ozone_du` [Dobson units], observer `altitude` [m]. Below the horizon\n"
           "`below_horizon`: 'horizon' (default) continues the sky from the horizon at each azimuth (Scene.set_sky's\n"
           "convention: the ground is geometry, and a ray ending its max_length still heading slightly down sees\n"
           "the horizon sky, importance-sampled over the whole sphere); 'ground' shows the Lambertian ground of\n"
           "`ground_albedo` (which must be 0 with 'horizon'). And the sun: a disc of `sun_angular_diameter` [deg]\n"
           "with linear limb darkening u, its radiance the 5778 K solar spectrum through the atmosphere's extinction (reddened\n"
           "toward the horizon; none below it). Units: spectral radiance W/(m^2 sr nm) in spectral renders,\n"
           "its CIE-Y-weighted mean in RGB (linear sRGB of XYZ / integral ybar, as Color.illuminant: times\n"
           "106.86 nm gives W/(m^2 sr)); RGB and spectral renders agree. `scale` multiplies sky and sun\n"
           "(e.g. an exposure). Builds the sky's table (1-3 s).\n"
           "aerial_perspective (default True): the same air dims and lights every segment the renderers cast\n"
           "(refracta.spectrum.AerialPerspective: transmittance and scattered sunlight, the sky's multiple\n"
           "scattering included), so distant\n"
           "objects grey and blue into the sky; False keeps surfaces as seen through empty space.\n"
           "visibility [km]: meteorological visibility at the ground (Koschmieder: extinction at 550 nm =\n"
           "3.912 / V), setting the aerosol in its place (give one of them). The scene's y = 0 lies `altitude`\n"
           "above the sky's sea level.")
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
           [](RenderScene& s, const std::shared_ptr<Light>& light) {
             if (!light) throw_invalid("light must be a refracta.lights light");
             return s.add_light(light);
           },
           py::arg("light"), "Add any refracta.lights light (not area lights of geometry: use emission=). Returns its index.")
      .def("add_point_light",
           [](RenderScene& s, const py::object& position, const py::object& intensity) {
             return s.add_light(std::make_shared<PointLight>(to_point(position, "position"), to_illuminant(intensity, "intensity")));
           },
           py::arg("position"), py::arg("intensity"),
           "Add a point light at `position` [m] of `intensity` [W/sr, RGB] (irradiance I cos / d^2). Returns its index.")
      .def("add_spot_light",
           [](RenderScene& s, const py::object& position, const py::object& direction, double angle,
              const py::object& intensity, double radius) {
             return add_spot_light(s, to_point(position, "position"), to_point(direction, "direction"), angle,
                                   to_illuminant(intensity, "intensity"), radius);
           },
           py::arg("position"), py::arg("direction"), py::arg("angle") = 60.0,
           py::arg("intensity") = py::make_tuple(100.0, 100.0, 100.0), py::arg("radius") = 0.0,
           "Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg] with\n"
           "`intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 gives render_raster's 'embree'\n"
           "reference soft shadows of a disc that size. Returns its index among the spot lights.")
      .def_property_readonly("lights", [](const RenderScene& s) { return s.lights(); });
}

}  // namespace refracta
