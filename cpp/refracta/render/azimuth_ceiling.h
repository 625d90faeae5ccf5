// The highest geometry around the eye by azimuth. The eye's table paths stop testing chords once
// they stay above everything (Caster::cast_table); with one ceiling for the whole scene, sky rays
// beside a coast 165 m high walked 1 km chords ~30 km out over an empty sea before they stopped.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/embree_scene.h"

#include <vector>

namespace refracta {

class AzimuthCeiling {
 public:
  AzimuthCeiling() = default;
  // Bins of azimuth about the vertical through `eye`, each holding the highest point [m] of every
  // triangle and sphere whose azimuth span meets it (a triangle or sphere around the eye's
  // vertical: every bin). Scenes with terrain grids keep the scene's top everywhere.
  AzimuthCeiling(const Scene& scene, const Vec3d& eye);
  // The highest geometry over the azimuth of `dir` and the bins either side (a path strays from
  // its vertical plane by a fraction of a pixel, a bin is 3 mrad); -inf where there is none.
  double at(const Vec3d& dir) const;

 private:
  void raise(double from, double to, double height);  // azimuths [rad], from <= to (may pass pi)
  std::vector<double> bins_;
};

}  // namespace refracta
