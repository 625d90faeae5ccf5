// Where a field that is height-only almost everywhere differs from its height-only part: a
// vertical cylinder (an areal hot spot) or a horizontal slab (a turbulent layer) below a top
// height. Outside every region the field equals the height-only part to a negligible fraction of
// each feature's peak (kNegligibleFeature); the renderer serves rays that stay outside from the
// height-only machinery (ElevationTable, Bouguer chords) and traces only the others.
#pragma once

#include "refracta/core/math.h"

#include <limits>
#include <optional>
#include <vector>

namespace refracta {

// A feature's change of n is cut where it falls below this fraction of its peak: 1e-6 of a hot
// spot's ~1e-5 in n is 1e-11, a deflection of ~1e-11 rad over the spot -- nothing a pixel shows.
constexpr double kNegligibleFeature = 1e-6;

struct LocalRegion {
  double x = 0.0, z = 0.0;  // axis of the cylinder [m]
  double radius = std::numeric_limits<double>::infinity();  // [m]; infinite: a slab
  double top = 0.0;         // the region is everything below this height [m]
  // The feature's horizontal scale [m] (a spot's radius): an integrator inside the region steps at
  // most half of it, so that its error estimate cannot step over the feature.
  double scale = std::numeric_limits<double>::infinity();

  bool contains(const Vec3d& p) const {
    if (!(p.y() < top)) return false;
    const double dx = p.x() - x, dz = p.z() - z;
    return !std::isfinite(radius) || dx * dx + dz * dz < radius * radius;
  }
  // The same region grown by `margin` [m] sideways and upward.
  LocalRegion grown(double margin) const { return {x, z, radius + margin, top + margin, scale}; }
  // The first parameter t in [0, length] where the segment p + t d (unit d) is inside, if any.
  std::optional<double> entry(const Vec3d& p, const Vec3d& d, double length) const;
};

// The earliest entry into any of the regions along the segment; nullopt if none is entered.
std::optional<double> first_entry(const std::vector<LocalRegion>& regions, const Vec3d& p, const Vec3d& d,
                                  double length);
// The highest top among the regions (-inf for none).
double highest_top(const std::vector<LocalRegion>& regions);
// The smallest scale among the regions (+inf for none).
double smallest_scale(const std::vector<LocalRegion>& regions);
// The longest step (at most h) [m] from p along the unit d that cannot pass over a region's
// feature: inside a region half its scale, from outside half a scale past where the straight step
// enters one. An adaptive integrator sees the field only at its stages: rk45 in calm air grows its
// steps to tens of metres and stepped over a 10 m hot spot whole (a trial: the spot changed no
// traced path, and editing its temperature had no gradient).
double step_within_regions(const std::vector<LocalRegion>& regions, const Vec3d& p, const Vec3d& d, double h);

}  // namespace refracta
