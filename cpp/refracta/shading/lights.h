// The lights of a mirage scene: a sun (a distant disc) and a sky (constant or a vertical
// gradient), in linear RGB radiance [W/(m^2 sr)] per channel.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/textures.h"

#include <memory>
#include <vector>

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

// A spot light: a point (or, for soft shadows, a disc of `radius` facing `direction`) emitting
// intensity [W/sr per channel] into a cone of full angle `angle`; irradiance I cos / d^2.
struct SpotLight {
  Vec3d position{0.0, 10.0, 0.0};
  Vec3d direction{0.0, -1.0, 0.0};  // the cone's axis (normalised on validate)
  double angle = 60.0;              // full cone angle [deg], in (0, 170]
  Vec3d intensity{100.0, 100.0, 100.0};
  double radius = 0.0;              // [m]; > 0: an area light, its shadows sampled (soft)

  // Whether a point lies inside the cone.
  bool covers(const Vec3d& point) const;
  void validate();
};

struct Lighting {
  Sun sun;
  Sky sky;
  std::vector<SpotLight> spots;
  bool shadows = true;
};

}  // namespace refracta
