// The bindings' Python -> C++ conversions (convert.h): one rule per kind of input.
#include "refracta/bindings/convert.h"

#include "refracta/core/error.h"
#include "refracta/core/spectrum.h"
#include "refracta/shading/environment_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace refracta {

namespace {

std::string shape_of(const DoubleArray& array) {
  std::string shape = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(array.shape(i));
  return shape + (array.ndim() == 1 ? ",)" : ")");
}

// real_array with `message` in place of the cast error of inputs that are not numbers at all;
// bools refused unless `bools` (a point (True, 0, 1) or a triangle of True is a mistake).
DoubleArray numbers(const py::handle& object, const char* what, const char* message, bool bools = false) {
  try {
    return real_array(object, what, bools);
  } catch (const py::cast_error&) {
    throw_invalid(what, message);
  }
}

// `object` as a numpy array of integer or float dtype, or bool with `bools` (not yet cast);
// ValueError naming `what` otherwise (numpy's cast would turn '1.5' into 1.5 or fail naming nothing).
py::array real_dtype_array(const py::handle& object, const char* what, bool bools = true) {
  py::array raw;
  try {
    raw = py::array::ensure(object);
  } catch (const py::error_already_set&) {
    raw = py::array();
  }
  if (!raw) throw_invalid(what, " must be an array of numbers");
  const char kind = raw.dtype().kind();
  if (!(kind == 'b' && bools) && kind != 'i' && kind != 'u' && kind != 'f') {
    throw_invalid(what, " must hold real numbers (got dtype ", py::str(raw.dtype()).cast<std::string>(), ")");
  }
  return raw;
}

}  // namespace

DoubleArray real_array(const py::handle& object, const char* what, bool bools) {
  return py::cast<DoubleArray>(real_dtype_array(object, what, bools));
}

std::optional<double> number_of(const py::handle& value) {
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) ||
      py::isinstance(value, py::module_::import("numpy").attr("bool_"))) {
    return std::nullopt;
  }
  try {
    return py::cast<double>(value);
  } catch (const py::cast_error&) {
    return std::nullopt;
  }
}

double to_number(const py::handle& value, const char* what) {
  const std::optional<double> number = number_of(value);
  if (!number) throw_invalid(what, " must be a number (got ", py::repr(value).cast<std::string>(), ")");
  return *number;
}

