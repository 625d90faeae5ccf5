// Python -> C++ conversions of the bindings: one rule per kind of input, each raising ValueError
// naming the argument (`what`). Every bind_*.cpp converts its arguments through these, so "a
// colour" or "a unit vector" means the same thing in every function that takes one.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/image.h"
#include "refracta/core/math.h"
#include "refracta/core/sampling.h"
#include "refracta/shading/color.h"

#include "refracta/bindings/strict_numbers.h"  // before any use of a number caster

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace refracta {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Any row count (the count argument of the converters below).
inline constexpr size_t kAnyCount = size_t(-1);
// Directions must be unit to this tolerance: float64 normalisation gives ~1e-16, float32 input
// ~1e-7; a direction off by more was not normalised.
inline constexpr double kUnitTolerance = 1e-6;

// Any array-like of real numbers (integer or float dtype; bool too with `bools`) as a
// C-contiguous double array; ValueError naming `what` for complex, string or object data (numpy
// would cast those silently).
DoubleArray real_array(const py::handle& object, const char* what, bool bools = true);

// A number: a Python or numpy int or float (or anything float() takes but a string or a bool:
// True would be 1); nullopt otherwise. to_number: ValueError "<what> must be a number (got ...)".
std::optional<double> number_of(const py::handle& value);
double to_number(const py::handle& value, const char* what);

namespace detail {
template <class>
using AnyObject = py::object;
// "name (shape), ..." of the arguments (vectorize_real's refusal of shapes that do not broadcast).
std::string shapes_of(const std::vector<std::pair<const char*, const DoubleArray*>>& arrays);

template <class Return, class... Args, size_t... I>
auto vectorize_real(Return (*f)(Args...), std::array<const char*, sizeof...(Args)> names, std::index_sequence<I...>) {
  return [f, names](const AnyObject<Args>&... args) {
    const std::array<DoubleArray, sizeof...(Args)> arrays{real_array(args, names[I], /*bools=*/false)...};
    try {
      return py::vectorize(f)(arrays[I]...);
    } catch (const std::runtime_error& error) {
      // py::vectorize's own message names no argument: "incompatible size/dimension of inputs!".
      if (std::string(error.what()).find("incompatible size") == std::string::npos) throw;
      throw_invalid("the arguments must broadcast together as numpy arrays do (got ",
                    shapes_of({{names[I], &arrays[I]}...}), ")");
    }
  };
}
}  // namespace detail

// f over numbers and arrays of them with numpy's broadcasting (py::vectorize: scalars in, a float
// out), each argument checked by real_array naming it (py::vectorize alone casts '550' to 550,
// True to 1).
template <class Return, class... Args>
auto vectorize_real(Return (*f)(Args...), std::array<const char*, sizeof...(Args)> names) {
  return detail::vectorize_real(f, names, std::index_sequence_for<Args...>());
}

// Points: (N, 3) or (3,), finite. `single` is set when the input was one point (3,).
std::vector<Vec3d> to_points(const py::handle& object, const char* what, bool* single = nullptr);
// Exactly one point (3,).
Vec3d to_point(const py::handle& object, const char* what);
// Numbers: a scalar or (N,), finite; not bools.
std::vector<double> to_values(const py::handle& object, const char* what, bool* single = nullptr);
// A horizontal vector (x, z): two finite numbers.
Vec2d to_vec2(const py::handle& object, const char* what);

// Unit vectors: points (N, 3) or (3,) of length 1 within kUnitTolerance; with `zero_ok` a row may
// be 0 (no normal). `count` (kAnyCount: any) is the number of rows required.
std::vector<Vec3d> to_unit_vectors(const py::handle& object, const char* what, size_t count = kAnyCount,
                                   bool zero_ok = false, bool* single = nullptr);

// A colour: a number (grey) or three (r, g, b), finite. Its range is the library's to check
// (reflectances in [0, 1], illuminants >= 0).
Vec3d to_rgb(const py::handle& value, const char* what);
std::optional<Vec3d> to_optional_rgb(const py::object& value, const char* what);  // None: nullopt
// An emitted colour: a colour each of whose channels is >= 0, as an illuminant (RGB x D65).
Color to_illuminant(const py::handle& value, const char* what);

// Uniform sample numbers, each in [0, 1) (the half-open range every sampler in the library is
// written for): rows of `dims` numbers, (N, dims) or one row (dims,); for dims = 1, (N,) or a
// scalar. `count` (kAnyCount: any) is the number of rows required.
struct Samples {
  int dims = 1;
  size_t rows = 0;
  bool single = false;  // one row given
  std::vector<double> values;
  const double* row(size_t i) const { return values.data() + size_t(dims) * i; }
  Vec2d pair(size_t i) const { return Vec2d(row(i)[0], row(i)[1]); }
};
Samples to_samples(const py::handle& object, const char* what, int dims, size_t count = kAnyCount);

// Triangles (M, 3) of vertex indices, each in [0, vertex_count).
std::vector<std::array<int, 3>> to_triangles(const py::handle& object, const char* what, size_t vertex_count);
// Texture coordinates (count, 2), finite; count kAnyCount: (N, 2), any N.
std::vector<Vec2d> to_uvs(const py::handle& object, const char* what, size_t count);
// An image: a float array (H, W) or (H, W, C), C in 1..4, finite. `raw`: (H, W, C) with any C >= 1,
// inf and NaN kept (a float file's channels: readouts give no hit an inf distance, a NaN position).
Image to_image(const py::handle& object, const char* what, bool raw = false);
// Refuses an array of radiances whose dtype is not a float's: integers are a picture's sRGB-encoded
// colours (a uint8 sky's 128 was radiance 128), booleans a mask.
void require_float_radiance(const py::handle& object, const char* what);
// A rotation: None (identity), an angle [deg] about +y, or a 3 x 3 matrix.
Eigen::Matrix3d to_rotation(const py::handle& object, const char* what);
// A path (str, bytes or os.PathLike) as the file system's bytes (os.fsencode): a name that is not
// UTF-8 (a str holding os.fsdecode's surrogates) stays the file's, and a NUL byte reaches the
// readers' check_path_text, which refuses it by name.
std::string file_system_path(const py::handle& path);

// C++ -> numpy.
DoubleArray points_to_array(const std::vector<Vec3d>& points);
DoubleArray values_to_array(const std::vector<double>& values);
DoubleArray vector_to_array(const Vec3d& v);  // shape (3,)
DoubleArray matrix_to_array(const Eigen::Matrix3d& m);  // shape (3, 3)

}  // namespace refracta
