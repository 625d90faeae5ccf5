// The highest geometry over each cell of a horizontal grid across a scene. A shadow or bounce ray
// rising from the sea far from the ships has nothing over the ground it crosses as high as where it
// starts: it cannot meet anything on its way up (Caster::cast_monotone), and the chords that test
// its path against the scene can be skipped.
#pragma once

#include "refracta/scene/embree_scene.h"

#include <vector>

namespace refracta {

class HeightCover {
 public:
  // Every triangle's, sphere's and terrain's horizontal box raises the cells it meets to its top.
  explicit HeightCover(const Scene& scene);

  // The highest top over the cells the horizontal segment from (x0, z0) to (x1, z1) [m] passes:
  // -inf where no geometry stands there; +inf where it passes more than kMostCells cells (a
  // caller then tests its path as before, rather than walk them) or is not finite.
  double highest(double x0, double z0, double x1, double z1) const;

  static constexpr int kMostCells = 512;

 private:
  void raise(double x0, double z0, double x1, double z1, double top);
  int column(double x) const;
  int row(double z) const;

  double x_lo_ = 0.0, z_lo_ = 0.0, cell_ = 1.0;  // the grid's corner and cell side [m]
  int columns_ = 0, rows_ = 0;
  std::vector<double> tops_;  // [row * columns_ + column]; -inf: nothing there
};

}  // namespace refracta
