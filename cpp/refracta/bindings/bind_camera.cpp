// Python bindings of the camera (scene/camera.h): pinhole, thin lens, the photographer's
// constructors and the geometric jitter.
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/render/picking.h"
#include "refracta/render/scene_building.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace refracta {

namespace {

using Sensor = std::pair<double, double>;  // (width, height) [mm]
using D = CameraDefaults;
constexpr Sensor kFullFrame(D::kSensorWidth, D::kSensorHeight);
constexpr int kPhotoWidth = D::kPhotoWidth, kPhotoHeight = D::kPhotoHeight;
constexpr int kWidth = D::kWidth, kHeight = D::kHeight;
using Side = std::optional<int>;  // an image side that may be left out (Camera::image_size)

// A photographic camera's image: a side left out follows the sensor's shape.
std::pair<int, int> photo_size(Side width, Side height, const Sensor& sensor_mm) {
  return Camera::photographic_size(width, height, sensor_mm.first, sensor_mm.second);
}

double photographic_vfov_of(double focal_length_mm, const Sensor& sensor_mm, int width, int height) {
  return Camera::photographic_vfov(focal_length_mm, sensor_mm.first, sensor_mm.second, width, height);
}

// Camera.framing's first argument: a Scene (framing_bounds) or (lower, upper) corners.
std::pair<Vec3d, Vec3d> bounds_of(const py::object& scene_or_bounds) {
  if (py::isinstance<RenderScene>(scene_or_bounds)) {
    return framing_bounds(py::cast<const RenderScene&>(scene_or_bounds));
  }
  const py::object& bounds = scene_or_bounds;
  if (!py::isinstance<py::sequence>(bounds) || py::isinstance<py::str>(bounds)) {
    throw_invalid("Camera.framing: give a Scene or its bounds (lower, upper)");
  }
  if (py::len(bounds) != 2) throw_invalid("Camera.framing: bounds must be (lower, upper)");
  return {to_point(bounds[py::int_(0)], "Camera.framing: bounds[0]"), to_point(bounds[py::int_(1)], "Camera.framing: bounds[1]")};
}

// Pickled as its constructor's arguments (and jitter, and lens): the copy's rays are bit-identical.
py::tuple camera_state(const Camera& c) {
  auto xyz = [](const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); };
  return py::make_tuple(xyz(c.position()), xyz(c.look_at()), xyz(c.up_hint()), c.vfov(), c.width(), c.height(),
                        c.jitter(), c.aperture_diameter(), c.focus_distance());
}

Camera camera_from_state(const py::tuple& t) {  // 6 items (no jitter), 7 (no lens) or 9
  if (t.size() != 6 && t.size() != 7 && t.size() != 9) throw_invalid("Camera: bad pickle state (", t.size(), " items)");
  const std::vector<float> jitter = t.size() >= 7 ? py::cast<std::vector<float>>(t[6]) : std::vector<float>();
  const auto lens = [&t](size_t i) { return t.size() == 9 ? py::cast<double>(t[i]) : 0.0; };
  return Camera::restore(to_point(t[0], "position"), to_point(t[1], "look_at"), to_point(t[2], "up"), py::cast<double>(t[3]),
                         py::cast<int>(t[4]), py::cast<int>(t[5]), jitter, lens(7), lens(8));
}

Camera jittered(const Camera& c, const py::object& angles) {
  Image map = to_image(angles, "Camera.jittered: angles", /*raw=*/true);  // finite: Camera::jittered checks
  if (map.height != c.height() || map.width != c.width() || map.channels != 2) {
    throw_invalid("Camera.jittered: angles must have shape (height, width, 2) = (", c.height(), ", ", c.width(), ", 2)");
  }
  return c.jittered(std::move(map.pixels));
}

py::object jitter_array(const Camera& c) {
  if (c.jitter().empty()) return py::none();
  return py::array_t<float>({py::ssize_t(c.height()), py::ssize_t(c.width()), py::ssize_t(2)}, c.jitter().data());
}

