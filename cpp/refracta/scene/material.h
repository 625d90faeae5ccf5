// Surface parameters of a Blinn-Phong material (as in Wavefront MTL: Kd, Ks, Ns), linear RGB.
// The shading layer evaluates it (shading/blinn_phong.h).
#pragma once

#include "refracta/core/math.h"

namespace refracta {

struct Material {
  Vec3d kd{0.5, 0.5, 0.5};  // diffuse albedo in [0, 1]
  Vec3d ks{0.0, 0.0, 0.0};  // specular albedo in [0, 1]
  double ns = 1.0;          // Phong exponent, >= 0
  int kd_texture = -1;      // Textures id multiplying kd (MTL map_Kd), -1 for none
  double alpha = 1.0;       // opacity in [0, 1] (MTL d); below 1, render_raster composites it as transparent

  void validate() const;  // throws std::invalid_argument naming the bad field
};

}  // namespace refracta
