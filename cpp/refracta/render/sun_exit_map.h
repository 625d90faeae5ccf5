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
// In a height-only air in CurvedEarth's flat frame a path depends on its start height and launch
// elevation alone (its flat vertical plane is kept), so one air-only cast per node, from the origin
// along +x, stands for every point's: its exit elevation and its horizontal run. A point's exit is
// then that path moved to the point, its end turned into the world by the frame's own rotation
// there (off the origin's axes the path turns in azimuth too: ~0.06 deg 60 km across). The map is
// linear between nodes in launch elevation, height and the air's dispersion scale; sampling
// (launch: Newton steps in elevation and azimuth) and the density of a launch (density: the exit
// it maps to, the Jacobian by difference quotients) use the same interpolant, so where the table
// differs from a path by its error, that error shows only as a sliver of the disc left to BSDF
// sampling again, never as bias.
#pragma once

#include "refracta/core/math.h"
#include "refracta/media/index_field.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/embree_scene.h"
#include "refracta/shading/sun_light.h"

#include <memory>
#include <optional>
#include <vector>

namespace refracta {

class Caster;

// The exit elevation [rad], in the start's own frame, of the path launched at `elevation` [rad]
// from (0, h, 0) along +x through `caster`, and its horizontal run [m] to the path's end in `run`
// (optional); NaN where the path meets the scene or cannot be traced (below the air's modelled
// heights). In a height-only air it stands for every start at height h (SunExitMap, LowestLaunches).
double start_frame_exit(const Caster& caster, double h, double elevation, double* run = nullptr);

class SunExitMap {
 public:
  // airs[k]: the render's air at dispersion scale scales[k] (ascending, one or two; height-only over
  // a spherical Earth), cast as the render's shadow rays are (options, ior floors none, `spread`
  // their secondary spread); `frame` the render's field, whose sky_direction turns a path's end into
  // the world frame (kept). Heights from scene.lowest() to scene.highest(); launch elevations around
  // the sun's elevations in the frames of the scene's points. Null where the sun is below every
  // point's horizon or no height's row holds a rising exit.
  static std::shared_ptr<const SunExitMap> build(const Scene& scene, const std::vector<const IndexField*>& airs,
                                                 const std::vector<double>& scales, FieldPtr frame,
                                                 const RenderOptions& options, double spread, const SunLight& sun);

  // A launch from p (a unit direction in the flat frame) and |d omega_exit / d omega_launch| there.
  struct Launch {
    Vec3d direction;
    double jacobian;
  };
  // The launch from p whose path leaves along `exit` (a unit vector in p's frame; to_world takes
  // p's frame to the world's), at dispersion scale `scale`; nullopt where the table does not cover
  // that exit (outside its heights, beyond the rows' monotone part). A path off the origin's axes
  // turns in azimuth too (the flattening's frame turns with the end point): the launch is solved
  // in elevation and azimuth, the Jacobian in solid angle.
  std::optional<Launch> launch(const Vec3d& p, const Eigen::Matrix3d& to_world, double scale, const Vec3d& exit) const;
  // Whether launch() takes up `exit` (p's frame) from p: its elevation within the interpolated
  // row's covered exits (launch() may still find no launch for it, rarely: then none).
  bool covers(const Vec3d& p, double scale, const Vec3d& exit) const;
  // The table's exit (p's frame) of a launch from p, in `exit`, and the Jacobian with which
  // launch() sends that exit back to it; nullopt where launch() does not take it up.
  std::optional<double> density(const Vec3d& p, const Eigen::Matrix3d& to_world, double scale, const Vec3d& launch,
                                Vec3d* exit) const;

 private:
  // The row of one (height, scale) point: node values (linear in height and scale) from `first`.
  struct Row {
    const SunExitMap* map;
    size_t cell, scale_cell;
    double w_height, w_scale;
    size_t first;
    double at(const std::vector<std::vector<double>>& table, size_t i) const;
  };
  bool row(double h, double scale, Row* out) const;
  // The exit (p's frame) of the launch at elevation e [rad] along the horizontal unit `across`.
  Vec3d exit_of(const Row& r, const Vec3d& p, const Eigen::Matrix3d& to_world, double e, const Vec3d& across) const;
  // |d omega_exit / d omega_launch| there, x its exit.
  double jacobian(const Row& r, const Vec3d& p, const Eigen::Matrix3d& to_world, double e, const Vec3d& across,
                  const Vec3d& x) const;
  bool covered(const Row& r, const Vec3d& exit) const;

  FieldPtr frame_;
  double radius_ = 0.0;                     // the frame's Earth radius [m]
  double h_lo_ = 0.0, h_step_ = 0.0;        // heights h_lo_ + j h_step_ [m]
  double e_lo_ = 0.0, e_step_ = 0.0;        // launch elevations e_lo_ + i e_step_ [rad]
  size_t launches_ = 0, heights_ = 0;
  std::vector<double> scales_;                      // ascending, one or two
  // [k][j * launches_ + i]: from (0, h_j, 0) along +x at scale k, the exit elevation [rad] in the
  // start's frame (NaN: no exit) and the horizontal run to the path's end [m].
  std::vector<std::vector<double>> exits_, runs_;
  std::vector<std::vector<size_t>> first_;          // first_[k][j]: first node of row j's monotone part
};

}  // namespace refracta
