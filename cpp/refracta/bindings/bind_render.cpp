// Python binding of the renderers (cpp/refracta/render).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/renderer.h"

#include <optional>
#include <string>

namespace refracta {

void bind_render(py::module_& m) {
  py::class_<RenderOptions>(m, "RenderOptions", R"doc(
Options of refracta.render, with their defaults (defined once, here). Set any field by name;
validate() reports every bad value at once.)doc")
      .def(py::init<>())
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
      .def_readwrite("table", &RenderOptions::use_table, "height-only fields: serve camera rays from one ElevationTable")
      .def_readwrite("tile", &RenderOptions::tile, "tile size [pixels] of the parallel loop")
      .def_readwrite("texture_filter", &RenderOptions::texture_filter, "filter textures over each sample's footprint")
      .def_readwrite("differentials", &RenderOptions::differentials,
                     "camera rays' footprints from ray differentials through the air (false: the ray cone)")
      .def_readwrite("surface_aovs", &RenderOptions::surface_aovs,
                     "also render the albedo and normal of the first non-specular hit: 9 channels (render's aovs, denoise)")
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
      // Pickled as its fields by name and rebuilt through them (the defaults stay C++'s).
      .def(py::pickle(
          [](const py::object& self) {
            py::dict state;
            const py::object type = py::type::of(self);
            const py::object property = py::module_::import("builtins").attr("property");
            for (const py::handle name : py::module_::import("builtins").attr("dir")(type)) {
              const std::string key = py::cast<std::string>(name);
              if (key.rfind("_", 0) != 0 && py::isinstance(type.attr(name), property)) state[name] = self.attr(name);
            }
            return state;
          },
          [](const py::dict& state) {
            py::object options = py::cast(RenderOptions());
            for (const auto& item : state) options.attr(item.first) = item.second;
            return py::cast<RenderOptions>(options);
          }));

  m.def("_render",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const std::shared_ptr<IndexField>& field,
           const RenderOptions& options, const py::object& progress) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          options.validate();
          // Refused before anything is allocated (core/image.h): float32 RGB, and room for one copy
          // by the caller (the pixels themselves move into the returned array).
          const PixelBounds bounds = options.bounds_in(camera.width(), camera.height());
          check_image_memory(bounds.width(), bounds.height(), options.surface_aovs ? 72.0 : 24.0, "render");
          WorkControl control;
          Image image;
          RenderStats stats;
          const Scene::ReadGuard reading(scene->geometry);
          run_interruptible(control, progress, [&] { image = render(*scene, camera, field, options, control, &stats); });
          py::dict counts;
          counts["samples"] = stats.samples;
          counts["chords"] = stats.chords;
          counts["invalid_samples"] = stats.invalid_samples;
          return py::make_tuple(image_to_float32(std::move(image)), counts);
        },
        py::arg("scene"), py::arg("camera"), py::arg("field"), py::arg("options"), py::arg("progress"));

  m.def("_render_raster",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const std::string& shadows, int resolution,
           int kernel, bool signed_depth, std::optional<double> bias, std::optional<std::vector<double>> bias_vector,
           const std::string& storage, double depth_bias, double normal_offset, double bleeding_reduction,
           const py::object& shadow_centre, std::optional<double> shadow_half_size, std::optional<double> shadow_distance,
           bool output_shadow, std::optional<std::string> transparency, int oit_moments, const std::string& oit_kind,
           double beta, int layers, const std::string& weight, int shadow_light, bool use_sun,
           std::optional<std::vector<int>> spots, const std::string& oit_storage, const py::object& progress) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          RasterRenderOptions options;
          if (transparency) {
            OitSettings oit;
            oit.method = parse_oit_method(*transparency);
            if (oit_kind != "power" && oit_kind != "trig") throw_invalid("kind must be 'power' or 'trig' (got '", oit_kind, "')");
            oit.mboit.trigonometric = oit_kind == "trig";
            oit.mboit.moments = oit_moments;
            oit.mboit.beta = beta;
            if (oit_storage != "fp32" && oit_storage != "unorm16") {
              throw_invalid("oit_storage must be 'fp32' or 'unorm16' (got '", oit_storage, "')");
            }
            oit.mboit.unorm16 = oit_storage == "unorm16";
            oit.layers = layers;
            oit.weight = weight;
            options.transparency = oit;
          }
          options.shadows = shadows;
          if (shadows != "embree" && shadows != "none") parse_shadow_method(shadows);
          ShadowMapOptions& map = options.shadow_map;
          map.resolution = resolution;
          map.kernel = kernel;
          map.moments = MomentShadowSettings::defaults(signed_depth, parse_moment_storage(storage));
          if (bias) map.moments.bias = *bias;
          if (bias_vector) {
            if (bias_vector->size() != 4) throw_invalid("bias_vector must have 4 entries (got ", bias_vector->size(), ")");
            std::copy(bias_vector->begin(), bias_vector->end(), map.moments.bias_vector.begin());
          }
          map.depth_bias = depth_bias;
          map.normal_offset = normal_offset;
          map.bleeding_reduction = bleeding_reduction;
          if (!shadow_centre.is_none()) options.shadow_centre = to_point(shadow_centre, "shadow_centre");
          options.shadow_half_size = shadow_half_size;
          if (shadow_distance) options.shadow_distance = *shadow_distance;
          options.output_shadow = output_shadow;
          options.shadow_light = shadow_light;
          options.use_sun = use_sun;
          options.spots = spots;
          options.validate();
          WorkControl control;
          Image image;
          RasterRenderStats stats;
          const Scene::ReadGuard reading(scene->geometry);
          run_interruptible(control, progress, [&] {
            image = render_raster(*scene, camera, options, control, &stats);
          });
          py::dict counts;
          counts["seconds"] = stats.seconds;
          counts["shadow_build_seconds"] = stats.shadow_build_seconds;
          counts["bytes_per_texel"] = stats.bytes_per_texel;
          counts["transparent_fragments"] = stats.transparent_fragments;
          counts["oit_bytes_per_pixel"] = stats.oit_bytes_per_pixel;
          return py::make_tuple(image_to_float32(std::move(image)), counts);
        },
        py::arg("scene"), py::arg("camera"), py::arg("shadows"), py::arg("resolution"), py::arg("kernel"),
        py::arg("signed_depth"), py::arg("bias"), py::arg("bias_vector"), py::arg("storage"), py::arg("depth_bias"),
        py::arg("normal_offset"), py::arg("bleeding_reduction"), py::arg("shadow_centre"), py::arg("shadow_half_size"),
        py::arg("shadow_distance"), py::arg("output_shadow"), py::arg("transparency"), py::arg("moments"),
        py::arg("kind"), py::arg("beta"), py::arg("layers"), py::arg("weight"), py::arg("shadow_light"),
        py::arg("use_sun"), py::arg("spots"), py::arg("oit_storage"), py::arg("progress"));
}

}  // namespace refracta
