// The sea (or a lake): a wind-roughened water surface over a deep water body (shared/SHADING.md;
// issue 19 section 2). Used through `shading.Water(...)`; built from the water optics of water.h.
//
// The interface. The sea surface's slopes are Gaussian with the total mean-square slope of Cox &
// Munk 1954, sigma^2 = 0.003 + 5.12e-3 U (U [m/s] the wind 12.5 m above the sea; water.h), so
// the interface is a Beckmann microfacet dielectric (beckmann.h) with alpha^2 = sigma^2 (alpha = 0.055
// in a calm, 0.17 at 5 m/s, 0.23 at 10 m/s) — less the slopes a displaced wave mesh already
// resolves (resolved_slope_variance; Scene.add_sea and scene/ocean_waves.h), in pbrt-v4's DielectricBxDF / Mitsuba 3's
// roughdielectric form (Walter et al. 2007, eqs. 20-21; the formulas of dielectric.h's
// RoughDielectricLobe, shared with RoughDielectric's GGX):
//   reflection     f_r = D(h) G(wo, wi) F(wo.h) / (4 |cos_o cos_i|),
//   transmission   f_t = D(m) G (1 - F(wo.m)) |wi.m| |wo.m| / (|cos_i cos_o| (wi.m + wo.m / eta')^2) / eta'^2,
// with the index of water_ior(lambda, temperature_c, salinity) over the outside medium's.
//
// The index per channel. Spectral rendering: each of the path's four wavelengths gets its own
// index in every lobe's value, while the direction is sampled with the hero's (its pdf); Beckmann's
// D > 0 everywhere, so the hero's density covers each wavelength's lobe except in slivers at the
// edge of total internal reflection where every lobe's value goes to 0. Water's dispersion is
// small beside its roughness (n = 1.343 at 400 nm, 1.331 at 700 nm: the refracted ray turns by
// 0.5 degrees, the lobe is 5-13 degrees wide), so the wavelengths are kept (no hero-only
// termination as for dispersive glass). RGB rendering likewise per channel, the index at 630,
// 532 and 465 nm (thin_film.h's kRgbWavelengths), the direction sampled with the index at
// Ior::kRgbWavelength (550 nm), which is also interior_ior().
//
// The water body (body = true, the default): light refracted into the water is either absorbed
// or scattered back up by the water itself, which is optically deep. Its irradiance reflectance
// just beneath the surface, R(lambda) = 0.33 b_b / (a + b_b) (water.h: Morel & Prieur 1977 with
// Gordon et al. 1975's X; pure-water absorption of Pope & Fry 1997, backscatter of Morel 1974),
// is returned as isotropic radiance (Q = pi) and leaves through the same rough interface, some of
// it reflected back down again (summed as a series, Weidlich & Wilkie 2007's layer; refracta's
// Plastic with the water body as its base):
//   f_body = T(cos_i) T(cos_o) R / (pi eta^2 (1 - R Fbar_int)),
//   Fbar_int = 1 - 2 int_0^1 T(mu) mu dmu / eta^2,
// T(mu) the rough interface's directional transmittance from above (RoughTransmittance: the
// integral of its transmission lobe, importance transport, tabulated per alpha over mu and eta;
// the flat interface's 1 - F(mu) when alpha -> 0). Light from wi crossing into the water is
// T(cos_i) of it; upwelling radiance L leaves toward wo as L T(cos_o) / eta^2 (the eta^2 law of
// transmission); light from below that does not cross is taken as reflected back down (the
// interface's masking loss from below, < 1 %, is kept in the water). Reciprocal, and the albedo
// rho_r(wi) + T(cos_i) R (1 - Fbar_int) / (1 - R Fbar_int) <= rho_r(wi) + T(cos_i) <= 1: energy is
// conserved because the rough dielectric's own reflection plus transmission is (tested: white
// furnace). Nothing continues below the surface: the material is reflection-only, two-sided, and
// bounds no medium (interior_ior() is None). Left out: the water's temperature and salinity in
// absorption, chlorophyll and dissolved matter (real seas are greener and darker than pure
// water), the angular shape of the upwelling light, foam, and the light of the sea floor.
//
// body = false: the bare interface, reflecting and transmitting (a pool, water over a floor, or
// under water): a rough dielectric that bounds a medium of the water's index (nested dielectrics,
// priority) without absorption in it.
#pragma once

