// A physical sky (shared/SHADING.md section 5): single scattering of sunlight through a spherical
// standard atmosphere (Nishita et al. 1993, "Display of the Earth Taking into Account Atmospheric
// Scattering", SIGGRAPH) plus the higher orders by the isotropic multiple-scattering table of
// Hillaire 2020 (multiple_scattering.h), spectral, and the sun's colour by extinction. PhysicalSkyLight makes it
// an infinite light (light.h); the sun disc itself is a separate light (sun_light.h), fed by
// PhysicalSky::sun_radiance / sun_radiance_rgb.
//
// The atmosphere (y up; the observer at height `altitude` above a sphere of radius 6371 km, the
// atmosphere's top 80 km up):
// - Rayleigh: beta_R(lambda) = beta_R(550) (550/lambda)^4, density e^(-h/8 km). beta_R(550) is
//   derived from Bodhaine et al. 1999 ("On Rayleigh Optical Depth Calculations", J. Atmos.
//   Oceanic Technol. 16): tau_R(550 nm) = 0.097 at sea level, so beta_R(550) = 0.097 / (8000 m
//   (1 - e^(-80/8))) = 1.2126e-5 /m (the lambda^-4 law, as asked, against Bodhaine's lambda^-4.08).
// - Mie (aerosols): scattering 2.1e-5 /m at sea level, extinction = scattering / 0.9, density
//   e^(-h/1.2 km) (Bruneton & Neyret 2008, "Precomputed Atmospheric Scattering", EGSR), times
//   `aerosol` (1: a clear sky, aerosol optical depth 0.028 at every wavelength; 0: none);
//   Cornette-Shanks phase with g = 0.76.
// - Ozone: absorption only, number density a tent from 10 km up to its peak at 25 km and down to
//   40 km, scaled to a column of `ozone_du` Dobson units (2.687e20 molecules/m^2 each; 300 DU
//   typical); cross-sections at 10 nm steps over [360, 830] nm: Serdyuchenko et al. 2014 / Gorshelev
//   et al. 2014 (IUP Bremen O3 reference spectra, 233 K), as binned in E. Bruneton's 2017
//   "precomputed_atmospheric_scattering" demo (a 48-value data table, cited in physical_sky.cpp).
// - The sun: extraterrestrial spectral irradiance of a 5778 K black body scaled to the solar
//   constant 1361 W/m^2 (Kopp & Lean 2011): E(lambda) = pi B(lambda, 5778 K) 1361 / (sigma 5778^4).
//
// Radiance [W/(m^2 sr nm)] of the sky looking along dir (unit, world, y up): the scattered sunlight
// along the view ray to the top of the atmosphere -- single scattering, and with
// multiple_scattering sigma_s Psi_ms E per unit length for the higher orders -- each step's
// attenuation integrated for constant air within it (exact however thick the haze), the direct sun
// excluded. Below the
// horizon (dir.y < 0), by PhysicalSkySettings::below_horizon:
// - kGround: the ground's Lambertian radiance albedo/pi E T_sun(observer) max(0, sun.y), without
//   the air between the observer and the ground (exact at altitude 0; 0 with albedo 0);
// - kHorizon: the sky continued from the horizon, L(azimuth, e < 0) = L(azimuth, 0) (Scene.set_sky's
//   convention; for scenes whose ground is geometry: a ray that ends its max_length still heading
//   slightly down would meet that ground at a grazing angle and see the horizon sky there).
// Tabulated on construction: 48 wavelengths (360..830 nm, 10 nm), elevation e = (pi/2) v^2 on 64
// rows (finer near the horizon) x 128 azimuths, in parallel over oneTBB.
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/sampling.h"
#include "refracta/shading/light.h"
#include "refracta/shading/multiple_scattering.h"

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// What the sky shows below the horizon (see above).
enum class BelowHorizon { kGround, kHorizon };

// "ground" or "horizon" (the Python names); anything else throws std::invalid_argument.
BelowHorizon below_horizon_from(const std::string& name);

