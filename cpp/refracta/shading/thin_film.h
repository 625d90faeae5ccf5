// Thin-film iridescence over a conductor or dielectric base (Belcour & Barla 2017, "A Practical
// Extension to Microfacet Theory for the Modeling of Varying Iridescence", SIGGRAPH): a film of
// index film_ior and thickness d [nm] on a base of complex index eta + i k, in an outside medium
// of index n1. The Fresnel term of a GGX reflection (or a smooth mirror, alpha = 0) becomes the
// exact Airy reflectance of the film, per polarisation (Born & Wolf 1.6.4):
//   r = (r12 + r23 e^{i delta}) / (1 + r12 r23 e^{i delta}),  delta = 4 pi n2 d cos theta_2 / lambda,
//   R = (|r_s|^2 + |r_p|^2) / 2,
// evaluated at the path's wavelengths in spectral rendering and, in RGB rendering, at one
// representative wavelength per channel (kRgbWavelengths: 630, 532, 465 nm; the paper's
// Fourier-space RGB integration is not implemented, so thick films alias in RGB). Reflection only:
// light transmitted into a dielectric base is absorbed (a coated opaque body). d = 0 or
// film_ior = n1 give the base's own Fresnel reflectance. Two-sided.
#pragma once

#include "refracta/shading/fresnel.h"
#include "refracta/shading/material_util.h"
#include "refracta/shading/microfacet.h"

#include <complex>
#include <utility>

