// SphereLight (shared/SHADING.md section 5). Seen from distance d on the normal of a facing
// surface, its irradiance is pi L_e (r / d)^2.
//
// Sampling (pbrt-v4 Sphere::Sample(ctx)): from outside, a uniform direction in the cone the sphere
// subtends, sin^2(theta_max) = r^2 / d^2, pdf_w = 1 / (2 pi (1 - cos theta_max)), the point on
// the sphere found through the angle at its centre (stable for small and grazing cones). From
// inside (d <= r) the outward-emitting sphere sends nothing to the point: sample_li samples the
// area uniformly, pdf_w = r'^2 / (|cos theta_l| 4 pi r^2), and returns nullopt (black).
//
// Integrator: an area light (kArea). The lead's Scene adds the sphere as geometry (add_spheres)
// and maps its geometry id -> light; at a hit, emitted = L(hit.point, outward normal
// (hit.point - centre)/r, -ray_dir); MIS with pdf_li(ctx_prev, ray_dir, hit.point, outward normal).
#pragma once

#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

namespace refracta {

// An emissive sphere: centre [m], radius [m], uniform emission radiance L_e [W/(m^2 sr)] (a
// colour) leaving its surface outward; power 4 pi^2 r^2 Y(L_e).
class SphereLight final : public Light {
 public:
  SphereLight(const Vec3d& centre, double radius, const Color& emission);

  LightType type() const override { return LightType::kArea; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  // Outside: the cone's density for wi inside the cone, else 0 (p_light, n_light unused).
  // Inside: the area density converted with p_light, n_light.
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  // L_e when w (unit, away from the surface) leaves the sphere outward: n_outward . w > 0, with
  // the outward normal taken from p_light (n_light may face either way).
  Spectrum L(const Vec3d& p_light, const Vec3d& n_light, const Vec3d& w, const SampledWavelengths& lambda) const override;
  double power() const override;
  std::string describe() const override;

  const Vec3d& centre() const { return centre_; }
  double radius() const { return radius_; }
  const Color& emission() const { return emission_; }

 private:
  // Whether p samples the sphere from inside: within it, or on it to a relative 1e-9 (its surface
  // from inside, a rounding outside: from just outside the cone would be the hemisphere, and a
  // trial saw the inner wall of a sphere light lit by the sphere).
  bool from_inside(const Vec3d& p) const;

  Vec3d centre_;
  double radius_;
  Color emission_;
};

}  // namespace refracta