#include "refracta/shading/beckmann.h"
#include "refracta/shading/color.h"
#include "refracta/shading/fresnel.h"
#include "refracta/shading/ior.h"
#include "refracta/shading/material_util.h"
#include "refracta/shading/rough_dielectric.h"

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// The directional transmittance T(mu, eta) = int f_t(wo, wi) |cos theta_i| dwi of the Beckmann
// interface of one alpha, light arriving from above at cos theta_o = mu (importance transport: the
// fraction of the energy that crosses), eta the relative index. Tabulated over kMu mu nodes, uniform
// in sqrt(mu) (T changes fastest near grazing, within mu ~ alpha / 10, where masking lets go; at
// mu = 0 it keeps its grazing limit, 0.25 on a calm sea: the visible normals tilt toward the light),
// by eta nodes, each a 64 x 64 midpoint quadrature over the visible-normal proposal's unit square,
// bilinear between nodes. Water against air over 360-830 nm, 0-40 C, 0-40 g/kg lies in 1.32-1.36:
// kNear's 5 nodes over [1.31, 1.37], built at construction. Another medium outside (Water under
// glass or oil: eta_outside) takes kWide's 31 nodes over [0.5, 2], built the first time one is
// asked for (0.7 s; a relative index beyond 0.89 is total internal reflection near grazing, which
// kNear clamped to light: a trial); beyond [0.5, 2] clamped. Shared by the materials of one alpha.
class RoughTransmittance {
 public:
  static constexpr int kMu = 33;
  explicit RoughTransmittance(const Beckmann& distribution);
  // The table of Beckmann(alpha), computed once per alpha and kept (a few kB each).
  static std::shared_ptr<const RoughTransmittance> for_alpha(double alpha);
  double operator()(double mu, double eta) const;
  // 2 int_0^1 T(mu, eta) mu dmu: the share of diffuse light from above that crosses.
  double hemispherical(double eta) const;

 private:
  // T over kMu x nodes nodes of eta in [lo, hi].
  struct EtaTable {
    double lo = 0.0, hi = 0.0;
    int nodes = 0;
    std::vector<double> t, hemispherical;
    EtaTable() = default;
    EtaTable(const Beckmann& distribution, double lo, double hi, int nodes);
    double node(double eta, int* k) const;  // the lower node and the weight of the upper one
    bool covers(double eta) const { return eta >= lo && eta <= hi; }
  };
  static constexpr double kNearLo = 1.31, kNearHi = 1.37, kWideLo = 0.5, kWideHi = 2.0;
  static constexpr int kNearNodes = 5, kWideNodes = 31;
  static double mu_node(int j) { return double(j * j) / double((kMu - 1) * (kMu - 1)); }
  const EtaTable& table_for(double eta) const;

  Beckmann distribution_;
  EtaTable near_;
  mutable std::once_flag wide_built_;
  mutable EtaTable wide_;
};

// The deep-water surface seen from above (two-sided by mirroring): Beckmann reflection plus the
// water body's upwelling light. Values per channel (indices eta, body reflectance r, internal
// diffuse reflectance fdr_int of the rough interface); sampling with eta_sampling.
class WaterBodyBsdf final : public TwoSidedReflection<WaterBodyBsdf> {
 public:
  WaterBodyBsdf(const Spectrum& eta, double eta_sampling, const Beckmann& distribution, const RoughTransmittance& transmittance,
                const Spectrum& r, const Spectrum& fdr_internal, double body_albedo)
      : eta_(eta), eta_sampling_(eta_sampling), distribution_(distribution), transmittance_(&transmittance), r_(r),
        fdr_internal_(fdr_internal), body_albedo_(body_albedo) {}