namespace {

// to_points, its messages for `one_point` (to_point's single (3,)) or for points (N, 3) or (3,).
std::vector<Vec3d> points_of(const py::handle& object, const char* what, bool* single, bool one_point) {
  const char* shapes = one_point ? "(3,), one point (x, y, z)" : "(N, 3) or (3,)";
  const DoubleArray array = numbers(object, what, concat(" must be an array of numbers with shape ", shapes).c_str());
  const bool one = array.ndim() == 1;
  if (!((one && array.shape(0) == 3) || (!one_point && array.ndim() == 2 && array.shape(1) == 3))) {
    throw_invalid(what, " must have shape ", shapes, " (got ", shape_of(array), ")");
  }
  if (single) *single = one;
  const py::ssize_t count = one ? 1 : array.shape(0);
  std::vector<Vec3d> points(count);
  const double* data = array.data();
  for (py::ssize_t i = 0; i < count; ++i) {
    points[i] = Vec3d(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
    if (!is_finite(points[i])) {
      throw_invalid(what, one ? "" : concat("[", i, "]"), " must be finite (got (", points[i].x(), ", ",
                    points[i].y(), ", ", points[i].z(), "))");
    }
  }
  return points;
}

}  // namespace

std::vector<Vec3d> to_points(const py::handle& object, const char* what, bool* single) {
  return points_of(object, what, single, false);
}

Vec3d to_point(const py::handle& object, const char* what) { return points_of(object, what, nullptr, true)[0]; }

std::vector<double> to_values(const py::handle& object, const char* what, bool* single) {
  // Bools are not numbers (True would be 1: Camera.ray(True, False) was the ray through (1, 0)).
  const DoubleArray array = numbers(object, what, " must be a number or an array of numbers");
  if (array.ndim() > 1) throw_invalid(what, " must be a number or a 1-D array (got ", array.ndim(), " dimensions)");
  if (single) *single = array.ndim() == 0;
  std::vector<double> values(array.data(), array.data() + array.size());
  for (double v : values) {
    if (!std::isfinite(v)) throw_invalid(what, " must be finite (got ", v, ")");
  }
  return values;
}

Vec2d to_vec2(const py::handle& object, const char* what) {
  const std::vector<double> v = to_values(object, what);
  if (v.size() != 2) {
    std::string got;  // the values, not their count (wind=5 said "got 1")
    for (size_t i = 0; i < v.size() && i < 4; ++i) got += concat(i ? ", " : "", v[i]);
    throw_invalid(what, " must be two numbers (x, z) (got ", v.size() == 1 ? got : concat(v.size(), " numbers: ", got, v.size() > 4 ? ", ..." : ""), ")");
  }
  return {v[0], v[1]};
}

std::vector<Vec3d> to_unit_vectors(const py::handle& object, const char* what, size_t count, bool zero_ok,
                                   bool* single) {
  std::vector<Vec3d> v = to_points(object, what, single);
  if (count != kAnyCount && v.size() != count) {
    throw_invalid(what, " must have shape (", count, ", 3) (got ", v.size(), " rows)");
  }
  for (size_t i = 0; i < v.size(); ++i) {
    const double length = v[i].norm();
    if (zero_ok && length == 0.0) continue;
    if (!(std::abs(length - 1.0) <= kUnitTolerance)) {
      throw_invalid(what, "[", i, "] must be a unit vector", zero_ok ? " or zero" : "", " (got length ", length, ")");
    }
  }
  return v;
}

Vec3d to_rgb(const py::handle& value, const char* what) {
  // Not True / False: Diffuse(True) was a white reflectance.
  const DoubleArray array = numbers(value, what, " must be a number or an (r, g, b) triple");
  Vec3d rgb;
  if (array.size() == 1 && array.ndim() <= 1) {
    rgb.setConstant(array.data()[0]);
  } else if (array.ndim() == 1 && array.shape(0) == 3) {
    rgb = Vec3d(array.data()[0], array.data()[1], array.data()[2]);
  } else {
    throw_invalid(what, " must be a number or an (r, g, b) triple (got shape ", shape_of(array), ")");
  }
  if (!is_finite(rgb)) throw_invalid(what, " must be finite (got (", rgb.x(), ", ", rgb.y(), ", ", rgb.z(), "))");
  if (!(rgb.cwiseAbs().maxCoeff() <= kMaxRadiance)) {
    throw_invalid(what, " must be at most ", kMaxRadiance, " per channel (got (", rgb.x(), ", ", rgb.y(), ", ", rgb.z(),
                  ")): images are float32");
  }
  return rgb;
}

std::optional<Vec3d> to_optional_rgb(const py::object& value, const char* what) {
  if (value.is_none()) return std::nullopt;
  return to_rgb(value, what);
}

Color to_illuminant(const py::handle& value, const char* what) {
  const Vec3d rgb = to_rgb(value, what);
  if (!(rgb.minCoeff() >= 0.0)) {
    throw_invalid(what, " must be finite and >= 0 per channel (got (", rgb.x(), ", ", rgb.y(), ", ", rgb.z(), "))");
  }
  return Color::illuminant(rgb);
}

Samples to_samples(const py::handle& object, const char* what, int dims, size_t count) {
  const DoubleArray array = numbers(object, what, " must be an array of numbers in [0, 1)");
  Samples s;
  s.dims = dims;
  const bool rows_shape = array.ndim() == (dims == 1 ? 1 : 2) && (dims == 1 || array.shape(1) == dims);
  s.single = dims == 1 ? array.ndim() == 0 : (array.ndim() == 1 && array.shape(0) == dims);
  if (!rows_shape && !s.single) {
    throw_invalid(what, dims == 1 ? " must be a number or of shape (N,)" : concat(" must have shape (N, ", dims, ") or (", dims, ",)"),
                  " (got ", shape_of(array), ")");
  }
  s.rows = s.single ? 1 : size_t(array.shape(0));
  if (count != kAnyCount && s.rows != count) {
    throw_invalid(what, " must have shape (", count, dims == 1 ? "" : concat(", ", dims), "): one row per point (got ",
                  s.rows, " rows)");
  }
  s.values.assign(array.data(), array.data() + array.size());
  for (size_t i = 0; i < s.values.size(); ++i) {
    if (!(s.values[i] >= 0.0 && s.values[i] < 1.0)) {
      throw_invalid(what, " must be in [0, 1) (got ", s.values[i], " in row ", i / size_t(dims), ")");
    }
  }
  return s;
}

std::string detail::shapes_of(const std::vector<std::pair<const char*, const DoubleArray*>>& arrays) {
  std::string out;
  for (const auto& [name, array] : arrays) out += std::string(out.empty() ? "" : ", ") + name + " " + shape_of(*array);
  return out;
}

std::vector<std::array<int, 3>> to_triangles(const py::handle& object, const char* what, size_t vertex_count) {
  // Float indices are taken where they are whole (np.array([[0.0, 1.0, 2.0]])); the integer cast
  // below alone would truncate 1.7 to 1.
  if (const py::array given = py::array::ensure(object); given && given.dtype().kind() == 'b') {
    throw_invalid(what, " must hold whole vertex indices (got booleans)");
  } else if (given && given.dtype().kind() == 'f') {
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(given);
    for (py::ssize_t i = 0; values && i < values.size(); ++i) {
      const double v = values.data()[i];
      if (v != std::floor(v)) throw_invalid(what, " must hold whole vertex indices (got ", v, ")");
    }
  }
  py::array_t<long long, py::array::c_style | py::array::forcecast> t;
  try {
    t = py::cast<decltype(t)>(object);
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be an integer array of shape (M, 3)");
  }
  if (t.ndim() != 2 || t.shape(1) != 3) throw_invalid(what, " must have shape (M, 3)");
  std::vector<std::array<int, 3>> out(size_t(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) {
      const long long id = t.at(i, k);
      if (id < 0 || id >= (long long)vertex_count) {
        throw_invalid(what, "[", i, "] refers to vertex ", id, " of ", vertex_count);
      }
      out[size_t(i)][size_t(k)] = int(id);
    }
  }
  return out;
}

std::vector<Vec2d> to_uvs(const py::handle& object, const char* what, size_t count) {
  const DoubleArray array = numbers(object, what, " must be a float array of shape (N, 2)");
  const bool any = count == kAnyCount;
  if (any && array.ndim() == 2) count = size_t(array.shape(0));
  if (array.ndim() != 2 || array.shape(1) != 2 || size_t(array.shape(0)) != count) {
    if (any) throw_invalid(what, " must have shape (N, 2)");
    throw_invalid(what, " must have shape (", count, ", 2): one per vertex");
  }
  std::vector<Vec2d> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = Vec2d(array.at(i, 0), array.at(i, 1));
    if (!std::isfinite(out[i].x()) || !std::isfinite(out[i].y())) throw_invalid(what, " must be finite");
  }
  return out;
}

