// Python binding of the renderers (cpp/refracta/render).
#include "refracta/bindings/bind_scene.h"
#include "refracta/bindings/interruptible.h"
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
}

}  // namespace refracta
