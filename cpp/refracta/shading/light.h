// The light interface (shared/SHADING.md section 5): point, spot, sun, area (emissive meshes and
// spheres), environment maps, a constant environment, the physical sky. Every light samples an
// incident direction at a point with its solid-angle density and evaluates what it emits; the
// integrators add occlusion and the curved air (a distant light is evaluated along the exit
// direction of the curved shadow ray). Units: radiance W/(m^2 sr), intensity W/sr.
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/sampling.h"
#include "refracta/core/spectrum.h"

#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace refracta {

enum class LightType {
  kDeltaPosition,   // point and spot lights
  kDeltaDirection,  // a direction without extent (none today; the sun has a disc)
  kArea,            // emissive geometry: found by rays, sampled by area or solid angle
  kInfinite,        // at infinity: sun disc, environment, sky: found by rays that escape
};

struct LightSampleContext {
  Vec3d p = Vec3d::Zero();   // the receiving point [m]
  Vec3d n = Vec3d::Zero();   // its geometric normal on the side of wo, or 0 off surfaces
};

struct LightLiSample {
  Spectrum L = Spectrum::Zero();  // radiance arriving at p along -wi (no occlusion, no air)
  Vec3d wi = Vec3d::UnitY();      // unit, from p toward the light
  double pdf = 0.0;               // per unit solid angle at p (delta lights: 1)
  Vec3d p_light = Vec3d::Zero();  // the point on a finite light (infinite lights: unused)
  double distance = std::numeric_limits<double>::infinity();  // |p_light - p|; infinite lights: inf
};

// A light. In Python its methods evaluate RGB rendering,
// vectorised over N points.
class Light {
 public:
  virtual ~Light() = default;
  virtual LightType type() const = 0;
  bool is_delta() const { return type() == LightType::kDeltaPosition || type() == LightType::kDeltaDirection; }
  bool is_infinite() const { return type() == LightType::kInfinite; }

  // A direction toward the light from ctx.p with its radiance and density; nullopt when the
  // light sends nothing there.
  virtual std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                                 const SampledWavelengths& lambda) const = 0;
  // The solid-angle density with which sample_li picks wi at ctx (0 for delta lights). Area
  // lights: the ray along wi hits the light at p_light with geometric normal n_light.
  virtual double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                        const Vec3d& n_light) const = 0;
  // Area lights: radiance leaving p_light (geometric normal n_light) toward w (unit, away).
  virtual Spectrum L(const Vec3d& /*p_light*/, const Vec3d& /*n_light*/, const Vec3d& /*w*/,
                     const SampledWavelengths& /*lambda*/) const {
    return Spectrum::Zero();
  }
  // Infinite lights: radiance seen looking along unit dir (the light arriving from far away in
  // direction dir).
  virtual Spectrum Le(const Vec3d& /*dir*/, const SampledWavelengths& /*lambda*/) const { return Spectrum::Zero(); }
  // Emitted power [W], as luminance (Y of the RGB power), for choosing among lights in proportion
  // to it. Infinite lights: the power through a disc of the scene's radius (after preprocess).
  virtual double power() const = 0;
  // Told the scene's bounding sphere before rendering (infinite lights need its radius).
  virtual void preprocess(const Vec3d& /*centre*/, double /*radius*/) {}
  virtual std::string describe() const = 0;
};

using LightPtr = std::shared_ptr<Light>;

}  // namespace refracta
