// The BSDF interface (pbrt-v4's BxDF): scattering in the local shading frame, z = shading
// normal. Conventions (shared/SHADING.md section 0): wo toward the viewer, wi toward the light,
// both unit and pointing away from the surface; f(wo, wi) excludes the cosine; sample() returns
// weight f |cos theta_i| / pdf; delta lobes have pdf() = 0 and sample() weight = the lobe's albedo.
// A BSDF lives in a ScratchBuffer for one path: trivially destructible, built per hit by a
// Material (shading/material.h) with its textures and wavelengths already resolved.
#pragma once

#include "refracta/core/frame.h"
#include "refracta/core/sampling.h"
#include "refracta/core/spectrum.h"

#include <optional>

namespace refracta {

enum BsdfFlags : unsigned {
  kBsdfReflection = 1u << 0,
  kBsdfTransmission = 1u << 1,
  kBsdfDiffuse = 1u << 2,
  kBsdfGlossy = 1u << 3,
  kBsdfSpecular = 1u << 4,  // a delta lobe
};

// Radiance (from the camera) or importance (from lights) transport: a refraction scales
// radiance by (eta_i / eta_t)^2 and importance not (pbrt-v4 TransportMode).
enum class TransportMode { kRadiance, kImportance };

struct BsdfSample {
  Vec3d wi = Vec3d::UnitZ();
  Spectrum weight = Spectrum::Zero();  // f |cos theta_i| / pdf (delta lobes: the lobe's albedo)
  Spectrum f = Spectrum::Zero();       // the BSDF value (delta lobes: weight * pdf / |cos|, informative only)
  double pdf = 0.0;                    // of wi, per unit solid angle (delta lobes: the lobe's probability)
  unsigned flags = 0;                  // the lobe sampled
  double eta = 1.0;                    // relative index eta_t / eta_i of a transmission (1 for reflection)

  bool is_specular() const { return flags & kBsdfSpecular; }
  bool is_transmission() const { return flags & kBsdfTransmission; }
};

inline double cos_theta(const Vec3d& w) { return w.z(); }
inline double abs_cos_theta(const Vec3d& w) { return std::abs(w.z()); }
inline bool same_hemisphere(const Vec3d& a, const Vec3d& b) { return a.z() * b.z() > 0.0; }

class Bsdf {
 public:
  virtual Spectrum f(const Vec3d& wo, const Vec3d& wi, TransportMode mode) const = 0;
  virtual double pdf(const Vec3d& wo, const Vec3d& wi, TransportMode mode) const = 0;
  // uc picks a lobe, u the direction within it.
  virtual std::optional<BsdfSample> sample(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const = 0;
  virtual unsigned flags() const = 0;
  bool has_delta_only() const { return (flags() & (kBsdfDiffuse | kBsdfGlossy)) == 0; }

 protected:
  ~Bsdf() = default;  // never deleted through the base: BSDFs live in a ScratchBuffer
};

// A BSDF placed at a surface point: the shading frame and the geometric normal, for world-space
// directions. Light leaking through the shading normal's approximation is cut by the geometric
// test (Veach 1997, ch. 5.3).
struct SurfaceBsdf {
  const Bsdf* bsdf = nullptr;
  Frame frame;          // n = shading normal
  Vec3d ng = Vec3d::UnitZ();  // geometric normal (any side)

  explicit operator bool() const { return bsdf != nullptr; }
  Spectrum f(const Vec3d& wo_world, const Vec3d& wi_world, TransportMode mode = TransportMode::kRadiance) const {
    const Vec3d wo = frame.to_local(wo_world), wi = frame.to_local(wi_world);
    if (wo.z() == 0.0) return Spectrum::Zero();
    return bsdf->f(wo, wi, mode);
  }
  double pdf(const Vec3d& wo_world, const Vec3d& wi_world, TransportMode mode = TransportMode::kRadiance) const {
    const Vec3d wo = frame.to_local(wo_world), wi = frame.to_local(wi_world);
    if (wo.z() == 0.0) return 0.0;
    return bsdf->pdf(wo, wi, mode);
  }
  // wi in world space.
  std::optional<BsdfSample> sample(const Vec3d& wo_world, double uc, const Vec2d& u,
                                   TransportMode mode = TransportMode::kRadiance) const {
    const Vec3d wo = frame.to_local(wo_world);
    if (wo.z() == 0.0) return std::nullopt;
    auto s = bsdf->sample(wo, uc, u, mode);
    if (!s || !(s->pdf > 0.0) || s->wi.z() == 0.0 || !(s->weight.maxCoeff() > 0.0)) return std::nullopt;
    s->wi = frame.from_local(s->wi);
    return s;
  }
};

}  // namespace refracta
