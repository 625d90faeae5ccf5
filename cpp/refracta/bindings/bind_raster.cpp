// Python bindings of the rasterizer's buffers, the moment math and per-pixel OIT (cpp/refracta/raster).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/raster/moment_arrays.h"
#include "refracta/raster/raster_images.h"

#include <pybind11/eigen.h>

#include <optional>

namespace refracta {

// MomentShadowSettings, ShadowMapOptions, MboitSettings, OitSettings, RasterRenderOptions and
// RasterRenderStats (bind_raster_options.cpp), bound before the functions that take them.
void bind_raster_options(py::module_& m);

void bind_raster(py::module_& m) {
  bind_raster_options(m);
  m.def("_mboit_unorm16", &stored_mboit_unorm16, py::arg("b"),
        "6 or 8 normalised power moments after MBOIT's 16-bit storage (transform, rounding, inverse).");
  m.def(
      "_rasterize",
      [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, double guard_band, std::optional<int> tile) {
        if (!scene) throw_invalid("scene must be a refracta.Scene");
        WorkControl control;
        RasterImages out;
        const Scene::ReadGuard reading(scene->geometry);
        run_interruptible(control, py::none(),
                          [&] { out = rasterize_images(scene->geometry, camera, guard_band, tile, control); });
        return py::make_tuple(out.depth, out.geometry, out.primitive, out.barycentric, out.offset,
                              out.stats.triangles_in, out.stats.triangles_drawn, out.stats.fragments);
      },
      py::arg("scene"), py::arg("camera"), py::arg("guard_band"), py::arg("tile"),
      "(depth, geometry, primitive, barycentric (H * W, 3), offset, triangles, screen triangles, fragments).");
  m.def("_shadow_intensity", &shadow_intensities, py::arg("moments"), py::arg("z_f"), py::arg("method"),
        py::arg("settings"), "Shadow intensities of (N, 4) moments at N receiver depths.");
  m.def("_quantize_moments", &quantize_moments, py::arg("moments"), py::arg("depth_range"), py::arg("inverse").noconvert(),
        "The optimised quantisation transform of (N, 4) moments, or its inverse.");
  m.def(
      "_canonical_bound",
      [](const std::vector<double>& b, double z_f) {
        const MomentBound bound = canonical_bound(b, z_f);
        return py::make_tuple(bound.lower, bound.at_query, bound.fallback);
      },
      py::arg("moments"), py::arg("z_f"), "(lower, at_query, fallback) of the canonical bound.");
  m.def("_power_moment_bound", &power_moment_bounds, py::arg("moments"), py::arg("z_f"),
        "MBOIT's per-pixel fast path: (lower, at_query, fallback) at every z_f.");
  m.def(
      "_composite",
      [](const py::object& depths, const py::object& alphas, const py::object& colors, const py::object& background,
         const OitSettings& settings) {
        const std::vector<double> z = to_values(depths, "depths"), a = to_values(alphas, "alphas");
        const std::vector<Vec3d> c = z.empty() ? std::vector<Vec3d>{} : to_points(colors, "colors");
        return vector_to_array(composite_pixel(z, a, c, to_point(background, "background"), settings));
      },
      py::arg("depths"), py::arg("alphas"), py::arg("colors"), py::arg("background"), py::arg("settings"),
      "One pixel's fragments composited over the background.");
}

}  // namespace refracta
