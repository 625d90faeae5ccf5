// Where the sun's light leaves the air, tabulated: over a spherical Earth in a height-only air, the
// exit elevation (in the start point's own frame) of a path launched at elevation e from height h,
// for the launches whose paths may leave toward the sun's disc above a point's horizon.
//
// Why: a sun sample launched along its own direction leaves bent down by the refraction (0.09 deg
// at 10 deg, half a degree at the horizon), so a crescent of the launches whose paths do leave in
// the disc (a fifth of them for a sun 10 deg high, 0.265 deg in radius) had light density zero:
// only BSDF samples found them, at full MIS weight, and a glossy sea under the sun sparkled with
// fireflies 10-200x its neighbours. Launched through this map's inverse, the light samples cover
// the disc's paths to within the table's error.
//
// In a height-only air over a sphere a path depends on its start height and launch elevation alone
// (its vertical plane holds the Earth's centre: the azimuth is kept, and the frame turns with the
// point), so one air-only cast per node stands for every point's. The map is linear between nodes
// in launch elevation, height and the air's dispersion scale; sampling (launch) and the density of
// a launch (exit) use the same interpolant, so the light strategy stays exactly invertible where
// the table differs from a path by its error: that error shows only as a sliver of the disc left to
// BSDF sampling again, never as bias.
#pragma once

#include "refracta/core/math.h"
#include "refracta/media/index_field.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/embree_scene.h"
#include "refracta/shading/sun_light.h"

#include <memory>
#include <vector>

namespace refracta {

class SunExitMap {
 public:
  // airs[k]: the render's air at dispersion scale scales[k] (ascending, one or two; height-only over
  // a spherical Earth), cast as the render's shadow rays are (options, ior floors none, `spread`
  // their secondary spread). Heights from scene.lowest() to scene.highest() plus a surface point's
  // largest offset; launch elevations around the sun's elevations in the frames of the scene's
  // points. Null where the sun is below every point's horizon or no height's row holds a rising exit.
  static std::shared_ptr<const SunExitMap> build(const Scene& scene, const std::vector<const IndexField*>& airs,
                                                 const std::vector<double>& scales, const RenderOptions& options,
                                                 double spread, const SunLight& sun);

  // The launch elevation [rad] from height h whose path leaves at elevation `exit` [rad] (p's
  // frame), and |d omega_exit / d omega_launch| there in `jacobian`; false where the table does
  // not cover that exit (outside its heights, or beyond the rows' monotone part).
  bool launch(double h, double scale, double exit, double* launch_elevation, double* jacobian) const;
  // The inverse: the exit elevation of a launch at `launch_elevation` from h, and the Jacobian;
  // false where the table does not cover that launch.
  bool exit(double h, double scale, double launch_elevation, double* exit_elevation, double* jacobian) const;
  // Whether launch() covers `exit` from h: the exits of the interpolated row's monotone part.
  bool covers(double h, double scale, double exit) const;

 private:
  // The row of one (height, scale) point: node values (linear in height and scale) from `first`.
  struct Row {
    const SunExitMap* map;
    size_t cell, scale_cell;
    double w_height, w_scale;
    size_t first;
    double at(size_t i) const;
  };
  bool row(double h, double scale, Row* out) const;

  double h_lo_ = 0.0, h_step_ = 0.0;        // heights h_lo_ + j h_step_ [m]
  double e_lo_ = 0.0, e_step_ = 0.0;        // launch elevations e_lo_ + i e_step_ [rad]
  size_t launches_ = 0, heights_ = 0;
  std::vector<double> scales_;                      // ascending, one or two
  std::vector<std::vector<double>> exits_;          // exits_[k][j * launches_ + i] [rad]; NaN: no exit
  std::vector<std::vector<size_t>> first_;          // first_[k][j]: first node of row j's monotone part
};

}  // namespace refracta