namespace refracta {

constexpr double kRgbWavelengths[3] = {630.0, 532.0, 465.0};  // [nm]

// Airy reflectance of a film (n2 real, thickness [nm]) between n1 (real, outside) and a base n3
// (complex), light arriving at cos_1 from the outside, wavelength [nm].
inline double thin_film_reflectance(double cos_1, double n1, double n2, std::complex<double> n3, double thickness, double lambda_nm) {
  using C = std::complex<double>;
  cos_1 = std::clamp(std::abs(cos_1), 0.0, 1.0);
  const double sin2_1 = 1.0 - cos_1 * cos_1;
  const double sin2_2 = n1 * n1 * sin2_1 / (n2 * n2);
  if (sin2_2 >= 1.0) return 1.0;  // total internal reflection at the film's top
  const double cos_2 = std::sqrt(1.0 - sin2_2);
  const C n3cos3 = std::sqrt(n3 * n3 - n1 * n1 * sin2_1);  // Im >= 0: the wave decays into an absorbing base
  const double a1 = n1 * cos_1, a2 = n2 * cos_2;
  const double rs12 = (a1 - a2) / (a1 + a2), rp12 = (n2 * cos_1 - n1 * cos_2) / (n2 * cos_1 + n1 * cos_2);
  const C rs23 = (a2 - n3cos3) / (a2 + n3cos3);
  const C rp23 = (n3 * n3 * cos_2 - n2 * n3cos3) / (n3 * n3 * cos_2 + n2 * n3cos3);
  const C phase = std::exp(C(0.0, 4.0 * kPi * n2 * thickness * cos_2 / lambda_nm));
  const C rs = (rs12 + rs23 * phase) / (1.0 + rs12 * rs23 * phase);
  const C rp = (rp12 + rp23 * phase) / (1.0 + rp12 * rp23 * phase);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

// The same with its arguments checked (std::invalid_argument), for Python: n1, n2, eta and the
// wavelength > 0, k and thickness >= 0, the base's index eta + i k.
inline double checked_thin_film_reflectance(double cos_1, double n1, double n2, double eta, double k, double thickness,
                                            double lambda_nm) {
  Problems problems("thin_film_reflectance");
  problems.check(std::abs(cos_1) <= 1.0, "cos_i must be in [-1, 1] (got ", cos_1, ")");
  for (const auto& [name, value] :
       {std::pair{"n1", n1}, std::pair{"n2", n2}, std::pair{"eta", eta}, std::pair{"wavelength", lambda_nm}}) {
    problems.check(value > 0.0 && std::isfinite(value), name, " must be > 0 and finite (got ", value, ")");
  }
  for (const auto& [name, value] : {std::pair{"k", k}, std::pair{"thickness", thickness}}) {
    problems.check(value >= 0.0 && std::isfinite(value), name, " must be >= 0 and finite (got ", value, ")");
  }
  problems.throw_if_any();
  return thin_film_reflectance(cos_1, n1, n2, {eta, k}, thickness, lambda_nm);
}

struct ThinFilmFresnel {
  double n1 = 1.0, n2 = 1.33, thickness = 500.0;
  Spectrum eta = Spectrum::Constant(1.5), k = Spectrum::Zero(), lambda = Spectrum::Zero();
  int channels = 3;
  Spectrum operator()(double cos_i) const {
    Spectrum out = Spectrum::Zero();
    for (int i = 0; i < channels; ++i) out[i] = thin_film_reflectance(cos_i, n1, n2, {eta[i], k[i]}, thickness, lambda[i]);
    return out;
  }
};

class ThinFilmBsdf final : public TwoSidedReflection<ThinFilmBsdf> {
 public:
  ThinFilmBsdf(const ThinFilmFresnel& fresnel, double alpha_x, double alpha_y)
      : fresnel_(fresnel), smooth_(alpha_x == 0.0), distribution_(smooth_ ? 1.0 : alpha_x, smooth_ ? 1.0 : alpha_y) {}
  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    if (smooth_ || !(wi.z() > 0.0)) return Spectrum::Zero();
    const Vec3d h = (wo + wi).normalized();
    return fresnel_(wo.dot(h)) * (distribution_.D(h) * distribution_.G(wo, wi) / (4.0 * wo.z() * wi.z()));
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    if (smooth_ || !(wi.z() > 0.0)) return 0.0;
    const Vec3d h = (wo + wi).normalized();
    return distribution_.D_visible(wo, h) / (4.0 * std::abs(wo.dot(h)));
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double, const Vec2d& u, TransportMode mode) const {
    BsdfSample s;
    if (smooth_) {
      s.wi = Vec3d(-wo.x(), -wo.y(), wo.z());
      s.weight = fresnel_(wo.z());
      s.f = s.weight / wo.z();
      s.pdf = 1.0;
      s.flags = kBsdfReflection | kBsdfSpecular;
      return s;
    }
    s.wi = reflect(wo, distribution_.sample_wm(wo, u));
    if (!(s.wi.z() > 0.0)) return std::nullopt;
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    s.flags = kBsdfReflection | kBsdfGlossy;
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | (smooth_ ? kBsdfSpecular : kBsdfGlossy); }

 private:
  ThinFilmFresnel fresnel_;
  bool smooth_;
  TrowbridgeReitz distribution_;
};

// Thin-film iridescence (Belcour & Barla 2017): a film of thickness [nm] and index film_ior on a
// base of complex index eta + i k, with GGX roughness alpha (or alpha_u, alpha_v; 0 = smooth
// mirror). The Fresnel term is the film's exact Airy reflectance (RGB: at 630, 532, 465 nm).
// Reflection only.
class ThinFilm final : public Material {
 public:
  // Python's defaults: a soap film (water's index) on glass, slightly rough.
  static constexpr double kDefaultFilmIor = 1.33, kDefaultEta = 1.5, kDefaultK = 0.0, kDefaultAlpha = 0.1;
  // thickness [nm] >= 0, film_ior > 0; base eta (> 0) and k (>= 0) per channel; alpha 0 = smooth.
  ThinFilm(double thickness, double film_ior, const Vec3d& eta, const Vec3d& k, double alpha_u, double alpha_v)
      : thickness_(checked_scalar(thickness, "thickness", 0.0, 1e6)), film_ior_(film_ior), eta_rgb_(eta), k_rgb_(k),
        eta_(checked_unbounded(eta, "eta", true)), k_(checked_unbounded(k, "k", false)) {
    if (!std::isfinite(film_ior) || film_ior <= 0.0) throw_invalid("film_ior must be finite and > 0 (got ", film_ior, ")");
    alpha_u_ = alpha_u == 0.0 ? 0.0 : TrowbridgeReitz::checked_alpha(alpha_u, "alpha_u");
    alpha_v_ = alpha_v == 0.0 ? 0.0 : TrowbridgeReitz::checked_alpha(alpha_v, "alpha_v");
    if ((alpha_u_ == 0.0) != (alpha_v_ == 0.0)) throw_invalid("alpha_u and alpha_v must both be 0 (smooth) or both > 0 (got ", alpha_u, ", ", alpha_v, ")");
  }
  const Bsdf* bsdf(const SurfaceInteraction&, const MaterialContext& context, ScratchBuffer& scratch) const override {
    ThinFilmFresnel f;
    f.n1 = context.eta_outside;
    f.n2 = film_ior_;
    f.thickness = thickness_;
    f.eta = eta_.sample(*context.lambda);
    f.k = k_.sample(*context.lambda);
    if (context.lambda->spectral) {
      f.lambda = context.lambda->lambda;
      f.channels = 4;
    } else {
      f.lambda = Spectrum(kRgbWavelengths[0], kRgbWavelengths[1], kRgbWavelengths[2], 550.0);
      f.channels = 3;
    }
    return scratch.make<ThinFilmBsdf>(f, alpha_u_, alpha_v_);
  }
  std::string describe() const override {
    return concat("ThinFilm(thickness=", thickness_, ", film_ior=", film_ior_, ", eta=", describe_rgb(eta_rgb_), ", k=",
                  describe_rgb(k_rgb_), ", alpha_u=", alpha_u_, ", alpha_v=", alpha_v_, ")");
  }
  double thickness() const { return thickness_; }
  double film_ior() const { return film_ior_; }
  const Vec3d& eta() const { return eta_rgb_; }
  const Vec3d& k() const { return k_rgb_; }
  double alpha_u() const { return alpha_u_; }
  double alpha_v() const { return alpha_v_; }

 private:
  double thickness_, film_ior_;
  Vec3d eta_rgb_, k_rgb_;
  Color eta_, k_;
  double alpha_u_ = 0.0, alpha_v_ = 0.0;
};

}  // namespace refracta
