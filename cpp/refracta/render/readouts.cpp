// Per-pixel readouts: angles, true elevations, hidden heights, mirage multiplicity (readouts.h).
#include "refracta/render/readouts.h"

#include "refracta/media/curved_earth.h"
#include "refracta/rays/trace.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegrees = 180.0 / kPi;

// A ray from `eye` at elevation e [rad] (its azimuth does not matter in height-only air).
Vec3d at_elevation(double e) { return Vec3d(std::cos(e), std::sin(e), 0.0); }

// The grazing ray's elevation is bisected to this [rad]: it moves the ray's heights by ~1e-6 m
// at 100 km (the hidden height is read to centimetres). Finer, the rays tried touch the ground
// within nanometres, and over a hot surface layer each exact trace of such a ray took ~1 s (half
// a minute for a readout of any image before this bound).
constexpr double kGrazingElevation = 1e-11;

TraceOptions grazing_options(double max_length, const std::atomic<bool>* cancel) {
  TraceOptions options;
  options.cancel = cancel;
  options.trace = TraceMethod::kStratified;
  options.tol = 1e-4;  // [m]: far below the centimetres a hidden height is read to
  options.max_length = max_length;
  options.stop_height = 0.0;  // the ground: a ray descending through it has met it
  return options;
}

}  // namespace

double true_path_length(double length, double y_start, double y_end, double slope_start, double slope_end,
                        double earth_radius) {
  if (!std::isfinite(earth_radius) || !std::isfinite(length)) return length;
  const double y_middle = 0.5 * (y_start + y_end) + 0.125 * length * (slope_start - slope_end);  // Hermite
  auto scale = [&](double y) { return std::exp(y / earth_radius); };
  return length * (scale(y_start) + 4.0 * scale(y_middle) + scale(y_end)) / 6.0;
}

Vec2d apparent_angles(const Vec3d& direction) {
  const Vec3d d = direction.normalized();
  double azimuth = std::atan2(d.x(), -d.z()) * kDegrees;
  if (azimuth < 0.0) azimuth += 360.0;
  if (azimuth >= 360.0) azimuth -= 360.0;  // -0 and rounding
  return Vec2d(std::asin(std::clamp(d.y(), -1.0, 1.0)) * kDegrees, azimuth);
}

ReadoutGeometry::ReadoutGeometry(const Vec3d& eye, const IndexField* field, double max_length,
                                 const std::atomic<bool>* cancel)
    : eye_(eye) {
  if (field) radius_ = field->earth_radius();
  std::shared_ptr<const IndexField> layered;
  const IndexField* air = nullptr;
  if (field && field->height_only()) {
    air = field;
  } else if (field) {
    layered = field->height_only_part();
    air = layered.get();
  }
  if (!air || !(eye.y() > 0.0)) return;
  const TraceOptions options = grazing_options(max_length, cancel);
  // A ray rising above straight_above() goes on straight in the world, away from the ground: it
  // never meets it. The bisection's traces end there (they ran to max_length, and over a curved
  // Earth's flat coordinates their steps shrink as they climb: 38 traces of 0.9 s each at 2000 km,
  // a trial's 14.7 s for the readouts of an 8 x 8 render).
  const double straight = air->straight_above();
  auto meets_ground = [&](double e) {
    return trace(*air, eye, at_elevation(e), options, [straight](const RayNode<double>&, const RayNode<double>& b) {
             return !(b.x.y() >= straight && b.tangent().y() > 0.0);
           }).stop == TraceStop::kStopHeight;
  };
  // Bisection between a ray that meets the ground and one that does not.
  double lo = -0.5 * kPi + 1e-9, hi = 0.0;
  if (!meets_ground(lo)) return;
  for (double up : {0.0, 0.25 * kPi, 0.5 * kPi - 1e-9}) {
    hi = up;
    if (!meets_ground(hi)) break;
    if (up > 0.5 * kPi - 1e-6) return;  // every ray meets the ground: no grazing ray
  }
  while (hi - lo > kGrazingElevation) {
    const double mid = 0.5 * (lo + hi);
    (meets_ground(mid) ? lo : hi) = mid;
  }
  double lowest = std::numeric_limits<double>::infinity();
  auto record = [&](const RayNode<double>& node) {
    const double r = std::hypot(node.x.x() - eye.x(), node.x.z() - eye.z());
    const Vec3d t = node.tangent();
    const double horizontal = std::hypot(t.x(), t.z());
    if (!r_.empty() && !(r > r_.back())) return;  // a vertical start: r does not advance
    r_.push_back(r);
    y_.push_back(node.x.y());
    slope_.push_back(t.y() / std::max(horizontal, 1e-300));
    if (node.x.y() < lowest) lowest = node.x.y(), touch_ = r;
  };
  bool first = true;
  trace(*air, eye, at_elevation(hi), options, [&](const RayNode<double>& a, const RayNode<double>& b) {
    if (first) record(a), first = false;
    record(b);
    return true;
  });
  has_grazing_ = r_.size() >= 2;
}

double ReadoutGeometry::true_height(double flat_y) const {
  return std::isfinite(radius_) ? radius_ * std::expm1(flat_y / radius_) : flat_y;
}

Vec3d ReadoutGeometry::sphere_point(const Vec3d& flat) const { return CurvedEarth::sphere_point(flat, radius_); }