// The highest observer altitude [m] the sky model takes (PhysicalSkySettings::altitude).
constexpr double kPhysicalSkyHighestAltitude = 20000.0;
// The most ozone [Dobson units] a sky takes (the Earth's column is 100-600 DU).
constexpr double kMostOzone = 10000.0;
// The least meteorological visibility [km] an air may have (1 m: the densest fog is ~10 m).
constexpr double kLeastVisibility = 1e-3;

struct PhysicalSkySettings {
  Vec3d sun_direction = Vec3d(0.0, 1.0, 0.0);  // unit, toward the sun, y up
  double aerosol = 1.0;        // Mie density scale >= 0 (1: clear, 0: none; ~3-5: hazy)
  double ozone_du = 300.0;     // ozone column [Dobson units] >= 0 (0: none)
  double ground_albedo = 0.0;  // in [0, 1]: the ground seen below the horizon (kGround; 0 with kHorizon)
  double altitude = 0.0;       // the observer's height [m] in [0, kPhysicalSkyHighestAltitude]
  double rayleigh_scale = 1.0; // Rayleigh density scale >= 0 (tests: 0 isolates the other terms)
  BelowHorizon below_horizon = BelowHorizon::kGround;
  // Add the higher orders of scattering (multiple_scattering.h, Hillaire 2020) to the single
  // scattering: on, because haze and fog are bright in photographs (single scattering alone leaves
  // a 1 km-visibility horizon at ~1e-4 of the clear sky's); off for the single-scattering sky alone.
  bool multiple_scattering = true;
  void validate() const;       // throws std::invalid_argument listing every problem
};

// The aerosol scale that gives meteorological visibility `visibility_km` at the ground (the
// scene's y = 0, `altitude` up): Koschmieder's law, total extinction at 550 nm = 3.912 / V (a black
// object's contrast against the horizon sky falls to 2 % at V), from the Rayleigh and ozone
// extinction of `settings` there and the Mie rest. Throws std::invalid_argument for V <= 0, NaN, or
// a V the air's molecules alone already limit (Rayleigh: ~320 km at sea level).
double aerosol_for_visibility(double visibility_km, const PhysicalSkySettings& settings);
// settings->aerosol from a visibility [km] (aerosol_for_visibility); throws std::invalid_argument
// when the aerosol was also set (differs from its default): one or the other.
void set_visibility(PhysicalSkySettings* settings, double visibility_km);
// Below this visibility [km] the multiple-scattering table's steps no longer resolve the fog: the
// sky's brightness stops following the visibility smoothly (sun 30 deg up, horizon green 0.0085
// at 0.5 km, 0.0105 at 0.55, 0.0047 at 0.65, 0.0053 at 1 km; smooth from 0.8 km up) and a
// sunlit fog comes out orders of magnitude too dark.
constexpr double kLeastResolvedVisibility = 0.8;
// The meteorological visibility [km] of settings' air at the observer (Koschmieder: 3.912 over
// the total extinction at 550 nm; the inverse of aerosol_for_visibility).
double visibility_of(const PhysicalSkySettings& settings);
// A caveat for an air of visibility below kLeastResolvedVisibility (to warn of), else nullopt:
// given by visibility= or by aerosol= alike. Throws as validate() for invalid settings.
std::optional<std::string> fog_caveat(const PhysicalSkySettings& settings);

class PhysicalSky {
 public:
  // Example: PhysicalSky sky({Vec3d(0.0, std::sin(0.5), std::cos(0.5)), 1.0});  // sun 28.6 deg up
  explicit PhysicalSky(const PhysicalSkySettings& settings);

  static constexpr int kWavelengths = 48;                // 360, 370, ..., 830 nm
  static constexpr int kElevations = 64, kAzimuths = 128;
  static double wavelength(int i) { return 360.0 + 10.0 * i; }