// The photographer's constructors: framing, photographic, eye_level.
void bind_camera_constructors(py::class_<Camera>& camera) {
  camera.def_static(
      "framing",
      [](const py::object& scene_or_bounds, const py::object& direction, double vfov, Side width, Side height,
         const py::object& up) {
        const auto [lower, upper] = bounds_of(scene_or_bounds);
        const auto [w, h] = Camera::image_size(width, height, kWidth, kHeight, double(kWidth) / kHeight);
        return Camera::framing(lower, upper, to_point(direction, "Camera.framing: direction"), to_point(up, "Camera.framing: up"), vfov, w, h);
      },
      py::arg("scene_or_bounds"), py::arg("direction") = py::make_tuple(-1.0, -0.5, -1.0), py::arg("vfov") = D::kVfov,
      py::arg("width") = py::none(), py::arg("height") = py::none(), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
      DOC(refracta, Camera, framing));
  camera.def_static("photographic_vfov", &photographic_vfov_of, py::arg("focal_length_mm"),
                    py::arg("sensor_mm") = kFullFrame, py::arg("width") = kPhotoWidth, py::arg("height") = kPhotoHeight,
                    DOC(refracta, Camera, photographic_vfov));
  camera.def_static(
      "photographic",
      [](const py::object& position, const py::object& look_at, double focal_length_mm, const Sensor& sensor_mm,
         Side width, Side height, const py::object& up, std::optional<double> f_number, std::optional<double> focus_distance) {
        const auto [w, h] = photo_size(width, height, sensor_mm);
        return Camera::photographic(to_point(position, "Camera.photographic: position"), to_point(look_at, "Camera.photographic: look_at"), to_point(up, "Camera.photographic: up"),
                                    focal_length_mm, sensor_mm.first, sensor_mm.second, w, h, f_number,
                                    focus_distance);
      },
      py::arg("position"), py::arg("look_at"), py::arg("focal_length_mm"), py::arg("sensor_mm") = kFullFrame,
      py::arg("width") = py::none(), py::arg("height") = py::none(), py::kw_only(), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
      py::arg("f_number") = py::none(), py::arg("focus_distance") = py::none(),
      DOC(refracta, Camera, photographic));
  camera.def_static(
      "eye_level",
      [](const py::object& eye, const py::object& target, double eye_height, double focal_length_mm,
         const Sensor& sensor_mm, Side width, Side height, std::optional<double> f_number,
         std::optional<double> focus_distance) {
        const auto [w, h] = photo_size(width, height, sensor_mm);
        return Camera::eye_level(to_point(eye, "Camera.eye_level: eye"), to_point(target, "Camera.eye_level: target"), eye_height, focal_length_mm,
                                 sensor_mm.first, sensor_mm.second, w, h, f_number, focus_distance);
      },
      py::arg("eye"), py::arg("target"), py::arg("eye_height") = D::kEyeHeight, py::arg("focal_length_mm") = D::kFocalLength,
      py::arg("sensor_mm") = kFullFrame, py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
      py::arg("f_number") = py::none(), py::arg("focus_distance") = py::none(),
      DOC(refracta, Camera, eye_level));
}

}  // namespace

