// Options of the renderers.
#pragma once

#include "refracta/rays/trace_options.h"

#include <cstdint>
#include <optional>
#include <string>

namespace refracta {

enum class RenderMethod { kStraight, kCurved };
RenderMethod parse_render_method(const std::string& name);  // "straight", "curved"

struct RenderOptions {
  RenderMethod method = RenderMethod::kCurved;
  int spp = 1;                // samples per pixel (1: the pixel centre; more: stratified jitter)
  uint64_t seed = 0;
  double max_length = 5000.0; // curved rays end here and show the sky in their last direction [m]
  double chord = 200.0;       // longest straight chord tested against the geometry [m]
  double sagitta = 1e-3;      // largest distance between a chord and the curved path [m]
  // Integrator for curved rays; tol [m]. Height-only fields use 'stratified', others 'rk45'.
  double tol = 1e-4;
  std::optional<TraceMethod> integrator;  // force 'rk45' or 'stratified' (default: by the field)
  // Height-only fields: serve every pixel from one ElevationTable for the camera's eye height
  // (interpolated to `tol`) instead of tracing each pixel.
  bool use_table = true;
  int tile = 16;

  void validate() const;
};

}  // namespace refracta
