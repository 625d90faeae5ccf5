// The sun's exit map (sun_exit_map.h).
#include "refracta/render/sun_exit_map.h"

#include "refracta/core/parallel.h"
#include "refracta/render/caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

constexpr int kMapHeightIntervals = 32;
constexpr size_t kMapLaunchNodes = 128;
// The launch band around the exits sought [rad]: refraction lifts a launch above its exit by up to
// ~0.6 deg at the horizon (more in a duct), a hot layer can bend it the other way.
constexpr double kMapBandAbove = 0.015, kMapBandBelow = 0.005;
constexpr double kLowestMapLaunch = 5e-6;  // [rad] a level ray would start on the surface's far side
constexpr double kMapExitPad = 1e-3;       // [rad] beyond the sun's extreme elevations in the scene
// [m] a point this far outside the surfaces' heights (float error of a hit) reads the nearest row.
constexpr double kMapHeightSlack = 1e-3;

// The exit elevation [rad] in the start's frame of the path launched at `elevation` from (0, h, 0)
// along +x through air alone; NaN where it ends inside the air or the cast fails.
double air_exit_elevation(const Caster& caster, double h, double elevation) {
  const Vec3d origin(0.0, h, 0.0);
  try {
    const PathEnd end = caster.cast(origin, Vec3d(std::cos(elevation), std::sin(elevation), 0.0));
    if (end.hit) return std::numeric_limits<double>::quiet_NaN();
    Eigen::Matrix3d to_world;
    for (int axis = 0; axis < 3; ++axis) to_world.col(axis) = caster.field()->sky_direction(origin, Vec3d::Unit(axis));
    return std::asin(std::clamp(Vec3d(to_world.transpose() * end.direction).y(), -1.0, 1.0));
  } catch (const std::exception&) {  // a path below the field's modelled heights: no exit
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

std::shared_ptr<const SunExitMap> SunExitMap::build(const Scene& scene, const std::vector<const IndexField*>& airs,
                                                     const std::vector<double>& scales, const RenderOptions& options,
                                                     double spread, const SunLight& sun) {
  if (airs.empty() || airs.size() != scales.size() || airs.size() > 2) return nullptr;
  if (!std::isfinite(scene.lowest()) || !std::isfinite(scene.highest())) return nullptr;
  // The sun's elevation in the frames of the scene box's corners (it changes linearly with the
  // position along the ground to first order in the central angle: the corners bound it).
  const Vec3d& lower = scene.lower();
  const Vec3d& upper = scene.upper();
  const double disc_radius = std::acos(1.0 - sun.solid_angle() / (2.0 * kPi));
  double e_min = std::numeric_limits<double>::infinity(), e_max = -e_min;
  for (double x : {lower.x(), upper.x()}) {
    for (double z : {lower.z(), upper.z()}) {
      const Vec3d p(x, 0.0, z);
      const Vec3d up = airs.front()->sky_direction(p, Vec3d::UnitY());
      const double e = std::asin(std::clamp(up.dot(sun.direction()), -1.0, 1.0));
      e_min = std::min(e_min, e), e_max = std::max(e_max, e);
    }
  }
  const double exit_lo = std::max(0.0, e_min - disc_radius - kMapExitPad), exit_hi = e_max + disc_radius + kMapExitPad;
  if (!(exit_hi > 0.0)) return nullptr;
  auto map = std::make_shared<SunExitMap>();
  // The surfaces' heights (a point's map is read at its own height; row() takes a height within
  // kMapHeightSlack of the ends as the end's).
  map->h_lo_ = scene.lowest();
  map->h_step_ = std::max(scene.highest() - scene.lowest(), kMapHeightSlack) / kMapHeightIntervals;
  map->heights_ = kMapHeightIntervals + 1;
  map->e_lo_ = std::max(kLowestMapLaunch, exit_lo - kMapBandBelow);
  const double e_hi = std::min(0.5 * kPi - 1e-6, exit_hi + kMapBandAbove);
  map->launches_ = kMapLaunchNodes;
  map->e_step_ = (e_hi - map->e_lo_) / double(kMapLaunchNodes - 1);
  map->scales_ = scales;
  // Air alone: the scene's surfaces block shadow rays, not the map (the render's casts say what
  // a path meets).
  Scene empty;
  empty.commit();
  std::vector<std::unique_ptr<Caster>> casters;
  for (const IndexField* air : airs) {
    casters.push_back(std::make_unique<Caster>(empty, air, options));
    casters.back()->set_secondary_spread(spread);
  }
  const size_t per_scale = map->heights_ * map->launches_;
  map->exits_.assign(airs.size(), std::vector<double>(per_scale));
  WorkControl control;  // the caller's cancel flags stay in force (parallel_for_each)
  parallel_for_each(int64_t(airs.size() * per_scale), 1, control, [&](int64_t index) {
    const size_t k = size_t(index) / per_scale, node = size_t(index) % per_scale;
    const size_t j = node / map->launches_, i = node % map->launches_;
    map->exits_[k][node] =
        air_exit_elevation(*casters[k], map->h_lo_ + double(j) * map->h_step_, map->e_lo_ + double(i) * map->e_step_);
  });
  // Each row's monotone part: from the highest launch down while the exit falls strictly.
  bool any = false;
  map->first_.assign(airs.size(), std::vector<size_t>(map->heights_, map->launches_));
  for (size_t k = 0; k < airs.size(); ++k) {
    for (size_t j = 0; j < map->heights_; ++j) {
      const double* row = &map->exits_[k][j * map->launches_];
      size_t first = map->launches_ - 1;
      if (std::isnan(row[first])) continue;
      while (first > 0 && row[first - 1] < row[first]) --first;
      map->first_[k][j] = first;
      any = any || (first + 1 < map->launches_ && row[map->launches_ - 1] > 0.0);
    }
  }
  return any ? map : nullptr;
}

double SunExitMap::Row::at(size_t i) const {
  auto value = [&](size_t k) {
    const std::vector<double>& exits = map->exits_[k];
    return (1.0 - w_height) * exits[cell * map->launches_ + i] + w_height * exits[(cell + 1) * map->launches_ + i];
  };
  const size_t last = map->scales_.size() - 1;
  return (1.0 - w_scale) * value(scale_cell) + w_scale * value(std::min(scale_cell + 1, last));
}

bool SunExitMap::row(double h, double scale, Row* out) const {
  const double h_hi = h_lo_ + kMapHeightIntervals * h_step_;
  if (!(h >= h_lo_ - kMapHeightSlack && h <= h_hi + kMapHeightSlack)) return false;
  const double u = (std::clamp(h, h_lo_, h_hi) - h_lo_) / h_step_;
  out->map = this;
  out->cell = std::min(size_t(u), size_t(kMapHeightIntervals - 1));
  out->w_height = u - double(out->cell);
  out->scale_cell = 0;
  // Two scales: linear in the air's n - 1 between them (clamped at the ends); one: the render's air.
  out->w_scale = scales_.size() < 2 ? 0.0 : std::clamp((scale - scales_[0]) / (scales_[1] - scales_[0]), 0.0, 1.0);
  out->first = 0;
  for (size_t k = 0; k < scales_.size(); ++k) {
    out->first = std::max({out->first, first_[k][out->cell], first_[k][out->cell + 1]});
  }
  return out->first + 1 < launches_;
}

bool SunExitMap::covers(double h, double scale, double exit) const {
  Row r;
  return row(h, scale, &r) && exit >= r.at(r.first) && exit <= r.at(launches_ - 1);
}

bool SunExitMap::launch(double h, double scale, double exit, double* launch_elevation, double* jacobian) const {
  Row r;
  if (!row(h, scale, &r) || !(exit >= r.at(r.first) && exit <= r.at(launches_ - 1))) return false;
  // The cell [i, i + 1] holding the exit (the row rises strictly from r.first), then the line through it.
  size_t lo = r.first, hi = launches_ - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (r.at(mid) <= exit ? lo : hi) = mid;
  }
  const double a = r.at(lo), b = r.at(hi);
  const double launch = e_lo_ + (double(lo) + (exit - a) / (b - a)) * e_step_;
  *launch_elevation = launch;
  // d omega_exit / d omega_launch = cos e_exit d e_exit / (cos e_launch d e_launch), azimuth kept.
  *jacobian = std::cos(exit) * (b - a) / (std::cos(launch) * e_step_);
  return true;
}

bool SunExitMap::exit(double h, double scale, double launch_elevation, double* exit_elevation,
                      double* jacobian) const {
  Row r;
  if (!row(h, scale, &r)) return false;
  const double u = (launch_elevation - e_lo_) / e_step_;
  if (!(u >= double(r.first) && u <= double(launches_ - 1))) return false;
  const size_t lo = std::min(size_t(u), launches_ - 2), hi = lo + 1;
  const double a = r.at(lo), b = r.at(hi);
  const double exit = a + (u - double(lo)) * (b - a);
  *exit_elevation = exit;
  *jacobian = std::cos(exit) * (b - a) / (std::cos(launch_elevation) * e_step_);
  return true;
}

}  // namespace refracta