  Spectrum f_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    Spectrum f = body(wo, wi);
    const Vec3d h = (wo + wi).normalized();
    const double base = distribution_.D(h) * distribution_.G(wo, wi) / (4.0 * wo.z() * wi.z());
    for (int c = 0; c < kSpectrumSamples; ++c) f[c] += base * fresnel_dielectric(wo.dot(h), eta_[c]);
    return f;
  }
  double pdf_up(const Vec3d& wo, const Vec3d& wi, TransportMode) const {
    const double p = specular_probability(wo);
    const Vec3d h = (wo + wi).normalized();
    return (1.0 - p) * cosine_hemisphere_pdf(wi.z()) + p * distribution_.sampling_pdf(wo, h) / (4.0 * std::abs(wo.dot(h)));
  }
  std::optional<BsdfSample> sample_up(const Vec3d& wo, double uc, const Vec2d& u, TransportMode mode) const {
    const bool specular = uc < specular_probability(wo);
    BsdfSample s;
    if (specular) {
      const auto m = distribution_.sample_wm(wo, u);
      if (!m) return std::nullopt;
      s.wi = reflect(wo, *m);
    } else {
      s.wi = sample_cosine_hemisphere(u);
    }
    if (!(s.wi.z() > 0.0)) return std::nullopt;
    s.pdf = pdf_up(wo, s.wi, mode);
    if (!(s.pdf > 0.0)) return std::nullopt;
    s.f = f_up(wo, s.wi, mode);
    s.weight = s.f * s.wi.z() / s.pdf;
    s.flags = kBsdfReflection | (specular ? kBsdfGlossy : kBsdfDiffuse);
    return s;
  }
  unsigned flags() const override { return kBsdfReflection | kBsdfGlossy | kBsdfDiffuse; }

 private:
  Spectrum body(const Vec3d& wo, const Vec3d& wi) const {
    Spectrum f;
    for (int c = 0; c < kSpectrumSamples; ++c) {
      const double t = (*transmittance_)(wi.z(), eta_[c]) * (*transmittance_)(wo.z(), eta_[c]);
      f[c] = t * r_[c] / (kPi * eta_[c] * eta_[c] * (1.0 - r_[c] * fdr_internal_[c]));
    }
    return f;
  }
  // The glossy lobe in proportion to its albedo (~F(wo)) against the body's, each kept at least
  // kMinLobeProbability so that neither lobe's support goes unsampled.
  double specular_probability(const Vec3d& wo) const {
    constexpr double kMinLobeProbability = 0.05;
    const double F = fresnel_dielectric(wo.z(), eta_sampling_);
    const double body = (1.0 - F) * body_albedo_;
    return std::clamp(F / (F + body), kMinLobeProbability, 1.0 - kMinLobeProbability);
  }
  Spectrum eta_;
  double eta_sampling_;
  Beckmann distribution_;
  const RoughTransmittance* transmittance_;  // the material's
  Spectrum r_, fdr_internal_;
  double body_albedo_;  // channel mean of R (1 - Fbar_int) / (1 - R Fbar_int): the body's albedo over T(cos_o)
};

// The bare interface (body = false): a Beckmann rough dielectric, values per channel.
using WaterInterfaceBsdf = RoughDielectricLobe<Beckmann>;

// The constructor's arguments, with their defaults (bound as the Python defaults).
struct WaterParameters {
  double wind_speed = 5.0;      // [m/s] 12.5 m above the sea: a gentle breeze (Beaufort 3); the ocean's mean is ~7
  double temperature_c = 20.0;  // [deg C] a temperate sea's surface
  double salinity = 35.0;       // [g/kg] the open ocean's mean
  bool body = true;             // a deep water body under the surface (false: the bare interface)
  int priority = 0;             // nested dielectrics (body = false only)
  // [-] the mean-square slope a displaced mesh under this material already shows (Scene.add_sea:
  // the Tessendorf waves it resolves); the microfacets keep the rest, alpha^2 = sigma^2 - this, so
  // that resolved + unresolved = Cox & Munk's total. In [0, sigma^2 - kMinUnresolvedSlopeVariance].
  double resolved_slope_variance = 0.0;
};