  // The table: spectral radiance along dir [W/(m^2 sr nm)], linear in lambda between the 10 nm
  // nodes (0 outside [360, 830]) and bilinear in (azimuth, v).
  double radiance(const Vec3d& dir, double lambda_nm) const;
  // As RGB renders see it: linear sRGB of the spectrum's XYZ (CIE 1931) / integral ybar (color.h),
  // i.e. a luminance-weighted spectral radiance [W/(m^2 sr nm)] (times 106.86 nm: W/(m^2 sr)).
  Vec3d rgb_radiance(const Vec3d& dir) const;
  // Direct integration along the ray, no view table (the table's reference; kHorizon: at e = 0 below
  // the horizon, the azimuth +x straight down).
  double radiance_direct(const Vec3d& dir, double lambda_nm) const;

  // Beer-Lambert transmittance of the sunlight from the top of the atmosphere to the observer at
  // a wavelength [nm] in [360, 830].
  double sun_transmittance(double lambda_nm) const;
  // Extraterrestrial solar spectral irradiance [W/(m^2 nm)] at a wavelength [nm] (a 5778 K black
  // body scaled to the solar constant, 1361 W/m^2).
  static double solar_irradiance(double lambda_nm);
  // The sun at the observer: irradiance at normal incidence [W/(m^2 nm)] = E T, and the radiance
  // of a uniform disc of `angular_diameter_deg` (0.53 by default) = E T / its solid angle.
  double sun_irradiance(double lambda_nm) const { return solar_irradiance(lambda_nm) * sun_transmittance(lambda_nm); }
  // The sun's radiance at the observer [W/(m^2 sr nm)] at a wavelength [nm] in [360, 830]: its
  // irradiance (solar_irradiance x sun_transmittance) spread uniformly over a disc of
  // `angular_diameter_deg`.
  double sun_radiance(double lambda_nm, double angular_diameter_deg = 0.53) const;
  // The sun's radiance at the observer as RGB renders see it: linear sRGB of its XYZ / integral ybar,
  // a luminance-weighted spectral radiance [W/(m^2 sr nm)] (times 106.86 nm: W/(m^2 sr)).
  Vec3d sun_radiance_rgb(double angular_diameter_deg = 0.53) const;

  // The Rayleigh optical depth from the observer straight up to the top at a wavelength [nm]
  // (a numerical integral of the profile).
  double rayleigh_optical_depth(double lambda_nm) const;
  // The whole optical depth (Rayleigh + Mie + ozone) from the observer straight up to the top at
  // a wavelength [nm].
  double optical_depth(double lambda_nm) const;

  const PhysicalSkySettings& settings() const { return settings_; }
  // The multiple-scattering table (empty with settings().multiple_scattering false).
  const MultipleScattering& multiple_scattering() const { return multiple_scattering_; }
  double build_seconds() const { return build_seconds_; }

  // The sky of these settings, shared: a process-wide cache of the last few tables (immutable), so
  // that scenes rebuilt with the same sky -- unpickled on a worker for every task of a sweep, or
  // built per point -- pay its build once per process (the same settings give the same table).
  static std::shared_ptr<const PhysicalSky> shared(const PhysicalSkySettings& settings);

  // The table's grid: direction <-> (x = azimuth / 2 pi, y = sqrt(elevation / (pi/2))) in [0, 1]^2,
  // azimuth = atan2(dir.z, dir.x) in [0, 2 pi); solid angle d omega = 2 pi^2 y cos(e) dx dy.
  static Vec2d direction_to_xy(const Vec3d& dir);
  static Vec3d xy_to_direction(const Vec2d& xy);

 private:
  // Where a direction falls in the table: its bilinear cell (rows y0, y0 + 1; columns xa, xb) and
  // the weight of the zenith's value.
  struct TablePoint {
    int y0, xa, xb;
    double tx, ty, zenith;
  };
  static TablePoint table_point(const Vec3d& dir);
  double ground_radiance(double lambda_nm) const;
  double table_at(int row, int column, int w) const { return table_[(size_t(row) * kAzimuths + column) * kWavelengths + w]; }

