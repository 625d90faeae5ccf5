// Python bindings of the lights (cpp/refracta/shading/*_light.h, light_sampler.h): each light a
// class under _core deriving from _core.Light, with vectorised sample_li / pdf_li / Le / L in
// RGB rendering (shading/light_batch.h), for tests and users' own integrators.
#include "refracta/bindings/bind_scene.h"  // image_to_float32
#include "refracta/bindings/pickle_state.h"
#include "generated/docstrings.h"
#include "refracta/shading/sky_presets.h"  // environment_from_file

#include "refracta/shading/area_light.h"
#include "refracta/shading/constant_environment.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/light_batch.h"
#include "refracta/shading/light_common.h"
#include "refracta/shading/light_sampler.h"
#include "refracta/shading/point_light.h"
#include "refracta/shading/scaled_light.h"
#include "refracta/shading/sphere_light.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"

namespace refracta {

namespace {

// Receiving points (N, 3) and their unit normals (N, 3) (rows may be 0) or None.
std::vector<LightSampleContext> contexts(const py::object& points, const py::object& normals) {
  const std::vector<Vec3d> p = to_points(points, "points");
  return light_contexts(p, normals.is_none() ? std::vector<Vec3d>() : to_unit_vectors(normals, "normals", p.size(), true));
}

// Pickle states: each light as its C++ constructor's arguments, colours by color_state (a
// tabulated colour, e.g. set_physical_sky's sun, keeps its spectrum), rebuilt by that constructor.
py::tuple xyz(const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); }

// The lights a point, a disc or a surface emits: point, spot, sun, area, sphere.
void bind_finite_lights(py::module_& m) {
  py::class_<PointLight, Light, std::shared_ptr<PointLight>> point(m, "PointLight", DOC(refracta, PointLight));
  point
      .def(py::init([](const py::object& position, const py::object& intensity) {
             return std::make_shared<PointLight>(to_point(position, "PointLight: position"), to_illuminant(intensity, "PointLight: intensity"));
           }),
           py::arg("position"), py::arg("intensity"))
      .def_property_readonly("position", [](const PointLight& l) { return vector_to_array(l.position()); });
  def_state_pickle(point, "PointLight", 2, [](const PointLight& l) { return py::make_tuple(xyz(l.position()), color_state(l.intensity())); },
                   [](const py::tuple& t) { return std::make_shared<PointLight>(to_point(t[0], "position"), color_from_state(t[1])); });

  py::class_<SpotLight, Light, std::shared_ptr<SpotLight>> spot(m, "SpotLight", DOC(refracta, SpotLight));
  spot
      .def(py::init([](const py::object& position, const py::object& direction, double angle, const py::object& intensity,
                       const py::object& inner_angle) {
             return std::make_shared<SpotLight>(to_point(position, "SpotLight: position"), to_point(direction, "SpotLight: direction"), angle,
                                                to_illuminant(intensity, "SpotLight: intensity"),
                                                inner_angle.is_none() ? -1.0 : to_number(inner_angle, "SpotLight: inner_angle"));
           }),
           py::arg("position"), py::arg("direction"), py::arg("angle"), py::arg("intensity"), py::arg("inner_angle") = py::none())
      .def_property_readonly("angle", &SpotLight::angle)
      .def_property_readonly("inner_angle", &SpotLight::inner_angle);
  def_state_pickle(
      spot, "SpotLight", 5,
      [](const SpotLight& l) {
        return py::make_tuple(xyz(l.position()), xyz(l.given_direction()), l.angle(), color_state(l.intensity()), l.inner_angle());
      },
      [](const py::tuple& t) {
        return std::make_shared<SpotLight>(to_point(t[0], "position"), to_point(t[1], "direction"), py::cast<double>(t[2]),
                                           color_from_state(t[3]), py::cast<double>(t[4]));
      });

  py::class_<SunLight, Light, std::shared_ptr<SunLight>> sun(m, "SunLight", DOC(refracta, SunLight));
  sun
      .def(py::init([](const py::object& direction, const py::object& radiance, double angular_diameter, double limb_darkening) {
             return std::make_shared<SunLight>(to_point(direction, "SunLight: direction"), to_illuminant(radiance, "SunLight: radiance"),
                                               angular_diameter, limb_darkening);
           }),
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = SunDisc().angular_diameter,
           py::arg("limb_darkening") = SunDisc().limb_darkening)
      .def_property_readonly("solid_angle", &SunLight::solid_angle, "Of the disc [sr].")
      .def_property_readonly("direction", [](const SunLight& l) { return vector_to_array(l.direction()); })
      .def_property_readonly("irradiance", [](const SunLight& l) { return vector_to_array(l.irradiance_rgb()); },
          "RGB irradiance [W/m^2] on a surface facing the sun.");
  def_state_pickle(
      sun, "SunLight", 4,
      [](const SunLight& l) {
        return py::make_tuple(xyz(l.given_direction()), color_state(l.radiance()), l.angular_diameter(), l.limb_darkening());
      },
      [](const py::tuple& t) {
        return std::make_shared<SunLight>(to_point(t[0], "direction"), color_from_state(t[1]), py::cast<double>(t[2]),
                                          py::cast<double>(t[3]));
      });

  py::class_<AreaLight, Light, std::shared_ptr<AreaLight>> area(m, "AreaLight", DOC(refracta, AreaLight));
  area
      .def(py::init([](const py::object& vertices, const py::object& triangles, const py::object& emission, bool two_sided) {
             Mesh mesh;
             mesh.vertices = to_points(vertices, "AreaLight: vertices");
             mesh.triangles = to_triangles(triangles, "AreaLight: triangles", mesh.vertices.size());
             return std::make_shared<AreaLight>(std::move(mesh), to_illuminant(emission, "AreaLight: emission"), two_sided);
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("emission"), py::arg("two_sided").noconvert() = false)
      .def_property_readonly("area", &AreaLight::area, "Total area [m^2] (zero-area triangles count 0).")
      .def_property_readonly("two_sided", &AreaLight::two_sided)
      .def("normal", [](const AreaLight& l, size_t t) { return vector_to_array(area_light_normal(l, t)); }, py::arg("triangle"),
           DOC(refracta, area_light_normal));
  def_state_pickle(
      area, "AreaLight", 3,
      [](const AreaLight& l) { return py::make_tuple(mesh_state(l.mesh()), color_state(l.emission()), l.two_sided()); },
      [](const py::tuple& t) { return std::make_shared<AreaLight>(mesh_from_state(t[0]), color_from_state(t[1]), py::cast<bool>(t[2])); });

  py::class_<SphereLight, Light, std::shared_ptr<SphereLight>> sphere(m, "SphereLight", DOC(refracta, SphereLight));
  sphere
      .def(py::init([](const py::object& centre, double radius, const py::object& emission) {
             return std::make_shared<SphereLight>(to_point(centre, "SphereLight: centre"), radius, to_illuminant(emission, "SphereLight: emission"));
           }),
           py::arg("centre"), py::arg("radius"), py::arg("emission"))
      .def_property_readonly("radius", &SphereLight::radius);
  def_state_pickle(
      sphere, "SphereLight", 3,
      [](const SphereLight& l) { return py::make_tuple(xyz(l.centre()), l.radius(), color_state(l.emission())); },
      [](const py::tuple& t) {
        return std::make_shared<SphereLight>(to_point(t[0], "centre"), py::cast<double>(t[1]), color_from_state(t[2]));
      });
}

// The lights at infinity: environment maps and the constant environment.
void bind_environment_lights(py::module_& m) {
  py::class_<EnvironmentLight, Light, std::shared_ptr<EnvironmentLight>> environment(m, "EnvironmentLight",
                                                                                       DOC(refracta, EnvironmentLight));
  environment
      .def(py::init([](const py::object& image, double scale, const py::object& rotation) {
             if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__")) {  // numpy read a path's characters
               throw_invalid("EnvironmentLight: image is an array of radiances; read a file with refracta.io.read_image "
                             "(or give its path to Scene.set_environment)");
             }
             require_float_radiance(image, "EnvironmentLight: image");
             return std::make_shared<EnvironmentLight>(to_image(image, "EnvironmentLight: image"), scale, to_rotation(rotation, "rotation"));
           }),
           py::arg("image"), py::arg("scale") = 1.0, py::arg("rotation") = py::none())
      .def("direction_to_uv", [](const EnvironmentLight& l, const py::object& dirs) {
             const std::vector<Vec2d> uv = directions_to_uv(l, to_points(dirs, "dirs"));
             DoubleArray out({py::ssize_t(uv.size()), py::ssize_t(2)});
             for (size_t i = 0; i < uv.size(); ++i) out.mutable_at(i, 0) = uv[i].x(), out.mutable_at(i, 1) = uv[i].y();
             return out;
           }, py::arg("dirs"), "(u, v) (N, 2) of directions (N, 3) (normalised here).")
      .def("uv_to_direction", [](const EnvironmentLight& l, const py::object& uv) {
             return points_to_array(uv_to_directions(l, to_uvs(uv, "uv", kAnyCount)));
           }, py::arg("uv"), "World directions (N, 3) of (u, v) (N, 2), each in [0, 1].")
      .def_static("rotation_about_y", [](double degrees) { return matrix_to_array(EnvironmentLight::rotation_about_y(degrees)); },
          py::arg("degrees"),
          "The 3 x 3 rotation about +y by degrees (right-handed: +x turns toward -z).")
      .def_property_readonly("scale", &EnvironmentLight::scale)
      .def_property_readonly("rotation", [](const EnvironmentLight& l) { return matrix_to_array(l.rotation()); },
          "The 3 x 3 rotation, map frame -> world.");
  def_state_pickle(
      environment, "EnvironmentLight", 3,
      [](const EnvironmentLight& l) -> py::tuple {
        // A map read from a file travels as its path (the file must be readable where it is unpickled).
        if (!l.source().empty()) return py::make_tuple(l.source(), l.scale(), matrix_to_array(l.rotation()));
        return py::make_tuple(image_to_float32(l.image()), l.scale(), matrix_to_array(l.rotation()));
      },
      [](const py::tuple& t) {
        const Eigen::Matrix3d rotation = to_rotation(t[2], "rotation");
        if (py::isinstance<py::str>(t[0])) return environment_from_file(py::cast<std::string>(t[0]), py::cast<double>(t[1]), rotation);
        return std::make_shared<EnvironmentLight>(to_image(t[0], "EnvironmentLight: image"), py::cast<double>(t[1]), rotation);
      });

  py::class_<ConstantEnvironment, Light, std::shared_ptr<ConstantEnvironment>> constant(m, "ConstantEnvironment",
                                                                                           DOC(refracta, ConstantEnvironment));
  constant.def(py::init([](const py::object& radiance, const std::string& sampling) {
                 return std::make_shared<ConstantEnvironment>(to_illuminant(radiance, "ConstantEnvironment: radiance"),
                                                              ConstantEnvironment::sampling_from(sampling));
               }),
               py::arg("radiance"), py::arg("sampling") = "cosine");
  def_state_pickle(
      constant, "ConstantEnvironment", 2,
      [](const ConstantEnvironment& l) { return py::make_tuple(color_state(l.radiance()), int(l.sampling())); },
      [](const py::tuple& t) {
        const int sampling = py::cast<int>(t[1]);
        if (sampling != int(ConstantEnvironment::Sampling::kCosine) && sampling != int(ConstantEnvironment::Sampling::kUniform)) {
          throw_invalid("ConstantEnvironment: bad pickle state (sampling ", sampling, ")");
        }
        return std::make_shared<ConstantEnvironment>(color_from_state(t[0]), ConstantEnvironment::Sampling(sampling));
      });

  py::class_<ScaledInfiniteLight, Light, std::shared_ptr<ScaledInfiniteLight>> scaled(m, "ScaledLight",
                                                                                      DOC(refracta, ScaledInfiniteLight));
  scaled
      .def(py::init([](const py::object& light, double scale) {
             return std::make_shared<ScaledInfiniteLight>(light_from(light), scale);
           }),
           py::arg("light"), py::arg("scale"))
      .def_property_readonly("light", [](const ScaledInfiniteLight& l) { return light_object(l.light()); })
      .def_property_readonly("scale", &ScaledInfiniteLight::scale);
  def_state_pickle(
      scaled, "ScaledLight", 2,
      [](const ScaledInfiniteLight& l) { return py::make_tuple(light_object(l.light()), l.scale()); },
      [](const py::tuple& t) { return std::make_shared<ScaledInfiniteLight>(light_from(t[0]), py::cast<double>(t[1])); });
}

}  // namespace

void bind_lights(py::module_& m) {
  py::class_<Light, std::shared_ptr<Light>>(m, "Light", DOC(refracta, Light))
      .def_property_readonly("type", [](const Light& l) { return light_type_name(l.type()); },
          "'delta_position' (point, spot), 'area' (meshes, spheres) or 'infinite' (sun, environments).")
      .def_property_readonly("is_delta", &Light::is_delta)
      .def_property_readonly("is_infinite", &Light::is_infinite)
      .def_property_readonly("power", &Light::power,
          "Emitted power [W] as luminance Y of the RGB power (infinite lights: through the disc of the scene "
          "radius given to preprocess, 1 m until then).")
      .def("preprocess", [](Light& l, const py::object& centre, double radius) { l.preprocess(to_point(centre, "centre"), radius); },
          py::arg("centre"), py::arg("radius"), "Tells the light the scene's bounding sphere (centre [m], radius [m]).")
      .def("sample_li",
           [](const Light& l, const py::object& points, const py::object& normals, const py::object& u) {
             const std::vector<LightSampleContext> ctx = contexts(points, normals);
             const RgbLightSamples s = sample_li_rgb(l, ctx, to_samples(u, "u", 2, ctx.size()).values);
             return py::make_tuple(points_to_array(s.wi), points_to_array(s.L), values_to_array(s.pdf), values_to_array(s.distance));
           },
           py::arg("points"), py::arg("normals"), py::arg("u"),
           DOC(refracta, sample_li_rgb))
      .def("pdf_li",
           [](const Light& l, const py::object& points, const py::object& normals, const py::object& wi,
              const py::object& p_light, const py::object& n_light) {
             const std::vector<LightSampleContext> ctx = contexts(points, normals);
             const std::vector<Vec3d> p = p_light.is_none() ? std::vector<Vec3d>() : to_points(p_light, "p_light");
             const std::vector<Vec3d> n = n_light.is_none() ? std::vector<Vec3d>() : to_unit_vectors(n_light, "n_light", ctx.size(), true);
             return values_to_array(pdf_li_all(l, ctx, to_unit_vectors(wi, "wi", ctx.size()), p, n));
           },
           py::arg("points"), py::arg("normals"), py::arg("wi"), py::arg("p_light") = py::none(), py::arg("n_light") = py::none(),
           DOC(refracta, pdf_li_all))
      .def("Le", [](const Light& l, const py::object& dirs) { return points_to_array(Le_rgb(l, to_unit_vectors(dirs, "dirs"))); },
          py::arg("dirs"), DOC(refracta, Le_rgb))
      .def("L",
           [](const Light& l, const py::object& points, const py::object& normals, const py::object& dirs) {
             const std::vector<Vec3d> p = to_points(points, "points");
             return points_to_array(L_rgb(l, p, to_points(normals, "normals"), to_unit_vectors(dirs, "dirs", p.size())));
           },
           py::arg("points"), py::arg("normals"), py::arg("dirs"),
           DOC(refracta, L_rgb))
      .def("__repr__", &Light::describe);

  py::class_<LightSampler> sampler(m, "LightSampler", DOC(refracta, LightSampler));
  sampler
      .def(py::init([](const std::vector<LightPtr>& lights, const std::string& strategy) {
             return LightSampler(lights, LightSampler::strategy_from(strategy));
           }),
           py::arg("lights"), py::arg("strategy") = "power")
      .def("sample", [](const LightSampler& s, const py::object& u) {
             const LightChoices chosen = sample_lights(s, to_samples(u, "u", 1).values);
             return py::make_tuple(py::array_t<long long>(py::ssize_t(chosen.index.size()), chosen.index.data()),
                                   values_to_array(chosen.probability));
           }, py::arg("u"), "(index (N,) int, probability (N,)) for u (N,) in [0, 1).")
      .def("pmf",
           [](const LightSampler& s, long long index) {
             if (index < 0) throw_invalid("LightSampler.pmf: index must be >= 0 (got ", index, ")");
             return s.pmf(size_t(index));
           },
           py::arg("index"))
      .def("__len__", &LightSampler::size)
      .def("__repr__", [](const LightSampler& s) {
        return concat("LightSampler(", s.size(), " lights, strategy='", LightSampler::strategy_name(s.strategy()), "')");
      });
  def_state_pickle(
      sampler, "LightSampler", 2, [](const LightSampler& s) { return py::make_tuple(s.lights(), int(s.strategy())); },
      [](const py::tuple& t) {
        const int strategy = py::cast<int>(t[1]);
        if (strategy < int(LightSampler::Strategy::kPower) || strategy > int(LightSampler::Strategy::kKind)) {
          throw_invalid("LightSampler: bad pickle state");
        }
        return LightSampler(py::cast<std::vector<LightPtr>>(t[0]), LightSampler::Strategy(strategy));
      });
  bind_finite_lights(m);
  bind_environment_lights(m);
}

}  // namespace refracta
