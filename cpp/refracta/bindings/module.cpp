// refracta._core: the compiled half of the refracta package. One bind_<area> per C++ folder.
#include "refracta/bindings/bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = "refracta's C++ core (private; use the refracta package)";
  refracta::bind_core(m);
  refracta::bind_runtime(m);  // first: threads and library messages set before any work
  refracta::bind_media(m);
  refracta::bind_rays(m);
  refracta::bind_scene(m);
  refracta::bind_raster(m);
  refracta::bind_render(m);
  refracta::bind_edit(m);
  refracta::bind_shading(m);
  refracta::bind_lights(m);
  refracta::bind_spectrum(m);
  refracta::bind_dispersion(m);
  refracta::refuse_unbuilt_objects();
  refracta::escape_undecodable_messages();
}