  PhysicalSkySettings settings_;
  Vec3d sun_;
  MultipleScattering multiple_scattering_;
  std::vector<float> table_;   // [row][column][wavelength], rows at v = (i + 1/2) / kElevations
  std::vector<Vec3d> rgb_;     // [row][column]
  std::array<double, kWavelengths> zenith_{};  // the sky straight up, which every azimuth shares
  Vec3d zenith_rgb_ = Vec3d::Zero();
  std::array<double, kWavelengths> ground_{};
  std::array<double, kWavelengths> sun_transmittance_{};
  Vec3d ground_rgb_ = Vec3d::Zero();
  double build_seconds_ = 0.0;
};

// The sky as an infinite light: Le from the table (spectral: the 4 wavelengths interpolated; RGB:
// the table's linear sRGB); sample_li/pdf_li importance-sample by a PiecewiseConstant2D over cells
// weighted by the luminance of Le at the cell centre x the cell's solid angle:
// - kGround: the upper hemisphere, the table's cells (x, y) (2 pi^2 y cos e / (kAzimuths
//   kElevations) each), pdf_w = pdf_xy / (2 pi^2 y cos e); the ground below the horizon is reached
//   by BSDF sampling only (pdf_li = 0 there);
// - kHorizon: the whole sphere, (x, t) with t = (1 + s) / 2, s = sign(e) sqrt(|e| / (pi/2)) in
//   [-1, 1] on 2 kElevations rows (the lower hemisphere mirrors the upper one's rows),
//   pdf_w = pdf_xt / (4 pi^2 |s| cos e).
// power() = pi R^2 integral of Y(L) over the sphere, R from preprocess (1 m before).

// A physical sky through a spherical standard atmosphere: single scattering (Nishita et al. 1993)
// plus, with multiple_scattering (default True), the higher orders by Hillaire 2020's isotropic
// multiple-scattering table (orders 2-13 explicit, then a geometric series):
// Rayleigh (lambda^-4, 8 km, tau(550 nm) = 0.097), Mie (1.2 km, Cornette-Shanks g = 0.76, scaled by
// `aerosol`, or set by a meteorological `visibility` [km] instead: the total extinction at the
// ground at 550 nm is 3.912 / visibility, Koschmieder), ozone absorption (`ozone_du` Dobson
// units), a 5778 K sun scaled to 1361 W/m^2.
// sun_direction: toward the sun (normalised), y up. Radiance in W/(m^2 sr nm); below the horizon, by
// below_horizon: 'ground' (default) the ground's Lambertian radiance (ground_albedo), reached by
// BSDF sampling only (pdf_li 0); 'horizon' the radiance at the horizon at the same azimuth
// (ground_albedo must be 0), sample_li/pdf_li then cover the whole sphere (Scene.set_physical_sky's
// default). Light sampling draws directions in proportion to a table of the sky's luminance
// (the upper hemisphere; the whole sphere with 'horizon').
class PhysicalSkyLight final : public Light {
 public:
  explicit PhysicalSkyLight(const PhysicalSkySettings& settings);
  LightType type() const override { return LightType::kInfinite; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  Spectrum Le(const Vec3d& dir, const SampledWavelengths& lambda) const override;
  double power() const override;
  void preprocess(const Vec3d& centre, double radius) override;
  std::string describe() const override;

  const PhysicalSky& sky() const { return *sky_; }
  const PhysicalSkySettings& settings() const { return sky_->settings(); }
  double pdf_direction(const Vec3d& wi) const;  // pdf_li without the context

 private:
  bool whole_sphere() const { return sky_->settings().below_horizon == BelowHorizon::kHorizon; }

  std::shared_ptr<const PhysicalSky> sky_;  // PhysicalSky::shared
  PiecewiseConstant2D distribution_;  // over (x, y) (kGround) or (x, t) (kHorizon)
  double radiance_integral_ = 0.0;  // integral of Y(L) over the sphere [W/m^2]
  std::atomic<double> scene_radius_{1.0};  // preprocess writes it while other renders may read it
};

}  // namespace refracta
