// Spectral colour science behind Color (color.h): the CIE 1931 2-degree colour-matching functions
// and D65 (cie_tables.inc, generated from colour-science), Planck's law, XYZ <-> linear sRGB
// (IEC 61966-2-1), and Jakob & Hanika 2019 reflectance upsampling ("A Low-Dimensional Function
// Space for Efficient Spectral Upsampling", CGF 38(2)): a Gauss-Newton fit per colour and the
// precomputed coefficient table textures are served from (pbrt-v4's RGBToSpectrumTable idea).
//
// Normalisations (shared/SHADING.md section 7):
// - XYZ of a radiance spectrum L: integral(L cmf) / integral(y), so that L = 1 at every
//   wavelength has Y = 1 (to_linear_srgb's Monte Carlo estimate has the same normalisation).
// - XYZ of a reflectance s: integral(s cmf D65) / integral(y D65) (white has Y = 1).
// - The illuminant spectrum of RGB emission is RGB x d65_normalised(lambda) with
//   d65_normalised = D65 integral(y) / integral(y D65): its Y is 1, so illuminant(1, 1, 1) renders
//   as linear sRGB (1.00001, 1.00008, 0.99983): the tabulated D65's chromaticity (0.312727,
//   0.329023) against the standard's 4-decimal white (0.3127, 0.3290) in its matrix.
// Integrals are over the tables' 1 nm grid [360, 830] nm with linear interpolation between samples
// (the trapezoidal rule), the same function the Monte Carlo estimate integrates.
#pragma once

#include "refracta/core/math.h"

#include <array>
#include <vector>

