// Python binding of the renderers (cpp/refracta/render).
#include "generated/docstrings.h"
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/enum_property.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/render/film.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/readouts.h"
#include "refracta/render/renderer.h"
#include "refracta/render/shimmer_cast.h"

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
  py::class_<O> options(m, "RenderOptions", DOC(refracta, RenderOptions));
  def_options_common<O>(options, "RenderOptions");
  def_enum_property(options, "method", &O::method, &render_method_name, &parse_render_method,
                    "'curved' (exact curved rays), 'straight' (no refraction) or 'raster_march' (the original "
                    "editor's method)");
  def_enum_property(options, "transport", &O::transport, &transport_name, &parse_transport,
                    "'direct' (direct lighting with MIS, mirror/glass chains) or 'path' (path tracing)");
  def_enum_property(options, "trace", &O::trace, &trace_method_name, &parse_trace_method,
                    "ray integrator for curved rays: None (stratified for height-only fields, rk45 otherwise), "
                    "'rk45', 'stratified'");
  def_enum_property(options, "turbulence_trace", &O::turbulence_trace, &turbulence_trace_name, &parse_turbulence_trace,
                    "camera rays through turbulence: 'auto' (default: 'perturbed' where it applies, else 'strict'),\n"
                    "'strict' (the full field, rk45) or 'perturbed' (deviations from each ray's calm path, traced\n"
                    "exactly to tol, in steps of the turbulence's cells; those samples' shadow and bounce rays through\n"
                    "the calm air; rays turned by more than 5 mrad traced strictly). 'perturbed' serves RGB curved\n"
                    "renders through height-only calm air, or hot spots over it, from a pinhole camera; elsewhere the\n"
                    "render traces strictly, and render() warns where 'perturbed' was asked for");
  def_enum_property(options, "march", &O::march, &trace_method_name,
                    &parse_march_method,
                    "raster_march: 'rk45' to tol, or 'rk4' with step (the original)");
  options.def_readwrite("spp", &O::spp, DOC(refracta, RenderOptions, spp))
      .def_readwrite("adaptive", &O::adaptive, DOC(refracta, RenderOptions, adaptive))
      .def_readwrite("edge_spp", &O::edge_spp, DOC(refracta, RenderOptions, edge_spp))
      .def_readwrite("seed", &O::seed, DOC(refracta, RenderOptions, seed))
      .def_readwrite("max_depth", &O::max_depth, DOC(refracta, RenderOptions, max_depth))
      .def_readwrite("rr_depth", &O::rr_depth, DOC(refracta, RenderOptions, rr_depth))
      .def_readwrite("spectral", &O::spectral, DOC(refracta, RenderOptions, spectral))
      .def_readwrite("max_length", &O::max_length, DOC(refracta, RenderOptions, max_length))
      .def_readwrite("chord", &O::chord, DOC(refracta, RenderOptions, chord))
      .def_readwrite("sagitta", &O::sagitta, DOC(refracta, RenderOptions, sagitta))
      .def_readwrite("sagitta_pixels", &O::sagitta_pixels, DOC(refracta, RenderOptions, sagitta_pixels))
      .def_readwrite("tol", &O::tol, DOC(refracta, RenderOptions, tol))
      .def_readwrite("turbulence_step", &O::turbulence_step, DOC(refracta, RenderOptions, turbulence_step))
      .def_readwrite("table", &O::use_table, DOC(refracta, RenderOptions, use_table))
      .def_readwrite("tile", &O::tile, DOC(refracta, RenderOptions, tile))
      .def_readwrite("texture_filter", &O::texture_filter, DOC(refracta, RenderOptions, texture_filter))
      .def_readwrite("differentials", &O::differentials, DOC(refracta, RenderOptions, differentials))
      .def_readwrite("surface_aovs", &O::surface_aovs, DOC(refracta, RenderOptions, surface_aovs))
      .def_readwrite("guide_spp", &O::guide_spp, DOC(refracta, RenderOptions, guide_spp))
      .def_readwrite("readouts", &O::readouts, DOC(refracta, RenderOptions, readouts))
      .def_readwrite("sample_counts", &O::sample_counts, DOC(refracta, RenderOptions, sample_counts))
      .def_readwrite("step", &O::step, DOC(refracta, RenderOptions, step))
      .def_readwrite("max_steps", &O::max_steps, DOC(refracta, RenderOptions, max_steps))
      .def_readwrite("guard_band", &O::guard_band, DOC(refracta, RenderOptions, guard_band))
      .def_property(
          "pixel_bounds",
          [](const O& o) { return o.pixel_bounds ? std::optional(corners(*o.pixel_bounds)) : std::nullopt; },
          [](O& o, const std::optional<std::vector<int>>& v) {
            o.pixel_bounds = v ? std::optional(pixel_bounds_from(*v)) : std::nullopt;
          },
          DOC(refracta, RenderOptions, pixel_bounds))
      .def(
          "bounds_in", [](const O& o, int width, int height) { return corners(o.bounds_in(width, height)); },
          py::arg("width"), py::arg("height"), DOC(refracta, RenderOptions, bounds_in));

  using S = RenderStats;
  py::class_<S> stats(m, "RenderStats", DOC(refracta, RenderStats));
  stats
      .def(py::init<>(), "All counts 0.")
      .def_readonly("samples", &S::samples, DOC(refracta, RenderStats, samples))
      .def_readonly("chords", &S::chords, DOC(refracta, RenderStats, chords))
      .def_readonly("invalid_samples", &S::invalid_samples, DOC(refracta, RenderStats, invalid_samples))
      .def(py::self + py::self)
      .def("__repr__", [](const py::object& self) { return "RenderStats(" + options_repr(self) + ")"; });
  def_options_eq(stats);  // a record: equal counts, equal stats (a pickled copy too)
  def_fields_pickle(stats, &S::samples, &S::chords, &S::invalid_samples);

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
      "_perturbed_trace_refusal",
      [](const std::shared_ptr<IndexField>& field, const O& options, const Camera& camera) -> std::optional<std::string> {
        std::string why = perturbed_trace_refusal(field.get(), options, camera);
        return why.empty() ? std::nullopt : std::optional<std::string>(std::move(why));
      },
      py::arg("field"), py::arg("options"), py::arg("camera"), DOC(refracta, perturbed_trace_refusal));
  m.def(
      "_cmj_pattern",
      [](int count, uint32_t seed) {
        if (count < 1) throw_invalid("count must be >= 1 (got ", count, ")");
        const CmjPattern pattern(count, seed);
        Rng rng(seed, 0);
        Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> points(count, 2);
        for (int s = 0; s < count; ++s) {
          const double jx = rng.uniform();
          points.row(s) = pattern.point(s, jx, rng.uniform()).transpose();
        }
        return points;
      },
      py::arg("count"), py::arg("seed"),
      "(count, 2) sample positions in [0, 1)^2 of the film's correlated multi-jittered pattern (core/sample_patterns.h,\n"
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
