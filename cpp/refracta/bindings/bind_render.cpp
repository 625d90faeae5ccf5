// Python binding of the renderers (cpp/refracta/render).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
#include "refracta/render/raster_renderer.h"
#include "refracta/render/renderer.h"

#include <optional>
#include <string>

namespace refracta {

void bind_render(py::module_& m) {
  m.def("_render",
        [](const std::shared_ptr<RenderScene>& scene, const Camera& camera, const std::shared_ptr<IndexField>& field,
           const std::string& method, int spp, uint64_t seed, double max_length, double chord, double sagitta, double tol,
           bool table, std::optional<std::string> integrator, const std::string& march, double step, int max_steps,
           double guard_band, bool texture_filter, const py::object& progress) {
          if (!scene) throw_invalid("scene must be a refracta.Scene");
          RenderOptions options;
          options.method = parse_render_method(method);
          options.spp = spp;
          options.seed = seed;
          options.max_length = max_length;
          options.chord = chord;
          options.sagitta = sagitta;
          options.tol = tol;
          options.use_table = table;
          if (integrator) options.integrator = parse_trace_method(*integrator);
          options.march = parse_trace_method(march);
          options.step = step;
          options.max_steps = max_steps;
          options.guard_band = guard_band;
          options.texture_filter = texture_filter;
          options.validate();
          WorkControl control;
          Image image;
          RenderStats stats;
          run_interruptible(control, progress, [&] {
            image = render(scene->geometry, scene->lighting, camera, field, options, control, &stats);
          });
          py::dict counts;
          counts["samples"] = stats.samples;
          counts["chords"] = stats.chords;
          return py::make_tuple(image_to_float32(image), counts);
        },
        py::arg("scene"), py::arg("camera"), py::arg("field"), py::arg("method"), py::arg("spp"), py::arg("seed"),
        py::arg("max_length"), py::arg("chord"), py::arg("sagitta"), py::arg("tol"), py::arg("table"), py::arg("integrator"),
        py::arg("march"), py::arg("step"), py::arg("max_steps"), py::arg("guard_band"), py::arg("texture_filter"), py::arg("progress"));

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
          run_interruptible(control, progress, [&] {
            image = render_raster(scene->geometry, scene->lighting, camera, options, control, &stats);
          });
          py::dict counts;
          counts["seconds"] = stats.seconds;
          counts["shadow_build_seconds"] = stats.shadow_build_seconds;
          counts["bytes_per_texel"] = stats.bytes_per_texel;
          counts["transparent_fragments"] = stats.transparent_fragments;
          counts["oit_bytes_per_pixel"] = stats.oit_bytes_per_pixel;
          return py::make_tuple(image_to_float32(image), counts);
        },
        py::arg("scene"), py::arg("camera"), py::arg("shadows"), py::arg("resolution"), py::arg("kernel"),
        py::arg("signed_depth"), py::arg("bias"), py::arg("bias_vector"), py::arg("storage"), py::arg("depth_bias"),
        py::arg("normal_offset"), py::arg("bleeding_reduction"), py::arg("shadow_centre"), py::arg("shadow_half_size"),
        py::arg("shadow_distance"), py::arg("output_shadow"), py::arg("transparency"), py::arg("moments"),
        py::arg("kind"), py::arg("beta"), py::arg("layers"), py::arg("weight"), py::arg("shadow_light"),
        py::arg("use_sun"), py::arg("spots"), py::arg("oit_storage"), py::arg("progress"));
}

}  // namespace refracta
