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
// The launch's solve: exits this far [rad] inside a row's covered ones (a path's azimuthal turn
// off the origin's axes, ~1e-3 rad at 60 km, moves its exit elevation far less), the tolerance
// [rad] on the exit's elevation and azimuth, the iterations allowed (2-3 taken), and the step
// [rad] of the Jacobian's difference quotients.
constexpr double kMapCoverMargin = 1e-3;
constexpr double kMapSolveTolerance = 1e-11;
constexpr int kMapSolveIterations = 8;
constexpr double kMapJacobianStep = 1e-7;

Vec3d toward(double elevation, const Vec3d& across) {
  return std::cos(elevation) * across + Vec3d(0.0, std::sin(elevation), 0.0);
}

}  // namespace

double start_frame_exit(const Caster& caster, double h, double elevation, double* run) {
  const Vec3d origin(0.0, h, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (run) *run = nan;
  try {
    const PathEnd end = caster.cast(origin, Vec3d(std::cos(elevation), std::sin(elevation), 0.0));
    if (end.hit) return nan;
    if (run) *run = end.end_point.x();
    return std::asin(std::clamp(Vec3d(caster.field()->sky_frame(origin).transpose() * end.direction).y(), -1.0, 1.0));
  } catch (const Cancelled&) {  // Ctrl-C: the render stops
    throw;
  } catch (const std::exception&) {  // a path below the field's modelled heights: no exit
    return nan;
  }
}

std::shared_ptr<const SunExitMap> SunExitMap::build(const Scene& scene, const std::vector<const IndexField*>& airs,
                                                     const std::vector<double>& scales, FieldPtr frame,
                                                     const RenderOptions& options, double spread, const SunLight& sun) {
  if (airs.empty() || airs.size() != scales.size() || airs.size() > 2 || !frame) return nullptr;
  if (!std::isfinite(frame->earth_radius())) return nullptr;
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
  map->radius_ = frame->earth_radius();
  map->frame_ = std::move(frame);
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
  map->runs_.assign(airs.size(), std::vector<double>(per_scale));
  WorkControl control;  // the caller's cancel flags stay in force (parallel_for_each)
  parallel_for_each(int64_t(airs.size() * per_scale), 1, control, [&](int64_t index) {
    const size_t k = size_t(index) / per_scale, node = size_t(index) % per_scale;
    const size_t j = node / map->launches_, i = node % map->launches_;
    map->exits_[k][node] = start_frame_exit(*casters[k], map->h_lo_ + double(j) * map->h_step_,
                                              map->e_lo_ + double(i) * map->e_step_, &map->runs_[k][node]);
  });
  // Each row's monotone part: from the highest launch down while the exit falls strictly.
  bool any = false;
  map->first_.assign(airs.size(), std::vector<size_t>(map->heights_, map->launches_));
  for (size_t k = 0; k < airs.size(); ++k) {
    for (size_t j = 0; j < map->heights_; ++j) {
      const double* row = &map->exits_[k][j * map->launches_];
      size_t first = map->launches_ - 1;
      if (std::isnan(row[first])) continue;
      const double* run = &map->runs_[k][j * map->launches_];
      while (first > 0 && row[first - 1] < row[first] && std::isfinite(run[first - 1])) --first;
      map->first_[k][j] = first;
      any = any || (first + 1 < map->launches_ && row[map->launches_ - 1] > 0.0);
    }
  }
  return any ? map : nullptr;
}

double SunExitMap::Row::at(const std::vector<std::vector<double>>& table, size_t i) const {
  auto value = [&](size_t k) {
    const std::vector<double>& nodes = table[k];
    return (1.0 - w_height) * nodes[cell * map->launches_ + i] + w_height * nodes[(cell + 1) * map->launches_ + i];
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

Vec3d SunExitMap::exit_of(const Row& r, const Vec3d& p, const Eigen::Matrix3d& to_world, double e,
                          const Vec3d& across) const {
  const double u = (e - e_lo_) / e_step_;
  const size_t i = std::min(size_t(std::max(u, 0.0)), launches_ - 2);
  const double t = u - double(i);
  const double exit = (1.0 - t) * r.at(exits_, i) + t * r.at(exits_, i + 1);
  const double run = (1.0 - t) * r.at(runs_, i) + t * r.at(runs_, i + 1);
  // Along +x from the origin the flat direction at the end is turned down by the central angle
  // run / R into the start's frame (CurvedEarth::sky_direction): undo that, then turn the path's
  // end at p + run across by the frame's own rotation there.
  const Vec3d end = p + run * across;
  return to_world.transpose() * frame_->sky_direction(end, toward(exit + run / radius_, across));
}

double SunExitMap::jacobian(const Row& r, const Vec3d& p, const Eigen::Matrix3d& to_world, double e,
                            const Vec3d& across, const Vec3d& x) const {
  // d omega_exit / d omega_launch: the area the exit's partial derivatives span over cos(e) de dphi,
  // by difference quotients (in elevation toward the inside of e's cell: the table is linear there).
  const double u = (e - e_lo_) / e_step_;
  const double cell_top = e_lo_ + (std::floor(u) + 1.0) * e_step_;
  const double de = e + kMapJacobianStep < cell_top ? kMapJacobianStep : -kMapJacobianStep;
  const Vec3d x_e = exit_of(r, p, to_world, e + de, across);
  const Vec3d sideways = Vec3d(-across.z(), 0.0, across.x());
  const Vec3d turned = (across + kMapJacobianStep * sideways).normalized();
  const Vec3d x_phi = exit_of(r, p, to_world, e, turned);
  const double dphi = std::atan2(kMapJacobianStep, 1.0);
  return (x_e - x).cross(x_phi - x).norm() / (std::abs(de) * dphi * std::cos(e));
}

bool SunExitMap::covered(const Row& r, const Vec3d& exit) const {
  const double target = std::asin(std::clamp(exit.y(), -1.0, 1.0));
  return target >= r.at(exits_, r.first) + kMapCoverMargin && target <= r.at(exits_, launches_ - 1) - kMapCoverMargin &&
         Vec3d(exit.x(), 0.0, exit.z()).norm() > 1e-9;
}

bool SunExitMap::covers(const Vec3d& p, double scale, const Vec3d& exit) const {
  Row r;
  return row(p.y(), scale, &r) && covered(r, exit);
}

std::optional<SunExitMap::Launch> SunExitMap::launch(const Vec3d& p, const Eigen::Matrix3d& to_world, double scale,
                                                     const Vec3d& exit) const {
  Row r;
  if (!row(p.y(), scale, &r) || !covered(r, exit)) return std::nullopt;
  Vec3d across = Vec3d(exit.x(), 0.0, exit.z()).normalized();
  const double target = std::asin(std::clamp(exit.y(), -1.0, 1.0));
  // The elevation along the origin's axis first: the cell [lo, lo + 1] holding the target exit.
  size_t lo = r.first, hi = launches_ - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (r.at(exits_, mid) <= target ? lo : hi) = mid;
  }
  double e = e_lo_ + (double(lo) + (target - r.at(exits_, lo)) / (r.at(exits_, hi) - r.at(exits_, lo))) * e_step_;
  const double e_first = e_lo_ + double(r.first) * e_step_, e_last = e_lo_ + double(launches_ - 1) * e_step_;
  // Then Newton steps in elevation (the cell's slope) and the azimuth's error turned back.
  for (int k = 0; k < kMapSolveIterations; ++k) {
    const Vec3d x = exit_of(r, p, to_world, e, across);
    const double elevation_error = target - std::asin(std::clamp(x.y(), -1.0, 1.0));
    const double azimuth_error =
        std::atan2(x.x() * exit.z() - x.z() * exit.x(), x.x() * exit.x() + x.z() * exit.z());
    if (std::abs(elevation_error) < kMapSolveTolerance && std::abs(azimuth_error) < kMapSolveTolerance) {
      return Launch{toward(e, across), jacobian(r, p, to_world, e, across, x)};
    }
    const double u = (e - e_lo_) / e_step_;
    const size_t i = std::min(size_t(std::max(u, 0.0)), launches_ - 2);
    const double slope = (r.at(exits_, i + 1) - r.at(exits_, i)) / e_step_;
    e += elevation_error / slope;
    const double c = std::cos(azimuth_error), s = std::sin(azimuth_error);
    across = Vec3d(c * across.x() - s * across.z(), 0.0, s * across.x() + c * across.z());
    if (!(e >= e_first && e <= e_last)) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<double> SunExitMap::density(const Vec3d& p, const Eigen::Matrix3d& to_world, double scale,
                                          const Vec3d& launch, Vec3d* exit) const {
  Row r;
  if (!row(p.y(), scale, &r)) return std::nullopt;
  Vec3d across(launch.x(), 0.0, launch.z());
  if (!(across.norm() > 1e-9)) return std::nullopt;
  across.normalize();
  const double e = std::asin(std::clamp(launch.y(), -1.0, 1.0));
  if (!(e >= e_lo_ + double(r.first) * e_step_ && e <= e_lo_ + double(launches_ - 1) * e_step_)) return std::nullopt;
  *exit = exit_of(r, p, to_world, e, across);
  // launch() takes up that exit and solves back to this launch (the rows rise strictly in
  // elevation, the azimuth turns smoothly: one launch per exit) to within kMapSolveTolerance.
  if (!covered(r, *exit)) return std::nullopt;
  return jacobian(r, p, to_world, e, across, *exit);
}

}  // namespace refracta
