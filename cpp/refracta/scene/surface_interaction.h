// What a ray found on a surface, in the form shading needs: the point, the geometric normal as
// the geometry defines it (not flipped toward the ray) with a front-face flag, the shading
// normal (interpolated vertex normals, or the geometric one), texture coordinates and their
// footprint, and the ids of the geometry and its material. pbrt-v4's SurfaceInteraction.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/textures.h"

#include <Eigen/Core>

#include <algorithm>

namespace refracta {

// A point of a surface moved off it along its unit normal n before a ray leaves, so that Embree's
// single-precision test of that ray does not meet the surface again. Embree holds the vertices in
// float and computes with them: the float surface may lie about gamma_7 = 7 u / (1 - 7 u) = 4.2e-7
// (u = 2^-24) of the coordinates away, per axis, and only the axes across the surface move it
// along n (pbrt-v4 6.8.6, "Robust spawned ray origins": the offset |n| . error). `extent`: per
// axis the largest |coordinate| of the primitive's vertices (Hit::extent; at least p's). 2e-6 of
// the point's largest coordinate lost a 1 m plate's shadow 1000 km from the origin (a trial), and
// of the point alone a 60 km tilted quad shadowed itself (a review); a level road 20 km wide keeps
// a 1e-5 m offset (its float plane is exact).
constexpr double kSurfaceOffsetAbsolute = 1e-5;  // [m]
constexpr double kSurfaceOffsetRelative = 5e-7;
inline Vec3d offset_point(const Vec3d& p, const Vec3d& n, const Vec3d& extent) {
  const double error = n.cwiseAbs().dot(extent.cwiseMax(p.cwiseAbs()));
  return p + n * (kSurfaceOffsetAbsolute + kSurfaceOffsetRelative * error);
}

struct SurfaceInteraction {
  Vec3d p = Vec3d::Zero();           // [m]
  Vec3d extent = Vec3d::Zero();      // [m] per axis, the primitive's largest |coordinate| (Hit::extent)
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
  // The width [m] across the arriving ray of the pixel's cone at p, pixel angle x path length (a
  // render's paths set it; 0: none). Rays leaving p stand for the pixel too (Caster::cast's
  // origin_width, cone_width_along).
  double cone_width = 0.0;

  // The pixel's footprint as a ray leaving along unit w sees it [m]: the cone (cone_width across
  // wo) carried along wo onto the surface's plane, then projected across w, its narrowest
  // width. A ray that strays from its path by less than that across w could have left from
  // another point of the footprint, as the pixel's own samples do. Head-on it is cone_width; a
  // ray leaving at grazing incidence across the footprint's short axis sees |n . w| of it; one
  // along the long axis of a grazing view (a sea's glitter) up to cone_width again. 0 without a cone.
  double cone_width_along(const Vec3d& w) const {
    const double cos_o = n.dot(wo);
    if (!(cone_width > 0.0) || !(std::abs(cos_o) > 1e-9)) return 0.0;
    const Vec3d u1 = wo.cross(std::abs(wo.x()) < 0.9 ? Vec3d::UnitX() : Vec3d::UnitY()).normalized();
    const Vec3d u2 = wo.cross(u1);
    auto carried = [&](const Vec3d& u) {
      const Vec3d on_surface = u - wo * (n.dot(u) / cos_o);
      return Vec3d(on_surface - w * on_surface.dot(w));
    };
    const Vec3d c1 = carried(u1), c2 = carried(u2);
    // The smaller singular value of [c1 c2]: the least eigenvalue of its Gram matrix, rooted.
    const double a = c1.squaredNorm(), b = c1.dot(c2), c = c2.squaredNorm();
    const double least = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    return cone_width * std::sqrt(std::max(least, 0.0));
  }

  // The geometric normal on wo's side (where the ray came from).
  Vec3d n_toward_wo() const { return front_face ? n : Vec3d(-n); }
  // Light leaking through a shading normal: wi on the other side of the surface from wo where the
  // BSDF takes it as reflected (the shading frame puts both on one side), refused by every sampler.
  bool leaks(const Vec3d& wi, bool transmitted) const {
    return (wi.dot(n) > 0.0) != (wo.dot(n) > 0.0) && !transmitted;
  }
  // A point moved off the surface along the geometric normal to the side of w, so that a ray
  // leaving along w does not find this surface again.
  Vec3d offset_toward(const Vec3d& w) const { return offset_point(p, n.dot(w) > 0.0 ? n : Vec3d(-n), extent); }
};

}  // namespace refracta
