// AreaLight (shared/SHADING.md section 5). Power: pi Y(L_e) A (one-sided), twice that two-sided.
//
// Sampling by area: a triangle with probability proportional to its area (PiecewiseConstant1D),
// a uniform point on it (sample_uniform_triangle), so pdf_A = 1 / A_total and the solid-angle
// density at the receiver pdf_w = pdf_A r^2 / |cos theta_l| (theta_l between the light's normal
// and -wi). Zero-area triangles get zero weight and are never sampled. A sample on the back of a
// one-sided light returns nullopt (it carries no light; the density is unchanged).
//
// Integrator: area lights are found by rays hitting the geometry. The lead's Scene adds the same
// mesh as geometry and keeps a map geometry id -> light; at a hit on it, the emitted radiance is
// L(hit.point, light.normal(hit.primitive), -ray_dir) -- pass the triangle's FRONT normal from
// normal(primitive), not Hit::normal (which faces the ray, so would make every side the front).
// MIS weight of that hit: pdf_li(ctx_of_previous_vertex, ray_dir, hit.point, any normal of the
// triangle) (|cos| is used, the sign does not matter). Next-event estimation: sample_li, then a
// shadow ray to p_light (stop short of it by an epsilon; the light's own triangle is there).
#pragma once

#include "refracta/scene/embree_scene.h"
#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

#include <memory>

namespace refracta {

// An emissive triangle mesh: vertices (V, 3) [m], triangles (T, 3) of vertex indices, uniform
// emission radiance L_e [W/(m^2 sr)] (a colour) from the counter-clockwise front of every
// triangle (front normal normalize((v1 - v0) x (v2 - v0))) or from both sides when two_sided.
class AreaLight final : public Light {
 public:
  // The mesh must have finite vertices, triangles indexing them, and a positive total area.
  AreaLight(std::shared_ptr<const Mesh> mesh, const Color& emission, bool two_sided = false);
  AreaLight(Mesh mesh, const Color& emission, bool two_sided = false)
      : AreaLight(std::make_shared<const Mesh>(std::move(mesh)), emission, two_sided) {}

  LightType type() const override { return LightType::kArea; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  // pdf_A |p_light - ctx.p|^2 / |n_light . wi| (0 when the cosine or the distance is 0).
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  // L_e when w (unit, away from the light) is on the emitting side of the front normal n_light.
  Spectrum L(const Vec3d& p_light, const Vec3d& n_light, const Vec3d& w, const SampledWavelengths& lambda) const override;
  double power() const override;
  std::string describe() const override;

  const Mesh& mesh() const { return *mesh_; }
  // The front normal of a triangle (unit; zero for a zero-area triangle).
  const Vec3d& normal(size_t triangle) const { return normals_.at(triangle); }
  double area() const { return area_; }
  bool two_sided() const { return two_sided_; }
  const Color& emission() const { return emission_; }

 private:
  std::shared_ptr<const Mesh> mesh_;
  Color emission_;
  bool two_sided_;
  std::vector<Vec3d> normals_;
  PiecewiseConstant1D distribution_;  // over triangles, by area
  double area_ = 0.0;
};

}  // namespace refracta
