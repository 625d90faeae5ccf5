// Python bindings of the lights (cpp/refracta/shading/*_light.h, light_sampler.h): each light a
// class under _core deriving from _core.Light, with vectorised sample_li / pdf_li / Le / L in
// RGB rendering, for tests and users' own integrators.
#include "refracta/bindings/bindings.h"
#include "refracta/bindings/pickle_state.h"
#include "refracta/shading/sky_presets.h"  // environment_from_file

#include "refracta/shading/area_light.h"
#include "refracta/shading/constant_environment.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/light_common.h"
#include "refracta/shading/light_sampler.h"
#include "refracta/shading/point_light.h"
#include "refracta/shading/sphere_light.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"

#include <cmath>

namespace refracta {

namespace {

std::vector<LightSampleContext> contexts(const py::object& points, const py::object& normals) {
  std::vector<Vec3d> p = to_points(points, "points");
  std::vector<LightSampleContext> ctx(p.size());
  std::vector<Vec3d> n;
  if (!normals.is_none()) n = to_unit_vectors(normals, "normals", p.size(), true);
  for (size_t i = 0; i < p.size(); ++i) {
    ctx[i].p = p[i];
    if (!n.empty()) ctx[i].n = n[i];
  }
  return ctx;
}

DoubleArray rgb_array(const std::vector<Spectrum>& values) {
  DoubleArray out({py::ssize_t(values.size()), py::ssize_t(3)});
  double* data = out.mutable_data();
  for (size_t i = 0; i < values.size(); ++i) {
    for (int k = 0; k < 3; ++k) data[3 * i + k] = values[i][k];
  }
  return out;
}

py::tuple sample_li(const Light& light, const py::object& points, const py::object& normals, const py::object& u_object) {
  const std::vector<LightSampleContext> ctx = contexts(points, normals);
  const Samples u = to_samples(u_object, "u", 2, ctx.size());
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  std::vector<Vec3d> wi(ctx.size(), Vec3d::Zero());
  std::vector<Spectrum> L(ctx.size(), Spectrum::Zero());
  std::vector<double> pdf(ctx.size(), 0.0), distance(ctx.size(), 0.0);
  for (size_t i = 0; i < ctx.size(); ++i) {
    if (auto s = light.sample_li(ctx[i], u.pair(i), lambda)) {
      wi[i] = s->wi, L[i] = s->L, pdf[i] = s->pdf, distance[i] = s->distance;
    }
  }
  return py::make_tuple(points_to_array(wi), rgb_array(L), values_to_array(pdf), values_to_array(distance));
}

py::array pdf_li(const Light& light, const py::object& points, const py::object& normals, const py::object& wi_object,
                 const py::object& p_light_object, const py::object& n_light_object) {
  const std::vector<LightSampleContext> ctx = contexts(points, normals);
  const std::vector<Vec3d> wi = to_unit_vectors(wi_object, "wi", ctx.size());
  std::vector<Vec3d> p_light(ctx.size(), Vec3d::Zero()), n_light(ctx.size(), Vec3d::Zero());
  if (!p_light_object.is_none()) {
    p_light = to_points(p_light_object, "p_light");
    if (p_light.size() != ctx.size()) throw_invalid("p_light must have shape (", ctx.size(), ", 3)");
  }
  if (!n_light_object.is_none()) n_light = to_unit_vectors(n_light_object, "n_light", ctx.size(), true);
  std::vector<double> pdf(ctx.size());
  for (size_t i = 0; i < ctx.size(); ++i) pdf[i] = light.pdf_li(ctx[i], wi[i], p_light[i], n_light[i]);
  return values_to_array(pdf);
}

py::array Le(const Light& light, const py::object& dirs_object) {
  const std::vector<Vec3d> dirs = to_unit_vectors(dirs_object, "dirs");
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  std::vector<Spectrum> out(dirs.size());
  for (size_t i = 0; i < dirs.size(); ++i) out[i] = light.Le(dirs[i], lambda);
  return rgb_array(out);
}

py::array L(const Light& light, const py::object& points_object, const py::object& normals_object, const py::object& dirs_object) {
  const std::vector<Vec3d> p = to_points(points_object, "points");
  const std::vector<Vec3d> n = to_points(normals_object, "normals");
  if (n.size() != p.size()) throw_invalid("normals must have shape (", p.size(), ", 3)");
  const std::vector<Vec3d> w = to_unit_vectors(dirs_object, "dirs", p.size());
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  std::vector<Spectrum> out(p.size());
  for (size_t i = 0; i < p.size(); ++i) out[i] = light.L(p[i], n[i], w[i], lambda);
  return rgb_array(out);
}

const char* type_name(LightType t) {
  switch (t) {
    case LightType::kDeltaPosition: return "delta_position";
    case LightType::kDeltaDirection: return "delta_direction";
    case LightType::kArea: return "area";
    case LightType::kInfinite: return "infinite";
  }
  return "unknown";
}

// Pickle states: each light as its C++ constructor's arguments, colours by color_state (a
// tabulated colour, e.g. set_physical_sky's sun, keeps its spectrum), rebuilt by that constructor.
py::tuple xyz(const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); }

void check_state(const py::tuple& t, size_t size, const char* light) {
  if (t.size() != size) throw_invalid(light, ": bad pickle state (", t.size(), " items, expected ", size, ")");
}

// The lights a point, a disc or a surface emits: point, spot, sun, area, sphere.
void bind_finite_lights(py::module_& m) {
  py::class_<PointLight, Light, std::shared_ptr<PointLight>>(m, "PointLight",
      "A point light: intensity [W/sr] (number or RGB) from position [m]; E = I cos(theta)/r^2, power 4 pi I.")
      .def(py::init([](const py::object& position, const py::object& intensity) {
             return std::make_shared<PointLight>(to_point(position, "PointLight: position"), to_illuminant(intensity, "PointLight: intensity"));
           }),
           py::arg("position"), py::arg("intensity"))
      .def_property_readonly("position", [](const PointLight& l) { return vector_to_array(l.position()); })
      .def(py::pickle([](const PointLight& l) { return py::make_tuple(xyz(l.position()), color_state(l.intensity())); },
                      [](const py::tuple& t) {
                        check_state(t, 2, "PointLight");
                        return std::make_shared<PointLight>(to_point(t[0], "position"), color_from_state(t[1]));
                      }));

  py::class_<SpotLight, Light, std::shared_ptr<SpotLight>>(m, "SpotLight",
      "A spot light at position [m] shining along direction into a cone of full angle [deg] with intensity [W/sr]; "
      "hard edge by default, a smoothstep falloff from inner_angle [deg] out to angle when inner_angle < angle.")
      .def(py::init([](const py::object& position, const py::object& direction, double angle, const py::object& intensity,
                       const py::object& inner_angle) {
             return std::make_shared<SpotLight>(to_point(position, "SpotLight: position"), to_point(direction, "SpotLight: direction"), angle,
                                                to_illuminant(intensity, "SpotLight: intensity"),
                                                inner_angle.is_none() ? -1.0 : py::cast<double>(inner_angle));
           }),
           py::arg("position"), py::arg("direction"), py::arg("angle"), py::arg("intensity"), py::arg("inner_angle") = py::none())
      .def_property_readonly("angle", &SpotLight::angle)
      .def_property_readonly("inner_angle", &SpotLight::inner_angle)
      .def(py::pickle(
          [](const SpotLight& l) {
            return py::make_tuple(xyz(l.position()), xyz(l.given_direction()), l.angle(), color_state(l.intensity()), l.inner_angle());
          },
          [](const py::tuple& t) {
            check_state(t, 5, "SpotLight");
            return std::make_shared<SpotLight>(to_point(t[0], "position"), to_point(t[1], "direction"), py::cast<double>(t[2]),
                                               color_from_state(t[3]), py::cast<double>(t[4]));
          }));

  py::class_<SunLight, Light, std::shared_ptr<SunLight>>(m, "SunLight",
      "The sun: a disc at infinity toward direction, mean radiance [W/(m^2 sr)] over the disc, angular_diameter "
      "[deg], linear limb darkening u in [0, 1] (I(mu) = 1 - u (1 - mu)).")
      .def(py::init([](const py::object& direction, const py::object& radiance, double angular_diameter, double limb_darkening) {
             return std::make_shared<SunLight>(to_point(direction, "SunLight: direction"), to_illuminant(radiance, "SunLight: radiance"),
                                               angular_diameter, limb_darkening);
           }),
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = 0.53, py::arg("limb_darkening") = 0.0)
      .def_property_readonly("solid_angle", &SunLight::solid_angle, "Of the disc [sr].")
      .def_property_readonly("direction", [](const SunLight& l) { return vector_to_array(l.direction()); })
      .def_property_readonly("irradiance", [](const SunLight& l) { return vector_to_array(l.irradiance_rgb()); },
          "RGB irradiance [W/m^2] on a surface facing the sun.")
      .def(py::pickle(
          [](const SunLight& l) {
            return py::make_tuple(xyz(l.given_direction()), color_state(l.radiance()), l.angular_diameter(), l.limb_darkening());
          },
          [](const py::tuple& t) {
            check_state(t, 4, "SunLight");
            return std::make_shared<SunLight>(to_point(t[0], "direction"), color_from_state(t[1]), py::cast<double>(t[2]),
                                              py::cast<double>(t[3]));
          }));

  py::class_<AreaLight, Light, std::shared_ptr<AreaLight>>(m, "AreaLight",
      "An emissive triangle mesh: vertices (V, 3) [m], triangles (T, 3) int, emission radiance [W/(m^2 sr)] from "
      "the counter-clockwise front ((v1 - v0) x (v2 - v0)) or both sides.")
      .def(py::init([](const py::object& vertices, const py::object& triangles, const py::object& emission, bool two_sided) {
             Mesh mesh;
             mesh.vertices = to_points(vertices, "AreaLight: vertices");
             mesh.triangles = to_triangles(triangles, "AreaLight: triangles", mesh.vertices.size());
             return std::make_shared<AreaLight>(std::move(mesh), to_illuminant(emission, "AreaLight: emission"), two_sided);
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("emission"), py::arg("two_sided") = false)
      .def_property_readonly("area", &AreaLight::area, "Total area [m^2] (zero-area triangles count 0).")
      .def_property_readonly("two_sided", &AreaLight::two_sided)
      .def("normal", [](const AreaLight& l, size_t t) {
             if (t >= l.mesh().triangles.size()) throw_invalid("triangle must be < ", l.mesh().triangles.size(), " (got ", t, ")");
             return vector_to_array(l.normal(t));
           }, py::arg("triangle"), "The front normal of a triangle (unit; 0 for a zero-area one).")
      .def(py::pickle([](const AreaLight& l) { return py::make_tuple(mesh_state(l.mesh()), color_state(l.emission()), l.two_sided()); },
                      [](const py::tuple& t) {
                        check_state(t, 3, "AreaLight");
                        return std::make_shared<AreaLight>(mesh_from_state(t[0]), color_from_state(t[1]), py::cast<bool>(t[2]));
                      }));

  py::class_<SphereLight, Light, std::shared_ptr<SphereLight>>(m, "SphereLight",
      "An emissive sphere: centre [m], radius [m], emission radiance [W/(m^2 sr)] outward; power 4 pi^2 r^2 L.")
      .def(py::init([](const py::object& centre, double radius, const py::object& emission) {
             return std::make_shared<SphereLight>(to_point(centre, "SphereLight: centre"), radius, to_illuminant(emission, "SphereLight: emission"));
           }),
           py::arg("centre"), py::arg("radius"), py::arg("emission"))
      .def_property_readonly("radius", &SphereLight::radius)
      .def(py::pickle([](const SphereLight& l) { return py::make_tuple(xyz(l.centre()), l.radius(), color_state(l.emission())); },
                      [](const py::tuple& t) {
                        check_state(t, 3, "SphereLight");
                        return std::make_shared<SphereLight>(to_point(t[0], "centre"), py::cast<double>(t[1]), color_from_state(t[2]));
                      }));

}

// The lights at infinity: environment maps and the constant environment.
void bind_environment_lights(py::module_& m) {
  py::class_<EnvironmentLight, Light, std::shared_ptr<EnvironmentLight>>(m, "EnvironmentLight",
      "An equirectangular environment map (H, W, 3) float linear RGB, rows top (up, +y) to bottom, times scale; "
      "rotation: degrees about +y or a 3 x 3 map-to-world rotation. Mitsuba 3's envmap orientation: "
      "u = atan2(d.x, -d.z)/(2 pi) wrapped to [0, 1), v = acos(d.y)/pi (d in the map's frame); column i at "
      "u = (i + 1/2)/W, row j at v = j/(H - 1), bilinear.")
      .def(py::init([](const py::object& image, double scale, const py::object& rotation) {
             return std::make_shared<EnvironmentLight>(to_image(image, "EnvironmentLight: image"), scale, to_rotation(rotation, "rotation"));
           }),
           py::arg("image"), py::arg("scale") = 1.0, py::arg("rotation") = py::none())
      .def("direction_to_uv", [](const EnvironmentLight& l, const py::object& dirs) {
             const std::vector<Vec3d> d = to_points(dirs, "dirs");
             DoubleArray out({py::ssize_t(d.size()), py::ssize_t(2)});
             for (size_t i = 0; i < d.size(); ++i) {
               const Vec2d uv = l.direction_to_uv(d[i].normalized());
               out.mutable_at(i, 0) = uv.x(), out.mutable_at(i, 1) = uv.y();
             }
             return out;
           }, py::arg("dirs"), "(u, v) (N, 2) of directions (N, 3) (normalised here).")
      .def("uv_to_direction", [](const EnvironmentLight& l, const DoubleArray& uv) {
             if (uv.ndim() != 2 || uv.shape(1) != 2) throw_invalid("uv must have shape (N, 2)");
             std::vector<Vec3d> d(uv.shape(0));
             for (size_t i = 0; i < d.size(); ++i) {
               if (!std::isfinite(uv.at(i, 0)) || !std::isfinite(uv.at(i, 1))) throw_invalid("uv must be finite");
               d[i] = l.uv_to_direction(Vec2d(uv.at(i, 0), uv.at(i, 1)));
             }
             return points_to_array(d);
           }, py::arg("uv"), "World directions (N, 3) of (u, v) (N, 2).")
      .def_static("rotation_about_y", [](double degrees) { return matrix_to_array(EnvironmentLight::rotation_about_y(degrees)); },
          py::arg("degrees"),
          "The 3 x 3 rotation about +y by degrees (right-handed: +x turns toward -z).")
      .def_property_readonly("scale", &EnvironmentLight::scale)
      .def_property_readonly("rotation", [](const EnvironmentLight& l) { return matrix_to_array(l.rotation()); },
          "The 3 x 3 rotation, map frame -> world.")
      .def(py::pickle(
          [](const EnvironmentLight& l) -> py::tuple {
            // A map read from a file travels as its path (the file must be readable where it is unpickled).
            if (!l.source().empty()) return py::make_tuple(l.source(), l.scale(), matrix_to_array(l.rotation()));
            py::array_t<float> image({py::ssize_t(l.height()), py::ssize_t(l.width()), py::ssize_t(3)});
            float* p = image.mutable_data();
            for (const Vec3d& texel : l.texels()) {
              for (int k = 0; k < 3; ++k) *p++ = float(texel[k]);  // exact: the texels came from floats
            }
            return py::make_tuple(image, l.scale(), matrix_to_array(l.rotation()));
          },
          [](const py::tuple& t) {
            check_state(t, 3, "EnvironmentLight");
            if (py::isinstance<py::str>(t[0])) {
              return environment_from_file(py::cast<std::string>(t[0]), py::cast<double>(t[1]), to_rotation(t[2], "rotation"));
            }
            return std::make_shared<EnvironmentLight>(to_image(t[0], "EnvironmentLight: image"), py::cast<double>(t[1]), to_rotation(t[2], "rotation"));
          }));

  py::class_<ConstantEnvironment, Light, std::shared_ptr<ConstantEnvironment>>(m, "ConstantEnvironment",
      "Uniform radiance [W/(m^2 sr)] from every direction; sampling 'cosine' (about the point's normal, when given) "
      "or 'uniform' (the sphere). Irradiance pi L.")
      .def(py::init([](const py::object& radiance, const std::string& sampling) {
             if (sampling != "cosine" && sampling != "uniform") throw_invalid("ConstantEnvironment: sampling must be 'cosine' or 'uniform' (got '", sampling, "')");
             return std::make_shared<ConstantEnvironment>(to_illuminant(radiance, "ConstantEnvironment: radiance"),
                 sampling == "cosine" ? ConstantEnvironment::Sampling::kCosine : ConstantEnvironment::Sampling::kUniform);
           }),
           py::arg("radiance"), py::arg("sampling") = "cosine")
      .def(py::pickle([](const ConstantEnvironment& l) { return py::make_tuple(color_state(l.radiance()), int(l.sampling())); },
                      [](const py::tuple& t) {
                        check_state(t, 2, "ConstantEnvironment");
                        return std::make_shared<ConstantEnvironment>(color_from_state(t[0]), ConstantEnvironment::Sampling(py::cast<int>(t[1])));
                      }));

}

}  // namespace

void bind_lights(py::module_& m) {
  py::class_<Light, std::shared_ptr<Light>>(m, "Light",
      "A light (shared/SHADING.md section 5). Methods evaluate RGB rendering, vectorised over N points.")
      .def_property_readonly("type", [](const Light& l) { return type_name(l.type()); },
          "'delta_position' (point, spot), 'area' (meshes, spheres) or 'infinite' (sun, environments).")
      .def_property_readonly("is_delta", &Light::is_delta)
      .def_property_readonly("is_infinite", &Light::is_infinite)
      .def_property_readonly("power", &Light::power,
          "Emitted power [W] as luminance Y of the RGB power (infinite lights: through the disc of the scene "
          "radius given to preprocess, 1 m until then).")
      .def("preprocess", [](Light& l, const py::object& centre, double radius) { l.preprocess(to_point(centre, "centre"), radius); },
          py::arg("centre"), py::arg("radius"), "Tells the light the scene's bounding sphere (centre [m], radius [m]).")
      .def("sample_li", &sample_li, py::arg("points"), py::arg("normals"), py::arg("u"),
          "Samples a direction toward the light from each point.\n\n"
          "points: (N, 3) [m]; normals: (N, 3) unit geometric normals (rows may be 0) or None; u: (N, 2) in [0, 1).\n"
          "Returns (wi (N, 3) unit toward the light, L (N, 3) RGB radiance arriving [W/(m^2 sr)] (point and spot: "
          "I/r^2), pdf (N,) per steradian (delta lights: 1), distance (N,) [m] (infinite lights: inf)). A point the "
          "light cannot reach gets wi = 0, L = 0, pdf = 0, distance = 0.")
      .def("pdf_li", &pdf_li, py::arg("points"), py::arg("normals"), py::arg("wi"), py::arg("p_light") = py::none(),
          py::arg("n_light") = py::none(),
          "The solid-angle density (N,) with which sample_li picks unit wi (N, 3) at points (N, 3). Area lights "
          "need the point p_light (N, 3) where the ray along wi hits the light and its normal n_light (N, 3).")
      .def("Le", &Le, py::arg("dirs"), "Infinite lights: RGB radiance (N, 3) seen looking along unit dirs (N, 3); 0 for others.")
      .def("L", &L, py::arg("points"), py::arg("normals"), py::arg("dirs"),
          "Area lights: RGB radiance (N, 3) leaving points (N, 3) with the light's front normals (N, 3) toward unit dirs (N, 3).")
      .def("__repr__", &Light::describe);

  py::class_<LightSampler>(m, "LightSampler",
      "Chooses one light per sample, in proportion to power ('power') or uniformly ('uniform'). Build it after "
      "preprocess() of infinite lights.")
      .def(py::init([](const std::vector<LightPtr>& lights, const std::string& strategy) {
             if (strategy != "power" && strategy != "uniform") throw_invalid("LightSampler: strategy must be 'power' or 'uniform' (got '", strategy, "')");
             return LightSampler(lights, strategy == "power" ? LightSampler::Strategy::kPower : LightSampler::Strategy::kUniform);
           }),
           py::arg("lights"), py::arg("strategy") = "power")
      .def("sample", [](const LightSampler& s, const py::object& u_object) {
             const Samples u = to_samples(u_object, "u", 1);
             py::array_t<long long> index(py::ssize_t(u.rows));
             std::vector<double> p(u.rows);
             for (size_t i = 0; i < u.rows; ++i) {
               const auto chosen = s.sample(u.values[i]);
               if (!chosen) throw_invalid("LightSampler: no lights to sample");
               index.mutable_at(i) = (long long)chosen->index, p[i] = chosen->probability;
             }
             return py::make_tuple(index, values_to_array(p));
           }, py::arg("u"), "(index (N,) int, probability (N,)) for u (N,) in [0, 1).")
      .def("pmf", &LightSampler::pmf, py::arg("index"))
      .def("__len__", &LightSampler::size)
      .def(py::pickle([](const LightSampler& s) { return py::make_tuple(s.lights(), int(s.strategy())); },
                      [](const py::tuple& t) {
                        const int strategy = t.size() == 2 ? py::cast<int>(t[1]) : -1;
                        if (strategy != int(LightSampler::Strategy::kPower) && strategy != int(LightSampler::Strategy::kUniform)) {
                          throw_invalid("LightSampler: bad pickle state");
                        }
                        return LightSampler(py::cast<std::vector<LightPtr>>(t[0]), LightSampler::Strategy(strategy));
                      }));
  bind_finite_lights(m);
  bind_environment_lights(m);
}

}  // namespace refracta
