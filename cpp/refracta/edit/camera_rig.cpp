// CameraRig: the names, search boxes and solved camera of an edit's camera parameters.
#include "refracta/edit/camera_rig.h"

#include "refracta/core/error.h"

#include <algorithm>

namespace refracta {

namespace {

// [deg] the default box of camera_roll: a photograph held by hand tilts a few degrees, one on a
// tripod less; beyond 15 deg the horizon would be plainly crooked.
constexpr double kRollBound = 15.0;
// The default box of camera_vfov: the start's within this factor either way (EXIF focal lengths
// and sensor sizes are off by percents, a crop or a converter by less than 2).
constexpr double kVfovFactor = 2.0;
// [deg] vfov stays this far inside (0, 180): tan(vfov / 2) is finite and the map invertible.
constexpr double kVfovMargin = 1e-3;

}  // namespace

const std::array<const char*, CameraRig::kCount>& CameraRig::names() {
  static const std::array<const char*, kCount> names = {"camera_yaw", "camera_pitch", "camera_roll", "camera_vfov"};
  return names;
}

int CameraRig::index_of(const std::string& name) {
  const auto& all = names();
  for (int k = 0; k < kCount; ++k) {
    if (name == all[k]) return k;
  }
  return -1;
}

CameraRig::CameraRig(const Camera& camera) : start_(camera) {
  if (!camera.jitter().empty()) {
    throw_invalid("camera parameters cannot be solved for a jittered camera (its rays do not follow the pinhole "
                  "map): pass the camera without jitter");
  }
}

std::array<double, CameraRig::kCount> CameraRig::start_values() const { return {0.0, 0.0, 0.0, start_.vfov()}; }

std::pair<double, double> CameraRig::default_bounds(int k) const {
  const double vfov = start_.vfov();
  const double hfov = radians_to_degrees(2.0 * std::atan(start_.tan_half() * start_.width() / start_.height()));
  switch (k) {
    case 0: return {-0.5 * hfov, 0.5 * hfov};
    case 1: return {-0.5 * vfov, 0.5 * vfov};
    case 2: return {-kRollBound, kRollBound};
    default: return {std::max(vfov / kVfovFactor, kVfovMargin), std::min(vfov * kVfovFactor, 180.0 - kVfovMargin)};
  }
}

std::pair<double, double> CameraRig::widest_bounds(int k) {
  return k < 3 ? std::make_pair(-180.0, 180.0) : std::make_pair(kVfovMargin, 180.0 - kVfovMargin);
}

void CameraRig::check_bounds(int k, double lower, double upper) {
  const char* name = names()[k];
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper)) {
    throw_invalid("bounds of '", name, "' must be finite with lower < upper (got [", lower, ", ", upper, "])");
  }
  const auto [lo, hi] = widest_bounds(k);
  if (lower < lo || upper > hi) {
    throw_invalid("bounds of '", name, "' must lie within [", lo, ", ", hi, "] deg (got [", lower, ", ", upper, "])");
  }
}

Camera CameraRig::camera(const double* values) const {
  const Vec3d forward = turned(0.0, 0.0, 1.0, values), up = turned(0.0, 1.0, 0.0, values);
  const Vec3d& position = start_.position();
  // The look-at point at the start's distance along the new view (a focus set from it is kept).
  const double distance = (start_.look_at() - position).norm();
  Camera out(position, position + distance * forward, up, values[3], start_.width(), start_.height());
  if (start_.aperture_diameter() > 0.0) out = out.with_lens(start_.aperture_diameter(), start_.focus_distance());
  return out;
}

}  // namespace refracta
