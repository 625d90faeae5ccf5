// What a ray found on a surface, in the form shading needs: the point, the geometric normal as
// the geometry defines it (not flipped toward the ray) with a front-face flag, the shading
// normal (interpolated vertex normals, or the geometric one), texture coordinates and their
// footprint, and the ids of the geometry and its material. pbrt-v4's SurfaceInteraction.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/textures.h"

#include <Eigen/Core>

namespace refracta {

struct SurfaceInteraction {
  Vec3d p = Vec3d::Zero();           // [m]
  Vec3d n = Vec3d::UnitY();          // unit geometric normal: triangles' counter-clockwise front, spheres outward
  Vec3d ns = Vec3d::UnitY();         // unit shading normal, on the same side as n
  Vec3d dpdu = Vec3d::UnitX();       // tangent along u (a unit fallback when there are no uvs)
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Vec3d wo = Vec3d::UnitY();         // unit, back along the arriving ray (toward its origin)
  bool front_face = true;            // the ray arrived on the side n points to (wo . n > 0)
  double t = 0.0;                    // distance along the chord that found it [m]
  unsigned geometry = 0, primitive = 0;
  int material = -1;                 // id in the render scene's material table
  TextureLookup texture;             // (s, t) and its footprint derivatives for image textures
  // The width [m] across the arriving ray of the pixel's cone at p (a render's paths set it; 0:
  // none): rays leaving p stand for that footprint (Caster::cast's origin_width).
  double footprint = 0.0;

  // The geometric normal on wo's side (where the ray came from).
  Vec3d n_toward_wo() const { return front_face ? n : Vec3d(-n); }
  // A point moved off the surface along the geometric normal to the side of w, so that a ray
  // leaving along w does not find this surface again.
  Vec3d offset_toward(const Vec3d& w) const {
    const double eps = 1e-5 + 2e-6 * p.cwiseAbs().maxCoeff();  // float Embree: relative precision
    return p + (n.dot(w) > 0.0 ? n : Vec3d(-n)) * eps;
  }
};

}  // namespace refracta
