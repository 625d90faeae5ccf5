// Python bindings of scenes, cameras, lights and image files (cpp/refracta/scene, shading).
#include "refracta/bindings/bind_scene.h"

#include "refracta/scene/image_io.h"
#include "refracta/scene/obj_loader.h"
#include "refracta/shading/tonemap.h"

#include <cmath>
#include <optional>

namespace refracta {

namespace {

Vec3d to_rgb(const py::handle& value, const char* what) { return to_point(value, what); }

Material material_from(const py::object& kd, const py::object& ks, double ns, double alpha = 1.0) {
  Material m;
  m.kd = to_rgb(kd, "kd");
  m.ks = to_rgb(ks, "ks");
  m.ns = ns;
  m.alpha = alpha;
  m.validate();
  return m;
}

std::vector<Eigen::Vector2d> to_uvs(const py::object& object, size_t count) {
  DoubleArray array;
  try {
    array = py::cast<DoubleArray>(object);
  } catch (const py::cast_error&) {
    throw_invalid("uvs must be a float array of shape (N, 2)");
  }
  if (array.ndim() != 2 || array.shape(1) != 2 || size_t(array.shape(0)) != count) {
    throw_invalid("uvs must have shape (", count, ", 2): one per vertex");
  }
  std::vector<Eigen::Vector2d> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = Eigen::Vector2d(array.at(i, 0), array.at(i, 1));
    if (!std::isfinite(out[i].x()) || !std::isfinite(out[i].y())) throw_invalid("uvs must be finite");
  }
  return out;
}

DoubleArray image_to_array(const Image& image) {
  DoubleArray out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

Image array_to_image(const py::object& object) {
  py::array_t<float, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(object);
  } catch (const py::cast_error&) {
    throw_invalid("image must be a float array of shape (H, W, C)");
  }
  if (array.ndim() == 2) array = array.reshape({array.shape(0), array.shape(1), py::ssize_t(1)});
  if (array.ndim() != 3 || array.shape(2) < 1 || array.shape(2) > 4 || array.shape(0) < 1 || array.shape(1) < 1) {
    throw_invalid("image must have shape (H, W), (H, W, 1..4)");
  }
  Image image(int(array.shape(1)), int(array.shape(0)), int(array.shape(2)));
  std::copy(array.data(), array.data() + array.size(), image.pixels.begin());
  for (float v : image.pixels) {
    if (!std::isfinite(v)) throw_invalid("image must be finite (found ", v, ")");
  }
  return image;
}

// Exposure, tone mapping and transfer curve for display (shading/tonemap.h; alpha untouched).
// gamma: 'srgb', 'linear' or a number g in [1, 3] (p = l^(1/g)).
void encode_for_display(Image& image, double exposure, const std::string& tonemap_name, const py::object& gamma,
                        std::optional<double> key, std::optional<double> white) {
  DisplaySettings settings;
  settings.exposure = exposure;
  settings.tonemap = parse_tonemap(tonemap_name);
  settings.key = key;
  settings.white = white;
  if (py::isinstance<py::str>(gamma)) {
    const std::string name = py::cast<std::string>(gamma);
    if (name == "srgb") {
      settings.transfer = Transfer::kSrgb;
    } else if (name == "linear") {
      settings.transfer = Transfer::kGamma, settings.gamma = 1.0;
    } else {
      throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3] (got '", name, "')");
    }
  } else {
    try {
      settings.transfer = Transfer::kGamma, settings.gamma = py::cast<double>(gamma);
    } catch (const py::cast_error&) {
      throw_invalid("gamma must be 'srgb', 'linear' or a number in [1, 3]");
    }
  }
  tonemap_image(image, settings);
}

}  // namespace

