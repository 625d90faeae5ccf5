// The lights of a mirage scene: a sun (a distant disc) and a sky (constant or a vertical
// gradient), in linear RGB radiance [W/(m^2 sr)] per channel.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/textures.h"

#include <memory>

namespace refracta {

struct Sun {
  Vec3d direction{0.3, 0.8, 0.2};   // toward the sun (normalised on validate)
  Vec3d radiance{0.0, 0.0, 0.0};    // of the disc; 0 switches the sun off
  double angular_diameter = 0.53;   // [deg]

  // Irradiance on a surface facing the sun: radiance x solid angle of the disc.
  Vec3d irradiance() const;
  void validate();
};

// A sky: a vertical gradient, or an equirectangular environment map (textures.h conventions)
// scaled by `scale`.
struct Sky {
  Vec3d horizon{0.7, 0.8, 0.95};  // radiance toward the horizon (and below it)
  Vec3d zenith{0.25, 0.45, 0.85}; // radiance straight up
  std::shared_ptr<const Textures> textures;
  int environment = -1;           // Textures id of the map, -1 for the gradient
  double scale = 1.0;

  Sky() { validate(); }

  // Radiance seen looking along dir (footprint: the angular width [rad] a map is filtered over):
  // the map, or linear in the elevation's sine from horizon to zenith.
  Vec3d radiance(const Vec3d& dir, double footprint = 0.0) const;
  // Mean radiance over the upper hemisphere weighted by cos (for ambient light).
  Vec3d mean_radiance() const { return mean_; }
  // Checks the values and computes mean_radiance (by quadrature for a map).
  void validate();

 private:
  Vec3d mean_ = Vec3d::Zero();
};

struct Lighting {
  Sun sun;
  Sky sky;
  bool shadows = true;
};

}  // namespace refracta
