// Segment entry into a region below a height: a slab, or a vertical cylinder (local_region.h).
#include "refracta/media/local_region.h"

#include <algorithm>
#include <cmath>

namespace refracta {

std::optional<double> LocalRegion::entry(const Vec3d& p, const Vec3d& d, double length) const {
  // Below the top: t in (-inf, t_top) or (t_top, inf) or all or none.
  double lo = 0.0, hi = length;
  if (d.y() == 0.0) {
    if (!(p.y() < top)) return std::nullopt;
  } else {
    const double t_top = (top - p.y()) / d.y();
    if (d.y() > 0.0) hi = std::min(hi, t_top);
    else lo = std::max(lo, t_top);
  }
  if (std::isfinite(radius)) {
    // |(p + t d - c)_xz|^2 < R^2: a quadratic in t.
    const double px = p.x() - x, pz = p.z() - z;
    const double a = d.x() * d.x() + d.z() * d.z();
    const double b = px * d.x() + pz * d.z();
    const double c = px * px + pz * pz - radius * radius;
    if (a == 0.0) {
      if (!(c < 0.0)) return std::nullopt;
    } else {
      const double disc = b * b - a * c;
      if (!(disc > 0.0)) return std::nullopt;
      const double root = std::sqrt(disc);
      lo = std::max(lo, (-b - root) / a);
      hi = std::min(hi, (-b + root) / a);
    }
  }
  if (!(lo < hi)) return std::nullopt;
  return lo;
}

std::optional<double> first_entry(const std::vector<LocalRegion>& regions, const Vec3d& p, const Vec3d& d,
                                  double length) {
  std::optional<double> first;
  for (const LocalRegion& region : regions) {
    if (const auto t = region.entry(p, d, length); t && (!first || *t < *first)) first = t;
  }
  return first;
}

double highest_top(const std::vector<LocalRegion>& regions) {
  double top = -std::numeric_limits<double>::infinity();
  for (const LocalRegion& region : regions) top = std::max(top, region.top);
  return top;
}

double smallest_scale(const std::vector<LocalRegion>& regions) {
  double scale = std::numeric_limits<double>::infinity();
  for (const LocalRegion& region : regions) scale = std::min(scale, region.scale);
  return scale;
}

double step_within_regions(const std::vector<LocalRegion>& regions, const Vec3d& p, const Vec3d& d, double h) {
  double step = h;
  for (const LocalRegion& region : regions) {
    if (region.contains(p)) {
      step = std::min(step, 0.5 * region.scale);
    } else if (const auto t = region.entry(p, d, step)) {
      step = std::min(step, *t + 0.5 * region.scale);
    }
  }
  return step;
}

}  // namespace refracta
