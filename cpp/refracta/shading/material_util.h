// Small helpers shared by the materials of the BSDF library: validated colours with the
// parameter's name in the message, texture resolution at a hit, channel averages for lobe
// selection, and the mirror that makes reflection-only BSDFs two-sided.
#pragma once

#include "refracta/core/error.h"
#include "refracta/shading/color.h"
#include "refracta/shading/material.h"

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>

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

// A microfacet roughness given as alpha or as (alpha_u, alpha_v): exactly one form; neither:
// (fallback, fallback) unless `required`. The materials check the values themselves.
inline std::pair<double, double> alphas_from(std::optional<double> alpha, std::optional<double> alpha_u,
                                             std::optional<double> alpha_v, bool required, double fallback) {
  if (alpha && (alpha_u || alpha_v)) throw_invalid("give either alpha or alpha_u and alpha_v, not both");
  if (alpha_u || alpha_v) {
    if (!alpha_u || !alpha_v) throw_invalid("alpha_u and alpha_v must be given together");
    return {*alpha_u, *alpha_v};
  }
  if (!alpha && required) throw_invalid("alpha (or alpha_u and alpha_v) is required");
  return alpha ? std::make_pair(*alpha, *alpha) : std::make_pair(fallback, fallback);
}

inline double checked_scalar(double value, const char* name, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) throw_invalid(name, " must be in [", lo, ", ", hi, "] (got ", value, ")");
  return value;
}

// A reflectance colour in [0, 1], optionally multiplied by an image texture: the one textured
// reflectance of the materials (Diffuse, BlinnPhong's kd, Plastic, Principled's base colour). The
// texture is either a file path, registered in a scene's texture table when the material is added
// to the scene (bound_to, through Material::with_textures), or an id of that table as add_mesh's
// texture= shorthand and OBJ map_Kd make it. Texels are linear RGB clamped to [0, 1].
class TexturedReflectance {
 public:
  TexturedReflectance(const Vec3d& rgb, const char* name, int texture = -1, std::string path = {})
      : rgb_(rgb), color_(checked_reflectance(rgb, name)), texture_(texture), path_(std::move(path)) {}

  // The colour's spectrum times the texel's (upsampled as a reflectance), when a texture is bound
  // and the context has a texture table (Material.f/pdf/sample evaluate without one: the colour).
  Spectrum at(const SurfaceInteraction& si, const MaterialContext& context) const {
    Spectrum value = color_.sample(*context.lambda);
    if (const auto texel = texel_at(si, context)) value *= reflectance_spectrum(*texel, *context.lambda);
    return value;
  }
  // Linear RGB at a hit: the colour times the texel.
  Vec3d rgb_at(const SurfaceInteraction& si, const MaterialContext& context) const {
    const auto texel = texel_at(si, context);
    return texel ? Vec3d(rgb_.cwiseProduct(*texel)) : rgb_;
  }
  // This reflectance with its texture file registered in `textures` (the file's id there).
  TexturedReflectance bound_to(Textures& textures) const {
    TexturedReflectance bound = *this;
    bound.texture_ = textures.add(path_);
    return bound;
  }
  const Vec3d& rgb() const { return rgb_; }
  int texture() const { return texture_; }           // -1: none bound
  const std::string& path() const { return path_; }  // "": given by id (or none)
  bool textured() const { return texture_ >= 0 || !path_.empty(); }
  // ", texture='albedo.png'", ", texture=3" or "" for describe().
  std::string describe_texture() const {
    if (!path_.empty()) return concat(", texture='", path_, "'");
    return texture_ >= 0 ? concat(", texture=", texture_) : std::string();
  }

 private:
  std::optional<Vec3d> texel_at(const SurfaceInteraction& si, const MaterialContext& context) const {
    if (texture_ < 0 || !context.textures) return std::nullopt;
    return context.textures->lookup(texture_, si.texture).cwiseMin(1.0).cwiseMax(0.0);
  }

  Vec3d rgb_;
  Color color_;
  int texture_;
  std::string path_;
};

// Material::with_textures of a material whose `member` is its textured reflectance: a copy with
// the texture file bound to `textures`, or null when the texture is not a file (an id must be one
// of `textures`': ValueError when the material is added, not an index error in the render).
template <class M>
std::shared_ptr<const Material> with_bound_texture(const M& material, TexturedReflectance M::*member, Textures& textures) {
  if ((material.*member).path().empty()) {
    const int id = (material.*member).texture();
    if (id >= 0 && size_t(id) >= textures.size()) {
      throw_invalid("texture id ", id, " is not one of this scene's textures (it has ", textures.size(),
                    "): give the texture's file path instead");
    }
    return nullptr;
  }
  auto copy = std::make_shared<M>(material);
  copy.get()->*member = (material.*member).bound_to(textures);
  return copy;
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