// The sea: a wind-roughened water surface over a deep water body (water_surface.h).
//
// The interface is a Beckmann microfacet dielectric (Walter et al. 2007; Mitsuba 3's roughdielectric
// with distribution='beckmann') whose alpha^2 is Cox & Munk 1954's total mean-square slope
// 0.003 + 5.12e-3 wind_speed (alpha = 0.17 at 5 m/s) and whose index is water_ior(lambda,
// temperature_c, salinity): per wavelength in spectral rendering, at 630, 532 and 465 nm per RGB
// channel (directions sampled at 550 nm). body=True (default): the deep water under it absorbs
// (Pope & Fry 1997) and backscatters (Morel 1974) the light refracted in and returns
// R = 0.33 b_b / (a + b_b) of it as isotropic light leaving through the rough interface,
// T(cos_i) T(cos_o) R / (pi eta^2 (1 - R Fbar_int)) (T = transmittance(mu), Fbar_int =
// internal_reflectance()); reflection-only and two-sided, nothing continues below. body=False: the
// bare interface, reflecting and transmitting, bounding a medium of the water's index (priority
// for nested dielectrics).
// Defaults: wind_speed 5 m/s (a gentle breeze), temperature_c 20 deg C, salinity 35 g/kg (the open
// ocean). resolved_slope_variance: the mean-square slope a displaced wave mesh under it already
// resolves (Scene.add_sea sets it): alpha^2 = Cox-Munk's total - it, so that resolved + unresolved
// = total. wind_speed in [0, 30] m/s, temperature_c in [-2, 40] (a cold sea at its freezing point), salinity in [0, 40] g/kg.
class Water final : public Material {
 public:
  // Validates every parameter (std::invalid_argument naming it) and tabulates the index and the
  // body reflectance over 360-830 nm and the rough interface's transmittance.
  explicit Water(const WaterParameters& parameters = {});

  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override;
  std::optional<double> interior_ior(const SampledWavelengths& lambda) const override;
  int priority() const override { return parameters_.priority; }
  bool transmits() const override { return true; }
  std::string describe() const override;

  const WaterParameters& parameters() const { return parameters_; }
  // The microfacets keep at least this mean-square slope (alpha >= 0.01): a Beckmann lobe narrower
  // than that is a mirror in all but cost, and a mesh resolving all of Cox-Munk's slope is a
  // setting error (a grid finer than the capillary waves), not a sea.
  static constexpr double kMinUnresolvedSlopeVariance = 1e-4;
  double mean_square_slope() const { return mean_square_slope_; }  // Cox-Munk's total sigma^2
  // The Beckmann roughness alpha = sqrt(sigma^2 - resolved_slope_variance). (Not Material::alpha,
  // the raster's opacity: overriding that made every sea 60-83 % transparent in render_raster.)
  double roughness() const { return alpha_; }
  // The water's index relative to vacuum at a wavelength [nm] in [kLambdaMin, kLambdaMax] (from the table).
  double ior(double wavelength_nm) const { return interpolate(ior_table_, wavelength_nm); }
  const RoughTransmittance& transmittance() const { return *transmittance_; }
  // The rough interface's directional transmittance T(mu) from above (the share of the energy
  // arriving at cos theta = mu that crosses into the water), as the water body's term uses it, at
  // the water's index at wavelength_nm under vacuum, mu in [-1, 1] (std::invalid_argument naming
  // them otherwise). Tabulated (33 mu x 5 eta nodes).
  double transmittance(double mu, double wavelength_nm) const;
  // Fbar_int = 1 - 2 int T(mu) mu dmu / eta^2: what of isotropic light under the rough surface is
  // sent back down, at wavelength_nm (the flat surface's fresnel_diffuse_reflectance(1 / eta) when
  // alpha -> 0).
  double internal_reflectance(double wavelength_nm) const;

 private:
  static double interpolate(const std::vector<double>& table, double wavelength_nm);
  WaterParameters parameters_;
  double mean_square_slope_;
  double alpha_;
  std::vector<double> ior_table_;  // every 1 nm from kLambdaMin
  Color body_reflectance_;         // R(lambda) of water.h
  Vec3d ior_rgb_;                  // at kRgbWavelengths
  double ior_sampling_rgb_;        // at Ior::kRgbWavelength
  std::shared_ptr<const RoughTransmittance> transmittance_;
};

}  // namespace refracta
