// Python binding of the renderers (cpp/refracta/render).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/bindings/options_binding.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/readouts.h"
#include "refracta/render/renderer.h"

#include <optional>
#include <string>

namespace refracta {

void bind_render(py::module_& m) {
  py::class_<RenderOptions> render_options(m, "RenderOptions", R"doc(
Options of refracta.render, with their defaults (defined once, here). Set any field by name;
validate() reports every bad value at once.)doc");
  render_options.def(py::init<>())
      .def_property("method", [](const RenderOptions& o) { return o.method == RenderMethod::kStraight ? "straight" : o.method == RenderMethod::kCurved ? "curved" : "raster_march"; },
                    [](RenderOptions& o, const std::string& v) { o.method = parse_render_method(v); },
                    "'curved' (exact curved rays), 'straight' (no refraction) or 'raster_march' (the original editor's method)")
      .def_property("transport", [](const RenderOptions& o) { return o.transport == Transport::kDirect ? "direct" : "path"; },
                    [](RenderOptions& o, const std::string& v) { o.transport = parse_transport(v); },
                    "'direct' (direct lighting with MIS, mirror/glass chains) or 'path' (path tracing)")
      .def_readwrite("spp", &RenderOptions::spp, "samples per pixel (stratified jitter when > 1)")
      .def_readwrite("seed", &RenderOptions::seed, "seed of the per-pixel random streams")
      .def_readwrite("max_depth", &RenderOptions::max_depth, "scattering events per path (Mitsuba's max_depth - 1)")
      .def_readwrite("rr_depth", &RenderOptions::rr_depth, "Russian roulette from this many events on")
      .def_readwrite("spectral", &RenderOptions::spectral, "4 hero wavelengths per sample instead of RGB")
      .def_readwrite("max_length", &RenderOptions::max_length, "[m] curved rays end here and show the sky")
      .def_readwrite("chord", &RenderOptions::chord, "[m] longest straight chord tested against the geometry")
      .def_readwrite("sagitta", &RenderOptions::sagitta, "[m] largest distance between a chord and the path")
      .def_readwrite("sagitta_pixels", &RenderOptions::sagitta_pixels,
                     "camera rays: chords may stray this fraction of a pixel's footprint when more than sagitta")
      .def_readwrite("tol", &RenderOptions::tol, "[m] curved-ray integration tolerance")
      .def_property("trace", [](const RenderOptions& o) -> py::object { if (o.trace) return py::str(trace_method_name(*o.trace)); return py::none(); },
                    [](RenderOptions& o, const py::object& v) { o.trace = v.is_none() ? std::nullopt : std::optional<TraceMethod>(parse_trace_method(py::cast<std::string>(v))); },
                    "ray integrator for curved rays: None (stratified for height-only fields, rk45 otherwise), 'rk45', 'stratified'")
      .def_property("turbulence_trace", [](const RenderOptions& o) { return turbulence_trace_name(o.turbulence_trace); },
                    [](RenderOptions& o, const std::string& v) { o.turbulence_trace = parse_turbulence_trace(v); },
                    "camera rays through turbulence: 'strict' (the full field, rk45) or 'perturbed' (deviations from\n"
                    "the calm rays of the eye's table in steps of the turbulence's cells; strict where not small)")
      .def_readwrite("turbulence_step", &RenderOptions::turbulence_step,
                     "turbulence_trace 'perturbed': the step through the layer in the turbulence's cells")
      .def_readwrite("table", &RenderOptions::use_table, "height-only fields: serve camera rays from one ElevationTable")
      .def_readwrite("tile", &RenderOptions::tile, "tile size [pixels] of the parallel loop")
      .def_readwrite("texture_filter", &RenderOptions::texture_filter, "filter textures over each sample's footprint")
      .def_readwrite("differentials", &RenderOptions::differentials,
                     "camera rays' footprints from ray differentials through the air (false: the ray cone)")
      .def_readwrite("surface_aovs", &RenderOptions::surface_aovs,
                     "also render the albedo and normal of the first non-specular hit: 9 channels (render's aovs, denoise)")
      .def_readwrite("readouts", &RenderOptions::readouts,
                     "also render the per-pixel readouts after those 9 channels: 19 (render's aovs 'distance', ...)")
      .def_property("march", [](const RenderOptions& o) { return trace_method_name(o.march); },
                    [](RenderOptions& o, const std::string& v) { o.march = parse_trace_method(v); },
                    "raster_march: 'rk45' to tol, or 'rk4' with step (the original)")
      .def_readwrite("step", &RenderOptions::step, "[m] raster_march rk4 step")
      .def_readwrite("max_steps", &RenderOptions::max_steps, "raster_march rk4 steps")
      .def_readwrite("guard_band", &RenderOptions::guard_band, "raster_march: extra raster view per side (fraction)")
      .def_property("pixel_bounds",
                    [](const RenderOptions& o) -> py::object {
                      if (!o.pixel_bounds) return py::none();
                      const PixelBounds& b = *o.pixel_bounds;
                      return py::make_tuple(b.x0, b.y0, b.x1, b.y1);
                    },
                    [](RenderOptions& o, const py::object& v) {
                      if (v.is_none()) {
                        o.pixel_bounds.reset();
                        return;
                      }
                      std::vector<int> b;
                      try {
                        b = py::cast<std::vector<int>>(v);
                      } catch (const py::cast_error&) {
                        throw_invalid("pixel_bounds must be None or (x0, y0, x1, y1) whole numbers");
                      }
                      if (b.size() != 4) throw_invalid("pixel_bounds must be (x0, y0, x1, y1) (got ", b.size(), " values)");
                      o.pixel_bounds = PixelBounds{b[0], b[1], b[2], b[3]};
                    },
                    "None (the whole image) or (x0, y0, x1, y1): render only pixels [x0, x1) x [y0, y1), each exactly as\n"
                    "in the whole image (distributed tiles); the image returned has that size")
      .def("validate", &RenderOptions::validate)
      .def(
          "bounds_in",
          [](const RenderOptions& o, int width, int height) {
            const PixelBounds b = o.bounds_in(width, height);
            return py::make_tuple(b.x0, b.y0, b.x1, b.y1);
          },
          py::arg("width"), py::arg("height"),
          "(x0, y0, x1, y1) of the pixels rendered in a width x height image (pixel_bounds, checked, or the whole)");
  // Pickled as its fields by name and rebuilt through them (the defaults stay C++'s).
  def_options_pickle<RenderOptions>(render_options);

  py::class_<RenderStats>(m, "RenderStats", "What refracta.render counted (read-only; tiles add up with +).")
      .def(py::init<>(), "All counts 0.")
      .def_readonly("samples", &RenderStats::samples, "camera samples traced")
      .def_readonly("chords", &RenderStats::chords, "Embree queries along camera paths (straight rays count one each)")
      .def_readonly("invalid_samples", &RenderStats::invalid_samples,
                    "samples whose radiance was not finite (dropped; should stay 0)")
      .def("__add__",
           [](const RenderStats& a, const RenderStats& b) {
             RenderStats sum;
             sum.samples = a.samples + b.samples, sum.chords = a.chords + b.chords;
             sum.invalid_samples = a.invalid_samples + b.invalid_samples;
             return sum;
           })
      .def("__repr__", [](const py::object& self) { return "RenderStats(" + options_repr(self) + ")"; })
      .def(py::pickle([](const RenderStats& s) { return py::make_tuple(s.samples, s.chords, s.invalid_samples); },
                      [](const py::tuple& t) {
                        RenderStats s;
                        s.samples = t[0].cast<int64_t>(), s.chords = t[1].cast<int64_t>();
                        s.invalid_samples = t[2].cast<int64_t>();
                        return s;
                      }));

  m.def("_render",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const std::shared_ptr<IndexField>& field,
           const RenderOptions& options, const py::object& progress) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          options.validate();
          // Refused before anything is allocated (core/image.h): float32 RGB, and room for one copy
          // by the caller (the pixels themselves move into the returned array).
          const PixelBounds bounds = options.bounds_in(camera.width(), camera.height());
          check_image_memory(bounds.width(), bounds.height(), options.readouts ? 152.0 : options.surface_aovs ? 72.0 : 24.0, "render");
          WorkControl control;
          Image image;
          RenderStats stats;
          const Scene::ReadGuard reading(scene->geometry);
          run_interruptible(control, progress, [&] { image = render(*scene, camera, field, options, control, &stats); });
          return py::make_tuple(image_to_float32(std::move(image)), stats);
        },
        py::arg("scene"), py::arg("camera"), py::arg("field"), py::arg("options"), py::arg("progress"));

  // Where each readout lies among the render's channels (readouts.h ReadoutChannel): name -> (first, count).
  py::dict readout_channels;
  const std::pair<const char*, std::pair<int, int>> channels[] = {
      {"distance", {kReadoutDistance, 1}},
      {"position", {kReadoutPosition, 3}},
      {"object_id", {kReadoutObject, 1}},
      {"apparent_elevation", {kReadoutApparentElevation, 1}},
      {"apparent_azimuth", {kReadoutApparentAzimuth, 1}},
      {"true_elevation", {kReadoutTrueElevation, 1}},
      {"hidden_height", {kReadoutHiddenHeight, 2}}};
  for (const auto& [name, at] : channels) readout_channels[name] = py::make_tuple(kSurfaceChannels + at.first, at.second);
  m.attr("_READOUT_CHANNELS") = readout_channels;

  m.def("_mirage_images",
        [](const py::array_t<float, py::array::c_style | py::array::forcecast>& true_elevation,
           const py::array_t<float, py::array::c_style | py::array::forcecast>& object_id) {
          if (true_elevation.ndim() != 2 || object_id.ndim() != 2 || true_elevation.shape(0) != object_id.shape(0) ||
              true_elevation.shape(1) != object_id.shape(1)) {
            throw_invalid("_mirage_images: true_elevation and object_id must be (H, W) arrays of one shape");
          }
          const int height = int(true_elevation.shape(0)), width = int(true_elevation.shape(1));
          const std::vector<float> elevations(true_elevation.data(), true_elevation.data() + true_elevation.size());
          const std::vector<float> ids(object_id.data(), object_id.data() + object_id.size());
          const std::vector<int> images = mirage_images(elevations, ids, width, height);
          py::array_t<int32_t> out({py::ssize_t(height), py::ssize_t(width)});
          std::copy(images.begin(), images.end(), out.mutable_data());
          return out;
        },
        py::arg("true_elevation"), py::arg("object_id"),
        "Mirage multiplicity per pixel (render's aovs 'images'; render/readouts.h mirage_images): (H, W) int32.");

  m.def("_render_raster",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const RasterRenderOptions& options,
           const py::object& progress) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          options.validate();
          WorkControl control;
          Image image;
          RasterRenderStats stats;
          const Scene::ReadGuard reading(scene->geometry);
          run_interruptible(control, progress, [&] { image = render_raster(*scene, camera, options, control, &stats); });
          return py::make_tuple(image_to_float32(std::move(image)), stats);
        },
        py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress"),
        "(image, RasterRenderStats) of refracta.render_raster.");
}

}  // namespace refracta