void require_float_radiance(const py::handle& object, const char* what) {
  if (!py::isinstance<py::array>(object)) return;  // lists: numbers, read as floats
  const py::dtype dtype = py::cast<py::array>(object).dtype();
  if (dtype.kind() == 'f') return;
  throw_invalid(what, " holds linear radiance as floats (got dtype ", std::string(py::str(dtype)),
                "; an 8-bit picture holds sRGB-encoded colour: give its file to Scene.set_environment, which "
                "decodes it, or decode it)");
}

Image to_image(const py::handle& object, const char* what, bool raw) {
  using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
  FloatArray array;
  try {
    array = py::cast<FloatArray>(real_dtype_array(object, what));
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be a float array of shape (H, W, C)");
  }
  if (!raw && array.ndim() == 2) array = array.reshape({array.shape(0), array.shape(1), py::ssize_t(1)});
  if (array.ndim() != 3 || array.shape(2) < 1 || (!raw && array.shape(2) > 4) || array.shape(0) < 1 ||
      array.shape(1) < 1) {
    std::string shape;
    for (py::ssize_t k = 0; k < array.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(array.shape(k));
    throw_invalid(what, raw ? " must have shape (H, W, C)" : " must have shape (H, W), (H, W, 1..4)",
                  ", H and W >= 1 (got (", shape, "))");
  }
  constexpr py::ssize_t kIntMax = std::numeric_limits<int>::max();
  if (array.shape(0) > kIntMax || array.shape(1) > kIntMax || array.shape(2) > kIntMax) {
    throw_invalid(what, " has a side past 2^31 - 1 pixels (got ", array.shape(0), " x ", array.shape(1), ")");
  }
  Image image(int(array.shape(1)), int(array.shape(0)), int(array.shape(2)));
  std::copy(array.data(), array.data() + array.size(), image.pixels.begin());
  if (raw) return image;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (std::isfinite(image.pixels[i])) continue;
    const size_t texel = i / size_t(image.channels);
    throw_invalid(what, " pixel (row ", texel / size_t(image.width), ", column ", texel % size_t(image.width),
                  ") must be finite (got ", image.pixels[i], ")");
  }
  return image;
}

std::string file_system_path(const py::handle& path) {
  return py::cast<std::string>(py::module_::import("os").attr("fsencode")(path));
}

Eigen::Matrix3d to_rotation(const py::handle& object, const char* what) {
  if (object.is_none()) return Eigen::Matrix3d::Identity();
  const DoubleArray array = numbers(object, what, " must be an angle about +y [deg] or a 3 x 3 rotation matrix");
  if (array.ndim() == 0) {
    const double degrees = array.data()[0];
    if (!std::isfinite(degrees)) throw_invalid(what, " must be finite (got ", degrees, ")");
    return EnvironmentLight::rotation_about_y(degrees);
  }
  if (array.ndim() != 2 || array.shape(0) != 3 || array.shape(1) != 3) {
    throw_invalid(what, " must be an angle about +y [deg] or of shape (3, 3) (got ", shape_of(array), ")");
  }
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(array.data());
}

// Vec3d is three packed doubles (no padding), so a vector of them is an (N, 3) row-major block.
static_assert(sizeof(Vec3d) == 3 * sizeof(double));

DoubleArray points_to_array(const std::vector<Vec3d>& points) {
  return DoubleArray({py::ssize_t(points.size()), py::ssize_t(3)}, points.empty() ? nullptr : points[0].data());
}

DoubleArray values_to_array(const std::vector<double>& values) {
  return DoubleArray(py::ssize_t(values.size()), values.data());
}

DoubleArray vector_to_array(const Vec3d& v) { return DoubleArray(py::ssize_t(3), v.data()); }

DoubleArray matrix_to_array(const Eigen::Matrix3d& m) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> rows = m;
  return DoubleArray({py::ssize_t(3), py::ssize_t(3)}, rows.data());
}

}  // namespace refracta
