// Python bindings of the moment math and per-pixel OIT (cpp/refracta/raster).
#include "refracta/bindings/bind_raster_options.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/raster/moment_shadow.h"
#include "refracta/raster/moments.h"
#include "refracta/raster/rasterizer.h"
#include "refracta/raster/oit.h"
#include "refracta/raster/power_moment_bound.h"
#include "refracta/raster/quantization.h"

#include <optional>

namespace refracta {

namespace {

constexpr double kMaxMoment = 1.5;  // see _shadow_intensity

DoubleArray as_matrix(const py::object& object, py::ssize_t columns, const char* what) {
  DoubleArray array;
  try {
    array = real_array(object, what);
  } catch (const py::cast_error&) {
    throw_invalid(what, " must be an array of numbers");
  }
  if (array.ndim() != 2 || (columns > 0 && array.shape(1) != columns)) {
    throw_invalid(what, " must have shape (N, ", columns, ")");
  }
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    if (!std::isfinite(array.data()[i])) throw_invalid(what, " must be finite");
  }
  return array;
}

}  // namespace

void bind_raster(py::module_& m) {
  bind_raster_options(m);
  m.def("_mboit_unorm16", [](const std::vector<double>& b) { return stored_mboit_unorm16(b); }, py::arg("b"),
        "6 or 8 normalised power moments after MBOIT's 16-bit storage (transform, rounding, inverse).");
  m.def("_rasterize",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, double guard_band, std::optional<int> tile) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          if (tile && *tile < 1) throw_invalid("tile must be a whole number >= 1 (got ", *tile, ")");
          const RasterView view = RasterView::from_camera(camera, guard_band);
          WorkControl control;
          VisibilityBuffer buffer;
          RasterStats stats;
          const Scene::ReadGuard reading(scene->geometry);
          run_interruptible(control, py::none(), [&] { buffer = rasterize(scene->geometry, view, control, tile.value_or(kRasterTile), &stats); });
          const py::ssize_t h = buffer.height, w = buffer.width;
          py::array_t<float> depth({h, w}), barycentric({h, w, py::ssize_t(3)});
          py::array_t<int64_t> geometry({h, w}), primitive({h, w});
          for (py::ssize_t i = 0; i < h * w; ++i) {
            depth.mutable_data()[i] = buffer.depth[i];
            const bool covered = buffer.geometry[i] != VisibilityBuffer::kNone;
            geometry.mutable_data()[i] = covered ? int64_t(buffer.geometry[i]) : -1;
            primitive.mutable_data()[i] = covered ? int64_t(buffer.primitive[i]) : -1;
            float* b = barycentric.mutable_data() + 3 * i;
            b[1] = buffer.b1[i], b[2] = buffer.b2[i], b[0] = covered ? 1.0f - b[1] - b[2] : 0.0f;
          }
          py::dict out;
          out["depth"] = depth;
          out["geometry"] = geometry;
          out["primitive"] = primitive;
          out["barycentric"] = barycentric;
          out["offset"] = py::make_tuple(view.offset_x(), view.offset_y());
          out["triangles"] = stats.triangles_in;
          out["screen_triangles"] = stats.triangles_drawn;
          out["fragments"] = stats.fragments;
          return out;
        },
        py::arg("scene"), py::arg("camera"), py::arg("guard_band"), py::arg("tile"));

  m.def("_shadow_intensity",
        [](const py::object& moments, const py::object& depths, const std::string& method,
           const MomentShadowSettings& settings) {
          const MomentShadowMethod parsed = parse_moment_shadow_method(method);
          settings.validate();
          const DoubleArray b = as_matrix(moments, 4, "moments");
          const std::vector<double> z = to_values(depths, "z_f");
          if (py::ssize_t(z.size()) != b.shape(0)) throw_invalid("moments and z_f must have the same length");
          // Power moments of depths in [0, 1] or [-1, 1] lie in [-1, 1]; beyond 1.5 (room for
          // biased or hand-made moments) the fp32 / unorm16 storage transforms overflowed to NaN.
          for (py::ssize_t i = 0; i < b.size(); ++i) {
            if (!(std::abs(b.data()[i]) <= kMaxMoment)) {
              throw_invalid("moments must lie in [-", kMaxMoment, ", ", kMaxMoment, "] (power moments of depths in [-1, 1]; got ",
                            b.data()[i], ")");
            }
          }
          std::vector<double> out(z.size());
          for (size_t i = 0; i < z.size(); ++i) {
            out[i] = moment_shadow({b.at(i, 0), b.at(i, 1), b.at(i, 2), b.at(i, 3)}, z[i], parsed, settings);
          }
          return values_to_array(out);
        },
        py::arg("moments"), py::arg("z_f"), py::arg("method"), py::arg("settings"));
  m.def("_quantize_moments",
        [](const py::object& moments, const std::string& depth_range, bool inverse) {
          const bool is_signed = parse_depth_range(depth_range) == DepthRange::kSigned;
          const DoubleArray b = as_matrix(moments, 4, "moments");
          DoubleArray out({b.shape(0), py::ssize_t(4)});
          for (py::ssize_t i = 0; i < b.shape(0); ++i) {
            const Moments4 in = {b.at(i, 0), b.at(i, 1), b.at(i, 2), b.at(i, 3)};
            const Moments4 r = inverse ? inverse_quantization_transform(in, is_signed) : quantization_transform(in, is_signed);
            for (int k = 0; k < 4; ++k) out.mutable_at(i, k) = r[k];
          }
          return out;
        },
        py::arg("moments"), py::arg("depth_range"), py::arg("inverse"));

  m.def("_canonical_bound",
        [](const std::vector<double>& b, double z_f) {
          const MomentBound bound = canonical_bound(b, z_f);
          return py::make_tuple(bound.lower, bound.at_query, bound.fallback);
        },
        py::arg("moments"), py::arg("z_f"));

  // MBOIT's per-pixel fast path: the moments factorised once, queried at every z_f.
  m.def("_power_moment_bound",
        [](const std::vector<double>& b, const py::object& z_f) {
          const int m = int(b.size()) - 1;
          if (m != 4 && m != 6 && m != 8) throw_invalid("moments must hold b_0 .. b_m with m = 4, 6 or 8 (got ", b.size(), " values)");
          const std::vector<double> z = to_values(z_f, "z_f");
          const PowerMomentBound bound(b.data(), m);
          std::vector<double> lower(z.size()), at_query(z.size()), fallback(z.size());
          for (size_t i = 0; i < z.size(); ++i) {
            const MomentBound r = bound.at(z[i]);
            lower[i] = r.lower, at_query[i] = r.at_query, fallback[i] = r.fallback ? 1.0 : 0.0;
          }
          return py::make_tuple(values_to_array(lower), values_to_array(at_query), values_to_array(fallback));
        },
        py::arg("moments"), py::arg("z_f"));

  m.def("_composite",
        [](const py::object& depths, const py::object& alphas, const py::object& colors, const py::object& background,
           const OitSettings& settings) {
          const std::vector<double> z = to_values(depths, "depths"), a = to_values(alphas, "alphas");
          const std::vector<Vec3d> c = z.empty() ? std::vector<Vec3d>{} : to_points(colors, "colors");
          if (a.size() != z.size() || c.size() != z.size()) {
            throw_invalid("depths, alphas and colors must describe the same fragments (", z.size(), ", ", a.size(),
                          ", ", c.size(), ")");
          }
          std::vector<Fragment> fragments;
          for (size_t i = 0; i < z.size(); ++i) fragments.push_back({z[i], a[i], c[i]});
          validate_fragments(fragments);
          const Vec3d bg = to_point(background, "background");
          settings.validate();
          const Vec3d out = composite(fragments, bg, settings);
          return points_to_array({out}).reshape({py::ssize_t(3)});
        },
        py::arg("depths"), py::arg("alphas"), py::arg("colors"), py::arg("background"), py::arg("settings"));
}

}  // namespace refracta