void bind_camera(py::module_& m) {
  py::class_<Camera> camera(m, "Camera", DOC(refracta, Camera));
  camera.def_property_readonly_static(
      "max_side", [](const py::object&) { return kMaxImageSide; }, "The longest image side [pixels] a camera takes: 2^24.");
  camera
      .def(py::init([](const py::object& position, const py::object& look_at, const py::object& up, double vfov,
                       Side width, Side height) {
             const auto [w, h] = Camera::image_size(width, height, kWidth, kHeight, double(kWidth) / kHeight);
             return Camera(to_point(position, "Camera: position"), to_point(look_at, "Camera: look_at"), to_point(up, "Camera: up"), vfov,
                           w, h);
           }),
           py::arg("position"), py::arg("look_at"), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0),
           py::arg("vfov") = D::kVfov, py::arg("width") = py::none(), py::arg("height") = py::none(),
           "width, height [pixels]: the image, 640 x 360 by default; one given alone, the other follows that\n"
           "16:9 shape (square pixels).")
      .def(
          "ray",
          [](const Camera& c, const py::object& u, const py::object& v) {
            bool single_u = false, single_v = false;
            const std::vector<double> us = to_values(u, "Camera.ray: u", &single_u);
            const std::vector<double> vs = to_values(v, "Camera.ray: v", &single_v);
            if (single_u && single_v) {
              return py::make_tuple(vector_to_array(c.position()), vector_to_array(c.pixel_direction(us[0], vs[0])));
            }
            if (!single_u && !single_v && us.size() != vs.size()) {
              throw_invalid("Camera.ray: u and v must have the same length (got ", us.size(), " and ", vs.size(), ")");
            }
            const size_t n = single_u ? vs.size() : us.size();
            std::vector<Vec3d> directions(n);
            for (size_t i = 0; i < n; ++i) directions[i] = c.pixel_direction(us[single_u ? 0 : i], vs[single_v ? 0 : i]);
            return py::make_tuple(points_to_array(std::vector<Vec3d>(n, c.position())), points_to_array(directions));
          },
          py::arg("u"), py::arg("v"),
          "(origin, unit direction) of the ray through pixel coordinates (u, v), the pixel's corner at its "
          "integers (its centre at x + 0.5); u and v numbers, or (N,) arrays (either may be a number): then "
          "(N, 3) origins and directions. Beyond [0, width] x [0, height] the pinhole's rays go on past the "
          "frame (overscan), as far as the view's half-space.")
      .def(
          "project",
          [](const Camera& c, const py::object& points, double earth_radius) {
            bool single = false;
            const std::vector<Vec3d> p = projected_over_sphere(c, earth_radius, to_points(points, "points", &single));
            return single ? py::object(vector_to_array(p[0])) : py::object(points_to_array(p));
          },
          py::arg("points"), py::arg("earth_radius") = std::numeric_limits<double>::infinity(),
          "(u, v, depth) per point (N, 3) through the pinhole; depth [m] along the view axis, <= 0 behind.\n"
          "earth_radius [m]: the scene is the flat frame of a CurvedEarth of this radius; the points are\n"
          "projected along the true geometry's straight lines, where pick(scene, u, v,\n"
          "refracta.without_refraction(field)) finds them (inf: the scene's own straight lines).")
      .def(
          "pick",
          [](const Camera& c, const RenderScene& s, double u, double v, const std::optional<std::shared_ptr<IndexField>>& field,
             std::optional<double> max_length) -> py::object {
            const auto point = picked_point(s.geometry, c, field.value_or(nullptr), u, v, max_length);
            return point ? py::object(vector_to_array(*point)) : py::object(py::none());
          },
          py::arg("scene"), py::arg("u"), py::arg("v"), py::arg("field") = py::none(), py::arg("max_length") = py::none(),
          "The scene point [m] seen at film position (u, v) [pixels; a pixel's centre at +0.5; in [0, width]\n"
          "x [0, height], else ValueError], or None.\n"
          "field=None: along the straight ray of the scene's own frame. With a field: along the path through\n"
          "it, at most max_length [m] long (None: as far as scene coordinates go; curved paths by the\n"
          "render's default options). Over a CurvedEarth's flat frame the point seen without the air is\n"
          "pick(scene, u, v, refracta.without_refraction(field)): the scene's own straight ray would\n"
          "cross a flat Earth.")
      .def_property_readonly("position", [](const Camera& c) { return vector_to_array(c.position()); })
      .def_property_readonly("look_at", [](const Camera& c) { return vector_to_array(c.look_at()); })
      .def_property_readonly("up", [](const Camera& c) { return vector_to_array(c.up_hint()); }, DOC(refracta, Camera, up_hint))
      .def("jittered", &jittered, py::arg("angles"), DOC(refracta, Camera, jittered))
      .def_property_readonly("jitter", &jitter_array, "The angle map (height, width, 2) [rad] of a jittered camera, or None.")
      .def(py::pickle(&camera_state, &camera_from_state))
      .def("with_lens", &Camera::with_lens, py::arg("aperture_diameter"), py::arg("focus_distance"), DOC(refracta, Camera, with_lens))
      .def_property_readonly("aperture_diameter", &Camera::aperture_diameter, DOC(refracta, Camera, aperture_diameter))
      .def_property_readonly("focus_distance", &Camera::focus_distance, "The depth [m] of the plane in focus, 0 for a pinhole.")
      .def("resized", &Camera::resized, py::arg("width"), py::arg("height"), DOC(refracta, Camera, resized))
      .def("without_jitter", &Camera::without_jitter, DOC(refracta, Camera, without_jitter))
      .def_property_readonly("width", &Camera::width)
      .def_property_readonly("height", &Camera::height)
      .def_property_readonly("vfov", &Camera::vfov)
      .def_property_readonly("pixel_angle", &Camera::pixel_angle, DOC(refracta, Camera, pixel_angle))
      .def("__repr__", &Camera::describe)
      .def(
          "__eq__",
          [](const Camera& a, const py::object& other) -> py::object {
            if (!py::isinstance<Camera>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            return py::bool_(camera_state(a).equal(camera_state(py::cast<const Camera&>(other))));
          },
          "The same view, image size, jitter and lens (what a pickle keeps: their rays are bit-identical).")
      .def("__hash__", [](const Camera& c) {  // a camera does not change: usable as a key
        py::tuple state = camera_state(c);
        state[6] = py::len(state[6]);  // the jitter map's size stands for it (equal cameras, equal hashes)
        return py::hash(state);
      });
  bind_camera_constructors(camera);
}

}  // namespace refracta
