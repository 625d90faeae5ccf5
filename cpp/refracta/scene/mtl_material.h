// A Wavefront MTL material record as a file states it (Kd, Ks, Ns, d, Ni, illum, Ke, Pr, Pm,
// map_Kd, map_d): data of the scene layer. The render layer turns it into a shading Material
// (render/mtl_materials.h); shading/ never sees this struct.
#pragma once

#include "refracta/core/math.h"

#include <string>

namespace refracta {

struct MtlMaterial {
  std::string name;
  Vec3d kd{0.5, 0.5, 0.5};   // diffuse albedo in [0, 1]
  Vec3d ks{0.0, 0.0, 0.0};   // specular albedo in [0, 1]
  double ns = 1.0;           // Phong exponent, >= 0
  double alpha = 1.0;        // opacity in [0, 1] (d)
  double ni = 1.0;           // index of refraction (Ni)
  int illum = 2;             // illumination model
  Vec3d ke{0.0, 0.0, 0.0};   // emitted radiance (Ke) [W/(m^2 sr)]
  double pr = -1.0;          // PBR roughness (Pr), -1 when absent
  double pm = -1.0;          // PBR metallic (Pm), -1 when absent
  std::string texture;       // map_Kd path (resolved against the MTL's folder), empty when none
  std::string texture_name;  // map_Kd as the MTL file writes it (find_texture searches for it)
  std::string cutout_name;   // map_d as the MTL file writes it (a cut-out mask), empty when none
  std::string folder;        // the folder map_Kd and map_d are relative to: the MTL's
  std::string clamped;       // the values the loader moved into range ("Kd (5, -1, 0.5), d 7"), empty if none
  std::string ignored;       // what it gives that refracta does not render ("map_d (an alpha texture)"), or empty
};

}  // namespace refracta
