// Python binding of the renderers (cpp/refracta/render).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/render/film.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/readouts.h"
#include "refracta/render/renderer.h"

#include <pybind11/eigen.h>
#include <pybind11/operators.h>

#include <tuple>

namespace refracta {

static std::tuple<int, int, int, int> corners(const PixelBounds& b) { return {b.x0, b.y0, b.x1, b.y1}; }

// (image, stats) of a render of `scene` under its read lock, interruptible by Ctrl-C.
template <class Stats, class Render>
static auto render_interruptibly(const std::shared_ptr<RenderScene>& scene, const py::object& progress,
                                 Render&& render) {
  if (!scene) throw_invalid("scene must be a refracta.Scene");
  WorkControl control;
  Image image;
  Stats stats;
  const Scene::ReadGuard reading(scene->geometry);
  run_interruptible(control, progress, [&] { image = render(control, &stats); });
  return py::make_tuple(image_to_float32(std::move(image)), stats);
}

void bind_render(py::module_& m) {
  using O = RenderOptions;
  py::class_<O> options(m, "RenderOptions", R"doc(
Options of refracta.render, with their defaults (defined once, here). Set any field by name;
validate() reports every bad value at once.)doc");
  options.def(py::init<>());
  def_enum_property(options, "method", &O::method, &render_method_name, &parse_render_method,
                    "'curved' (exact curved rays), 'straight' (no refraction) or 'raster_march' (the original "
                    "editor's method)");
  def_enum_property(options, "transport", &O::transport, &transport_name, &parse_transport,
                    "'direct' (direct lighting with MIS, mirror/glass chains) or 'path' (path tracing)");
  def_enum_property(options, "trace", &O::trace, &trace_method_name, &parse_trace_method,
                    "ray integrator for curved rays: None (stratified for height-only fields, rk45 otherwise), "
                    "'rk45', 'stratified'");
  def_enum_property(options, "turbulence_trace", &O::turbulence_trace, &turbulence_trace_name, &parse_turbulence_trace,
                    "camera rays through turbulence: 'strict' (the full field, rk45) or 'perturbed' (deviations from\n"
                    "each ray's calm path, traced exactly to tol, in steps of the turbulence's cells; those samples'\n"
                    "shadow and bounce rays through the calm air)");
  def_enum_property(options, "march", &O::march, &trace_method_name, &parse_trace_method,
                    "raster_march: 'rk45' to tol, or 'rk4' with step (the original)");
  options.def_readwrite("spp", &O::spp, "samples per pixel (correlated multi-jittered when > 1)")
      .def_readwrite("adaptive", &O::adaptive, "a pilot of spp / 8 per pixel shares each 32-pixel block's "
                     "budget: half of spp each, the rest where the pilot varies (same total, unbiased)")
      .def_readwrite("edge_spp", &O::edge_spp, "when above spp: pixels at edges between surfaces (first hits' albedo "
                     "or normal differ from a neighbour's) rendered again with this many samples (0: off)")
      .def_readwrite("seed", &O::seed, "seed of the per-pixel random streams")
      .def_readwrite("max_depth", &O::max_depth, "scattering events per path (Mitsuba's max_depth - 1)")
      .def_readwrite("rr_depth", &O::rr_depth, "Russian roulette from this many events on")
      .def_readwrite("spectral", &O::spectral, "4 hero wavelengths per sample instead of RGB")
      .def_readwrite("max_length", &O::max_length, "[m] curved rays end here and show the sky")
      .def_readwrite("chord", &O::chord, "[m] longest straight chord tested against the geometry")
      .def_readwrite("sagitta", &O::sagitta, "[m] largest distance between a chord and the path")
      .def_readwrite("sagitta_pixels", &O::sagitta_pixels,
                     "camera rays: chords may stray this fraction of a pixel's footprint when more than sagitta")
      .def_readwrite("tol", &O::tol, "[m] curved-ray integration tolerance")
      .def_readwrite("turbulence_step", &O::turbulence_step,
                     "turbulence_trace 'perturbed': the step through the layer in the turbulence's cells")
      .def_readwrite("table", &O::use_table, "height-only fields: serve camera rays from one ElevationTable")
      .def_readwrite("tile", &O::tile, "tile size [pixels] of the parallel loop")
      .def_readwrite("texture_filter", &O::texture_filter, "filter textures over each sample's footprint")
      .def_readwrite("differentials", &O::differentials,
                     "camera rays' footprints from ray differentials through the air (false: the ray cone)")
      .def_readwrite("surface_aovs", &O::surface_aovs, "also render the albedo and normal of the first "
                     "non-specular hit: 9 channels (render's aovs, denoise)")
      .def_readwrite("guide_spp", &O::guide_spp, "with surface_aovs, when above spp: the albedo and normal from "
                     "a pass of their own, this many first-hit samples per pixel (denoise's guides; 0: the image's)")
      .def_readwrite("readouts", &O::readouts, "also render the per-pixel readouts after those 9 channels: 19 "
                     "(render's aovs 'distance', ...)")
      .def_readwrite("step", &O::step, "[m] raster_march rk4 step")
      .def_readwrite("max_steps", &O::max_steps, "raster_march rk4 steps")
      .def_readwrite("guard_band", &O::guard_band, "raster_march: extra raster view per side (fraction)")
      .def_property(
          "pixel_bounds",
          [](const O& o) { return o.pixel_bounds ? std::optional(corners(*o.pixel_bounds)) : std::nullopt; },
          [](O& o, const std::optional<std::vector<int>>& v) {
            o.pixel_bounds = v ? std::optional(pixel_bounds_from(*v)) : std::nullopt;
          },
          "None (the whole image) or (x0, y0, x1, y1): render only pixels [x0, x1) x [y0, y1), each exactly as\n"
          "in the whole image (distributed tiles); the image returned has that size")
      .def("validate", &O::validate)
      .def(
          "bounds_in", [](const O& o, int width, int height) { return corners(o.bounds_in(width, height)); },
          py::arg("width"), py::arg("height"),
          "(x0, y0, x1, y1) of the pixels rendered in a width x height image (pixel_bounds, checked, or the whole)");
  // Pickled as its fields by name and rebuilt through them (the defaults stay C++'s).
  def_options_pickle<O>(options);

  using S = RenderStats;
  py::class_<S>(m, "RenderStats", "What refracta.render counted (read-only; tiles add up with +).")
      .def(py::init<>(), "All counts 0.")
      .def_readonly("samples", &S::samples, "camera samples traced")
      .def_readonly("chords", &S::chords, "Embree queries along camera paths (straight rays count one each)")
      .def_readonly("invalid_samples", &S::invalid_samples,
                    "samples whose radiance was not finite (dropped; should stay 0)")
      .def(py::self + py::self)
      .def("__repr__", [](const py::object& self) { return "RenderStats(" + options_repr(self) + ")"; })
      .def(py::pickle([](const S& s) { return std::make_tuple(s.samples, s.chords, s.invalid_samples); },
                      [](const std::tuple<int64_t, int64_t, int64_t>& t) {
                        return S{std::get<0>(t), std::get<1>(t), std::get<2>(t)};
                      }));

  m.def(
      "_render",
      [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const std::shared_ptr<IndexField>& field,
         const O& options, const py::object& progress) {
        return render_interruptibly<S>(scene, progress, [&](WorkControl& control, S* stats) {
          return render(*scene, camera, field, options, control, stats);
        });
      },
      py::arg("scene"), py::arg("camera"), py::arg("field"), py::arg("options"), py::arg("progress"));
  m.def(
      "_cmj_pattern",
      [](int count, uint32_t seed) {
        if (count < 1) throw_invalid("count must be >= 1 (got ", count, ")");
        const detail::CmjPattern pattern(count, seed);
        Sampler sampler{Rng(seed, 0)};
        Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> points(count, 2);
        for (int s = 0; s < count; ++s) {
          const double jx = sampler.uniform();
          points.row(s) = pattern.point(s, jx, sampler.uniform()).transpose();
        }
        return points;
      },
      py::arg("count"), py::arg("seed"),
      "(count, 2) sample positions in [0, 1)^2 of the film's correlated multi-jittered pattern (render/film.h,\n"
      "Kensler 2013) with the shuffles of `seed`, jittered by the generator Rng(seed, 0).");
  // Where each readout lies among the render's channels (readouts.h ReadoutChannel): name -> (first, count).
  m.attr("_READOUT_CHANNELS") = py::dict(py::cast(readout_channels()));
  m.def("_mirage_images", &mirage_images, py::arg("true_elevation"), py::arg("object_id"),
        "Mirage multiplicity per pixel (render's aovs 'images'; render/readouts.h mirage_images): (H, W) int32.");
  m.def(
      "_render_raster",
      [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const RasterRenderOptions& options,
         const py::object& progress) {
        return render_interruptibly<RasterRenderStats>(scene, progress, [&](WorkControl& control, auto* stats) {
          return render_raster(*scene, camera, options, control, stats);
        });
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress"),
      "(image, RasterRenderStats) of refracta.render_raster.");
}

}  // namespace refracta
