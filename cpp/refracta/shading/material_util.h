// Small helpers shared by the materials of the BSDF library: validated colours with the
// parameter's name in the message, texture resolution at a hit, channel averages for lobe
// selection, and the mirror that makes reflection-only BSDFs two-sided.
#pragma once

#include "refracta/core/error.h"
#include "refracta/shading/color.h"
#include "refracta/shading/material.h"

#include <cmath>
#include <string>

namespace refracta {

// A reflectance in [0, 1] per channel; > 1 is refused because it creates energy.
inline Color checked_reflectance(const Vec3d& rgb, const char* name) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0 || rgb[i] > 1.0) {
      throw_invalid(name, " must be in [0, 1] per channel (got (", rgb.x(), ", ", rgb.y(), ", ", rgb.z(), "))");
    }
  }
  return Color::reflectance(rgb);
}

// A non-negative colour without upper bound (eta, k); `positive` refuses 0 too.
inline Color checked_unbounded(const Vec3d& rgb, const char* name, bool positive) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(rgb[i]) || rgb[i] < 0.0 || (positive && rgb[i] == 0.0)) {
      throw_invalid(name, positive ? " must be finite and > 0" : " must be finite and >= 0", " per channel (got (", rgb.x(),
                    ", ", rgb.y(), ", ", rgb.z(), "))");
    }
  }
  return Color::unbounded(rgb);
}

inline double checked_scalar(double value, const char* name, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) throw_invalid(name, " must be in [", lo, ", ", hi, "] (got ", value, ")");
  return value;
}

// A reflectance colour at a hit: the colour's spectrum times the texture's (linear RGB, upsampled
// as a reflectance) when a texture id is set and the context has a texture table.
inline Spectrum resolve_reflectance(const Color& color, int texture, const SurfaceInteraction& si, const MaterialContext& context) {
  Spectrum value = color.sample(*context.lambda);
  if (texture >= 0 && context.textures) {
    value *= reflectance_spectrum(context.textures->lookup(texture, si.texture).cwiseMin(1.0).cwiseMax(0.0), *context.lambda);
  }
  return value;
}

// The mean over the channels a path carries (RGB: r, g, b; spectral: the four wavelengths).
inline double channel_mean(const Spectrum& s, const SampledWavelengths& lambda) {
  return lambda.spectral ? s.mean() : s.head<3>().mean();
}

inline Vec3d mirror_z(const Vec3d& w) { return Vec3d(w.x(), w.y(), -w.z()); }

inline std::string describe_rgb(const Vec3d& rgb) { return concat("(", rgb.x(), ", ", rgb.y(), ", ", rgb.z(), ")"); }

// A reflection-only BSDF written for wo.z > 0 made two-sided: wo below the surface mirrors both
// directions (an opaque surface looks the same from either side of its shading normal).
template <class Derived>
class TwoSidedReflection : public Bsdf {
 public:
  Spectrum f(const Vec3d& wo, const Vec3d& wi, TransportMode mode) const override {
    if (!same_hemisphere(wo, wi)) return Spectrum::Zero();
    return wo.z() > 0.0 ? self().f_up(wo, wi, mode) : self().f_up(mirror_z(wo), mirror_z(wi), mode);
  }
  double pdf(const Vec3d& wo, const Vec3d& wi, TransportMode mode) const override {
    if (!same_hemisphere(wo, wi)) return 0.0;
    return wo.z() > 0.0 ? self().pdf_up(wo, wi, mode) : self().pdf_up(mirror_z(wo), mirror_z(wi), mode);
  }
  std::optional<BsdfSample> sample(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const override {
    if (wo.z() == 0.0) return std::nullopt;
    const bool flip = wo.z() < 0.0;
    auto s = self().sample_up(flip ? mirror_z(wo) : wo, uc, u, mode);
    if (!s || !(s->wi.z() > 0.0) || !(s->pdf > 0.0)) return std::nullopt;
    if (flip) s->wi = mirror_z(s->wi);
    return s;
  }

 protected:
  ~TwoSidedReflection() = default;

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace refracta