double ReadoutGeometry::true_elevation(const Vec3d& point) const {
  if (!point.allFinite()) return kNaN;
  Vec3d chord = point - eye_, up(0.0, 1.0, 0.0);
  if (std::isfinite(radius_)) {
    const Vec3d e = sphere_point(eye_);
    chord = sphere_point(point) - e;
    up = e.normalized();
  }
  const double length = chord.norm();
  if (!(length > 0.0)) return kNaN;
  return std::asin(std::clamp(chord.dot(up) / length, -1.0, 1.0)) * kDegrees;
}

double ReadoutGeometry::hidden_geometric(const Vec3d& point) const {
  if (!point.allFinite()) return kNaN;
  if (!std::isfinite(radius_)) return 0.0;
  const double eye_height = true_height(eye_.y());
  if (!(eye_height > 0.0)) return kNaN;
  const Vec3d e = sphere_point(eye_).normalized(), p = sphere_point(point).normalized();
  const double theta = std::atan2(e.cross(p).norm(), e.dot(p));
  const double horizon = std::acos(radius_ / (radius_ + eye_height));
  if (theta <= horizon) return 0.0;
  const double beyond = theta - horizon;
  if (beyond >= 0.5 * kPi) return std::numeric_limits<double>::infinity();
  // R (sec(beyond) - 1) without cancellation: 2 R sin^2(beyond / 2) / cos(beyond).
  const double half = std::sin(0.5 * beyond);
  return 2.0 * radius_ * half * half / std::cos(beyond);
}

double ReadoutGeometry::hidden_refracted(const Vec3d& point) const {
  if (!point.allFinite()) return kNaN;
  if (!has_grazing_) return kNaN;
  const double r = std::hypot(point.x() - eye_.x(), point.z() - eye_.z());
  if (r <= touch_) return 0.0;
  if (r > r_.back()) return kNaN;
  // Cubic Hermite interpolation of y'(r) between the nodes, from their heights and slopes.
  const size_t i = size_t(std::upper_bound(r_.begin(), r_.end(), r) - r_.begin()) - 1;
  const size_t j = std::min(i + 1, r_.size() - 1);
  const double h = r_[j] - r_[i];
  double y = y_[i];
  if (h > 0.0) {
    const double t = (r - r_[i]) / h, t2 = t * t, t3 = t2 * t;
    y = (2 * t3 - 3 * t2 + 1) * y_[i] + (t3 - 2 * t2 + t) * h * slope_[i] + (-2 * t3 + 3 * t2) * y_[j] +
        (t3 - t2) * h * slope_[j];
  }
  return std::max(0.0, true_height(y));
}

std::vector<std::pair<std::string, std::pair<int, int>>> readout_channels() {
  const std::pair<const char*, std::pair<int, int>> layout[] = {
      {"distance", {kReadoutDistance, 1}},
      {"position", {kReadoutPosition, 3}},
      {"object_id", {kReadoutObject, 1}},
      {"apparent_elevation", {kReadoutApparentElevation, 1}},
      {"apparent_azimuth", {kReadoutApparentAzimuth, 1}},
      {"true_elevation", {kReadoutTrueElevation, 1}},
      {"hidden_height", {kReadoutHiddenHeight, 2}}};
  std::vector<std::pair<std::string, std::pair<int, int>>> out;
  for (const auto& [name, at] : layout) out.push_back({name, {kSurfaceChannels + at.first, at.second}});
  return out;
}

CountImage mirage_images(const FloatImage& true_elevation, const FloatImage& object_id) {
  if (true_elevation.rows() != object_id.rows() || true_elevation.cols() != object_id.cols()) {
    throw_invalid("mirage_images: true_elevation and object_id must be (H, W) arrays of one shape (got ",
                  true_elevation.rows(), " x ", true_elevation.cols(), " and ", object_id.rows(), " x ", object_id.cols(),
                  ")");
  }
  const int height = int(true_elevation.rows()), width = int(true_elevation.cols());
  CountImage images = CountImage::Zero(height, width);
  struct Branch {
    float object, lo, hi;
  };
  std::vector<Branch> branches;
  for (int x = 0; x < width; ++x) {
    auto value = [&](int y) { return true_elevation(y, x); };
    auto object = [&](int y) { return object_id(y, x); };
    auto valid = [&](int y) { return object(y) >= 0.0f && std::isfinite(value(y)); };
    branches.clear();
    int y = 0;
    while (y < height) {
      if (!valid(y)) {
        ++y;
        continue;
      }
      // One run of rows on the same object, cut into monotone branches.
      int start = y;
      int sign = 0;  // the branch's direction so far: +1 rising, -1 falling, 0 not yet known
      int end = y;
      while (end + 1 < height && valid(end + 1) && object(end + 1) == object(start)) {
        const float step = value(end + 1) - value(end);
        const int s = step > 0.0f ? 1 : step < 0.0f ? -1 : 0;
        if (s != 0 && sign != 0 && s != sign) {  // a turning row: it ends this branch and starts the next
          branches.push_back({object(start), std::min(value(start), value(end)), std::max(value(start), value(end))});
          start = end;
          sign = s;
        } else if (s != 0) {
          sign = s;
        }
        ++end;
      }
      branches.push_back({object(start), std::min(value(start), value(end)), std::max(value(start), value(end))});
      y = end + 1;
    }
    for (int row = 0; row < height; ++row) {
      if (!valid(row)) continue;
      int count = 0;
      for (const Branch& b : branches) count += b.object == object(row) && b.lo <= value(row) && value(row) <= b.hi;
      images(row, x) = count;
    }
  }
  return images;
}

}  // namespace refracta