namespace refracta {

namespace spectral {

constexpr double kTableMin = 360.0;  // [nm] first sample of the CIE tables
constexpr double kTableMax = 830.0;  // [nm] last sample
constexpr int kTableSamples = 471;   // 1 nm steps

// The CIE 1931 2-degree colour-matching functions at lambda [nm], linearly interpolated, 0 outside
// [360, 830].
Vec3d cie_xyz(double lambda_nm);
// integral of y(lambda) d lambda over the tables [nm] (106.857).
double cie_y_integral();
// CIE D65 relative SPD (100 at 560 nm), linearly interpolated, 0 outside [360, 830].
double d65(double lambda_nm);
// D65 scaled to Y = 1 in the radiance normalisation above: d65 * cie_y_integral / integral(y D65).
double d65_normalised(double lambda_nm);

// Planck's law: spectral radiance of a black body [W/(m^2 sr nm)] at lambda [nm], temperature [K].
double planck(double lambda_nm, double temperature);
// [K] the hottest temperature planck and Color::blackbody take: a choice far beyond any physical
// source (a quark-gluon plasma's); the radiance itself overflows a double only near 4e296 K.
constexpr double kHottestBlackbody = 1e12;
// temperature itself; throws (ValueError) naming `what` unless it is in (0, kHottestBlackbody] K.
double checked_temperature(double temperature, const char* what);

// IEC 61966-2-1: XYZ -> linear sRGB (colour-science's matrix) and its exact inverse.
Vec3d xyz_to_linear_srgb(const Vec3d& xyz);
Vec3d linear_srgb_to_xyz(const Vec3d& rgb);

// --- White points and chromatic adaptation (the display's white balance, tonemap.h) ---------------
// XYZ of the light a white balance names, scaled to Y = 1:
// - planckian_white: Planck's radiator at `kelvin` (planck() at the tables' 1 nm wavelengths through
//   xyz_of_radiance: the Planckian locus, a photographer's colour temperature with tint 0);
// - daylight_white: the CIE daylight locus at a correlated colour temperature in [4000, 25000] K
//   (CIE 015:2004 eq. 3.3-3.4: x_D a cubic in 10^3/T on two ranges, y_D = -3 x_D^2 + 2.87 x_D -
//   0.275); the standard illuminants sit at 1.4388/1.4380 x their nominal T (D55 5503 K, D65
//   6504 K, D75 7504 K). Both throw std::invalid_argument outside their range or for NaN.
Vec3d planckian_white(double kelvin);
Vec3d daylight_white(double kelvin);
// The Bradford chromatic adaptation (Lam 1985; Lindbloom's "Chromatic Adaptation"; colour-science's
// matrix_chromatic_adaptation_VonKries(..., transform='Bradford')): the XYZ -> XYZ matrix
// M^-1 diag(M target / M source) M, M the Bradford cone-response matrix, taking `source_white` to
// `target_white`. Throws when a white has a cone response <= 0.
Eigen::Matrix3d bradford_adaptation(const Vec3d& source_white, const Vec3d& target_white);
// Whether XYZ `white` can be adapted from or to: its Bradford cone responses all > 0 and finite.
bool adaptable_white(const Vec3d& white);

// XYZ of a spectrum given as values at the 471 table wavelengths (1 nm over [360, 830]):
// as a radiance (normalised by integral y) or as a reflectance under D65 (normalised by D65's Y).
Vec3d xyz_of_radiance(const std::vector<double>& values_1nm);
Vec3d xyz_of_reflectance(const std::vector<double>& values_1nm);

// --- Jakob & Hanika 2019 sigmoid polynomials -----------------------------------------------------
// s(lambda) = 1/2 + x / (2 sqrt(1 + x^2)), x = c0 t^2 + c1 t + c2, with t = (lambda - 360)/(830 -
// 360) the wavelength normalised to [0, 1] over the tables (better conditioned than lambda in nm:
// the three monomials have comparable magnitudes). x = -inf / +inf give 0 / 1 (black, white).
using Coefficients = std::array<double, 3>;
double sigmoid_polynomial(const Coefficients& c, double lambda_nm);

struct FitResult {
  Coefficients c{0.0, 0.0, 0.0};
  double residual = 0.0;  // CIELAB distance (Delta E 1976) between the target and the fit
  int iterations = 0;
};
// The coefficients whose reflectance under D65 has the CIELAB coordinates of linear sRGB `rgb`
// (in [0, 1]^3): Gauss-Newton on the CIELAB difference with the analytic Jacobian and step halving
// (the paper's rgb2spec_opt uses finite differences), from `start`. `quadrature_step_nm` (1, 2, 5,
// 10: a divisor of 470) integrates on a coarser grid, exactly for spectra linear between nodes.
// Greys r = g = b have the exact flat solution (0, 0, (g - 1/2)/sqrt(g (1 - g))).
FitResult fit_reflectance(const Vec3d& rgb, const Coefficients& start = {0.0, 0.0, 0.0},
                          int quadrature_step_nm = 1);
// A fit that reaches saturated colours from any start: continuation from the grey of the same
// mean along the segment to rgb, each step warm-started by the last (as rgb2spec_opt walks its
// table outward), then polished at 1 nm.
FitResult fit_reflectance_robust(const Vec3d& rgb);

// The coefficient table over RGB (pbrt-v4 RGBToSpectrumTable): for each largest component l,
// z = that component on res nodes z_k = smoothstep(smoothstep(k/(res-1))) (dense near black and
// white, where the coefficients change fastest), x, y = the next two components (cyclically)
// divided by z on a uniform grid; coefficients trilinearly interpolated.
class RgbToSpectrumTable {
 public:
  RgbToSpectrumTable(int resolution, int quadrature_step_nm, int polish_steps);
  Coefficients coefficients(const Vec3d& rgb) const;  // rgb clamped to [0, 1] (NaN -> 0)
  int resolution() const { return res_; }
  double build_seconds() const { return build_seconds_; }
  double worst_fit_residual() const { return worst_residual_; }  // CIELAB Delta E over the nodes

 private:
  int res_, quadrature_step_, polish_steps_;
  std::vector<double> z_, xy_;  // nodes of the largest component and of the two ratios
  std::vector<double> c_;  // [l][z][y][x][3]
  double build_seconds_ = 0.0, worst_residual_ = 0.0;
};
// The table textures use, built once on first use (std::call_once; in parallel over oneTBB).
// kTableResolution and kTableQuadratureStep were chosen by measuring build time and round-trip
// error (see color.cpp).
constexpr int kTableResolution = 32;
constexpr int kTableQuadratureStep = 5;  // [nm]
constexpr int kTablePolishSteps = 2;  // Gauss-Newton steps after the interpolation
const RgbToSpectrumTable& rgb_to_spectrum_table();

}  // namespace spectral

}  // namespace refracta
