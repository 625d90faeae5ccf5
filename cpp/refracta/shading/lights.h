// The lights of a mirage scene: a sun (a distant disc) and a sky (constant or a vertical
// gradient), in linear RGB radiance [W/(m^2 sr)] per channel.
#pragma once

#include "refracta/core/math.h"

namespace refracta {

struct Sun {
  Vec3d direction{0.3, 0.8, 0.2};   // toward the sun (normalised on validate)
  Vec3d radiance{0.0, 0.0, 0.0};    // of the disc; 0 switches the sun off
  double angular_diameter = 0.53;   // [deg]

  // Irradiance on a surface facing the sun: radiance x solid angle of the disc.
  Vec3d irradiance() const;
  void validate();
};

struct Sky {
  Vec3d horizon{0.7, 0.8, 0.95};  // radiance toward the horizon (and below it)
  Vec3d zenith{0.25, 0.45, 0.85}; // radiance straight up

  // Radiance seen looking along dir: linear in the elevation's sine from horizon to zenith.
  Vec3d radiance(const Vec3d& dir) const;
  // Mean radiance over the upper hemisphere weighted by cos (for ambient light).
  Vec3d mean_radiance() const;
  void validate() const;
};

struct Lighting {
  Sun sun;
  Sky sky;
  bool shadows = true;
};

}  // namespace refracta