py::array_t<float> image_to_float32(const Image& image) {
  py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

void bind_scene(py::module_& m) {
  py::class_<RenderScene, std::shared_ptr<RenderScene>>(m, "Scene", R"doc(
Geometry (Embree) with Blinn-Phong materials, a sun and a sky. Materials: kd (diffuse albedo,
RGB in [0, 1]), ks (specular albedo), ns (Phong exponent). Units: metres, y up.)doc")
      .def(py::init<>())
      .def("add_mesh",
           [](RenderScene& s, const py::object& vertices, const py::object& triangles, const py::object& kd,
              const py::object& ks, double ns, const py::object& uvs, std::optional<std::string> texture, double alpha) {
             Mesh mesh;
             mesh.vertices = to_points(vertices, "vertices");
             const std::vector<Vec3d>& v = mesh.vertices;
             py::array_t<long long, py::array::c_style | py::array::forcecast> t;
             try {
               t = py::cast<decltype(t)>(triangles);
             } catch (const py::cast_error&) {
               throw_invalid("triangles must be an integer array of shape (M, 3)");
             }
             if (t.ndim() != 2 || t.shape(1) != 3) throw_invalid("triangles must have shape (M, 3)");
             std::vector<std::array<int, 3>> tris(t.shape(0));
             for (py::ssize_t i = 0; i < t.shape(0); ++i) {
               for (int k = 0; k < 3; ++k) tris[i][k] = int(std::clamp<long long>(t.at(i, k), -1, 1LL << 30));
             }
             mesh.triangles = tris;
             if (!uvs.is_none()) mesh.uvs = to_uvs(uvs, v.size());
             Material material = material_from(kd, ks, ns, alpha);
             if (texture) material.kd_texture = s.geometry.textures().add(*texture);
             return s.geometry.add_mesh(mesh, material);
           },
           py::arg("vertices"), py::arg("triangles"), py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5),
           py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0), py::arg("ns") = 1.0, py::arg("uvs") = py::none(),
           py::arg("texture") = py::none(), py::arg("alpha") = 1.0,
           "Add a triangle mesh: vertices (N, 3) [m], triangles (M, 3) indices; optional uvs (N, 2) texture\n"
           "coordinates (u right, v up) and a texture image file multiplying kd; alpha < 1 makes it transparent\n"
           "in render_raster. Returns its id.")
      .def("add_obj",
           [](RenderScene& s, const std::string& path, const py::object& offset, double scale) {
             const Vec3d shift = to_point(offset, "offset");
             if (!(scale > 0.0) || !std::isfinite(scale)) throw_invalid("scale must be > 0 (got ", scale, ")");
             py::list ids;
             for (auto& part : load_obj(path)) {
               for (auto& v : part.mesh.vertices) v = v * scale + shift;
               if (!part.texture.empty()) part.material.kd_texture = s.geometry.textures().add(part.texture);
               ids.append(s.geometry.add_mesh(part.mesh, part.material));
             }
             return ids;
           },
           py::arg("path"), py::arg("offset") = py::make_tuple(0.0, 0.0, 0.0), py::arg("scale") = 1.0,
           "Add a Wavefront OBJ (+ MTL: Kd, Ks, Ns, map_Kd with the file's texture coordinates) file, scaled\n"
           "then offset; returns the geometry ids. A missing OBJ, MTL or texture raises refracta.IoError.")
      .def("add_ground",
           [](RenderScene& s, double height, double size, const py::object& kd, const py::object& ks, double ns,
              std::optional<std::string> texture, double texture_size) {
             Mesh mesh = ground_mesh(height, 0.5 * size);
             Material material = material_from(kd, ks, ns);
             if (texture) {
               if (!(texture_size > 0.0) || !std::isfinite(texture_size)) {
                 throw_invalid("texture_size must be > 0 (got ", texture_size, ")");
               }
               material.kd_texture = s.geometry.textures().add(*texture);
               for (const auto& v : mesh.vertices) mesh.uvs.emplace_back(v.x() / texture_size, -v.z() / texture_size);
             }
             return s.geometry.add_mesh(mesh, material);
           },
           py::arg("height") = 0.0, py::arg("size") = 20000.0, py::arg("kd") = py::make_tuple(0.3, 0.3, 0.3),
           py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0), py::arg("ns") = 1.0, py::arg("texture") = py::none(),
           py::arg("texture_size") = 1.0,
           "Add a square ground of side `size` [m] at y = height, centred on the origin; an optional texture\n"
           "repeats every texture_size [m] (u along +x, v along -z).")
      .def("add_billboard",
           [](RenderScene& s, const py::object& centre, double width, double height, const std::string& texture,
              const py::object& facing, const py::object& kd) {
             const Vec3d c = to_point(centre, "centre"), f = to_point(facing, "facing");
             Vec3d across(f.z(), 0.0, -f.x());
             if (across.norm() == 0.0) throw_invalid("facing must have a horizontal component");
             if (!(width > 0.0) || !(height > 0.0)) throw_invalid("width and height must be > 0");
             across = across.normalized() * (0.5 * width);
             const Vec3d up(0.0, 0.5 * height, 0.0);
             Mesh mesh;
             mesh.vertices = {c - across - up, c + across - up, c + across + up, c - across + up};
             mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
             mesh.uvs = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
             Material material = material_from(kd, py::make_tuple(0.0, 0.0, 0.0), 1.0);
             material.kd_texture = s.geometry.textures().add(texture);
             return s.geometry.add_mesh(mesh, material);
           },
           py::arg("centre"), py::arg("width"), py::arg("height"), py::arg("texture"),
           py::arg("facing") = py::make_tuple(-1.0, 0.0, 0.0), py::arg("kd") = py::make_tuple(1.0, 1.0, 1.0),
           "Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at\n"
           "`centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the\n"
           "-x side), upright.")
      .def("add_box",
           [](RenderScene& s, const py::object& centre, const py::object& size, const py::object& kd,
              const py::object& ks, double ns, double alpha) {
             const Mesh mesh = box_mesh(to_point(centre, "centre"), to_point(size, "size"));
             return s.geometry.add_mesh(mesh.vertices, mesh.triangles, material_from(kd, ks, ns, alpha));
           },
           py::arg("centre"), py::arg("size"), py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5),
           py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0), py::arg("ns") = 1.0, py::arg("alpha") = 1.0,
           "Add an axis-aligned box: centre (3,) and size (3,) [m]; alpha < 1: transparent in render_raster.")
      .def("add_sphere",
           [](RenderScene& s, const py::object& centre, double radius, const py::object& kd, const py::object& ks,
              double ns) {
             return s.geometry.add_spheres({to_point(centre, "centre")}, {radius}, material_from(kd, ks, ns));
           },
           py::arg("centre"), py::arg("radius"), py::arg("kd") = py::make_tuple(0.5, 0.5, 0.5),
           py::arg("ks") = py::make_tuple(0.0, 0.0, 0.0), py::arg("ns") = 1.0, "Add a sphere (exact, not tessellated).")
      .def("set_sun",
           [](RenderScene& s, const py::object& direction, const py::object& radiance, double angular_diameter) {
             Sun sun;
             sun.direction = to_point(direction, "direction");
             sun.radiance = to_rgb(radiance, "radiance");
             sun.angular_diameter = angular_diameter;
             sun.validate();
             s.lighting.sun = sun;
           },
           py::arg("direction"), py::arg("radiance"), py::arg("angular_diameter") = 0.53,
           "The sun: direction toward it, disc radiance (RGB), angular diameter [deg].")
      .def("set_sky",
           [](RenderScene& s, const py::object& horizon, const py::object& zenith,
              std::optional<std::string> environment, double scale) {
             Sky sky;
             sky.horizon = horizon.is_none() ? sky.horizon : to_rgb(horizon, "horizon");
             sky.zenith = zenith.is_none() ? sky.horizon : to_rgb(zenith, "zenith");
             sky.scale = scale;
             if (environment) {
               sky.textures = s.geometry.shared_textures();
               sky.environment = s.geometry.textures().add(*environment);
             }
             sky.validate();
             s.lighting.sky = sky;
           },
           py::arg("horizon") = py::none(), py::arg("zenith") = py::none(), py::arg("environment") = py::none(),
           py::arg("scale") = 1.0,
           "Sky radiance toward the horizon (and below) and straight up (default: same, a constant sky), or an\n"
           "equirectangular environment map file (y up, top row the zenith, centre column along +x, radiance\n"
           "times `scale`; 8/16-bit files are sRGB-decoded).")
      .def("add_spot_light",
           [](RenderScene& s, const py::object& position, const py::object& direction, double angle,
              const py::object& intensity, double radius) {
             SpotLight spot;
             spot.position = to_point(position, "position");
             spot.direction = to_point(direction, "direction");
             spot.angle = angle;
             spot.intensity = to_rgb(intensity, "intensity");
             spot.radius = radius;
             spot.validate();
             s.lighting.spots.push_back(spot);
             return s.lighting.spots.size() - 1;
           },
           py::arg("position"), py::arg("direction"), py::arg("angle") = 60.0,
           py::arg("intensity") = py::make_tuple(100.0, 100.0, 100.0), py::arg("radius") = 0.0,
           "Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg] with\n"
           "`intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 makes it a disc (area light) whose\n"
           "shadows are sampled soft. Returns its index.")
      .def_property("shadows", [](const RenderScene& s) { return s.lighting.shadows; },
                    [](RenderScene& s, bool on) { s.lighting.shadows = on; })
      .def_property_readonly("geometry_count", [](const RenderScene& s) { return s.geometry.geometry_count(); })
      .def("intersect",
           [](const RenderScene& s, const py::object& origin, const py::object& direction) -> py::object {
             const Vec3d d = to_point(direction, "direction");
             if (d.norm() == 0.0) throw_invalid("direction must be non-zero");
             const auto hit = s.geometry.intersect(to_point(origin, "origin"), d.normalized(), 1e7);
             if (!hit) return py::none();
             return py::make_tuple(points_to_array({hit->point}).reshape({py::ssize_t(3)}), hit->t, hit->geometry);
           },
           py::arg("origin"), py::arg("direction"),
           "First hit of a straight ray: (point, distance, geometry id), or None.");

  py::class_<Camera>(m, "Camera", R"doc(
Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360): vfov is the
vertical field of view [deg]. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred at
(i + 0.5, j + 0.5).)doc")
      .def(py::init([](const py::object& position, const py::object& look_at, const py::object& up, double vfov,
                       int width, int height) {
             return Camera(to_point(position, "position"), to_point(look_at, "look_at"), to_point(up, "up"), vfov,
                           width, height);
           }),
           py::arg("position"), py::arg("look_at"), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
           py::arg("vfov") = 45.0, py::arg("width") = 640, py::arg("height") = 360)
      .def("ray",
           [](const Camera& c, double u, double v) {
             if (!std::isfinite(u) || !std::isfinite(v)) throw_invalid("u and v must be finite");
             return py::make_tuple(points_to_array({c.position()}).reshape({py::ssize_t(3)}),
                                   points_to_array({c.direction(u, v)}).reshape({py::ssize_t(3)}));
           },
           py::arg("u"), py::arg("v"), "(origin, unit direction) of the ray through pixel coordinates (u, v).")
      .def("project",
           [](const Camera& c, const py::object& points) {
             bool single = false;
             std::vector<Vec3d> p = to_points(points, "points", &single);
             for (auto& x : p) x = c.project(x);
             DoubleArray out = points_to_array(p);
             return single ? py::object(out.reshape({py::ssize_t(3)})) : py::object(out);
           },
           py::arg("points"), "(u, v, depth) per point (N, 3); depth [m] along the view axis, <= 0 behind.")
      .def("pick",
           [](const Camera& c, const RenderScene& s, double u, double v) -> py::object {
             if (!std::isfinite(u) || !std::isfinite(v)) throw_invalid("u and v must be finite");
             const auto hit = s.geometry.intersect(c.position(), c.direction(u, v), 1e7);
             if (!hit) return py::none();
             return points_to_array({hit->point}).reshape({py::ssize_t(3)});
           },
           py::arg("scene"), py::arg("u"), py::arg("v"),
           "The scene point seen at pixel (u, v) without atmosphere (straight ray), or None.")
      .def_property_readonly("position", [](const Camera& c) { return points_to_array({c.position()}).reshape({py::ssize_t(3)}); })
      .def("resized", &Camera::resized, py::arg("width"), py::arg("height"),
           "The same view at another image size (vertical field of view kept).")
      .def_property_readonly("width", &Camera::width)
      .def_property_readonly("height", &Camera::height)
      .def_property_readonly("vfov", &Camera::vfov)
      .def("__repr__", [](const Camera& c) {
        return concat("Camera(position=(", c.position().x(), ", ", c.position().y(), ", ", c.position().z(),
                      "), vfov=", c.vfov(), ", size=", c.width(), "x", c.height(), ")");
      });

  m.def("_write_image",
        [](const std::string& path, const py::object& array, double exposure, const std::string& tonemap_name,
           const py::object& gamma, std::optional<double> key, std::optional<double> white) {
          Image image = array_to_image(array);
          if (is_float_format(path)) {
            if (!(exposure > 0.0) || !std::isfinite(exposure)) throw_invalid("exposure must be > 0 (got ", exposure, ")");
            for (float& v : image.pixels) v *= float(exposure);
          } else {
            encode_for_display(image, exposure, tonemap_name, gamma, key, white);
          }
          py::gil_scoped_release release;
          write_image(path, image);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure"), py::arg("tonemap"), py::arg("gamma"),
        py::arg("key") = py::none(), py::arg("white") = py::none());
  m.def("_display",
        [](const py::object& array, double exposure, const std::string& tonemap_name, const py::object& gamma,
           std::optional<double> key, std::optional<double> white) {
          Image image = array_to_image(array);
          encode_for_display(image, exposure, tonemap_name, gamma, key, white);
          return image_to_float32(image);
        },
        py::arg("image"), py::arg("exposure"), py::arg("tonemap"), py::arg("gamma"), py::arg("key") = py::none(),
        py::arg("white") = py::none());
  m.def("_read_image", [](const std::string& path) { return image_to_float32(read_image(path)); }, py::arg("path"));
}

}  // namespace refracta
