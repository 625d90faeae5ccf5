// The air's scattering and absorption: the one set of coefficients, density profiles and phase
// functions that both the physical sky (physical_sky.h) and aerial perspective
// (aerial_perspective.h) integrate (DESIGN.md "One atmosphere, many uses"). The sources of every
// number are given in physical_sky.h.
#pragma once

#include "refracta/core/math.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace refracta::air_optics {

constexpr double kEarthRadius = 6371e3;           // [m] the sky's planet
constexpr double kTop = 80e3;                     // [m] the atmosphere's top above the ground
constexpr double kTopRadius = kEarthRadius + kTop;
constexpr double kRayleighHeight = 8000.0;        // [m] scale height
constexpr double kMieHeight = 1200.0;             // [m]
constexpr double kRayleighDepth550 = 0.097;       // Bodhaine et al. 1999, sea level, 550 nm
// beta_R(550) [1/m] at sea level from that optical depth over the exponential column to kTop.
inline double rayleigh_550() { return kRayleighDepth550 / (kRayleighHeight * (1.0 - std::exp(-kTop / kRayleighHeight))); }
constexpr double kMieScattering = 2.1e-5;         // [1/m] at sea level, aerosol = 1 (Bruneton & Neyret 2008)
constexpr double kMieExtinction = kMieScattering / 0.9;
constexpr double kMieG = 0.76;
constexpr double kDobsonUnit = 2.687e20;          // [molecules/m^2]
constexpr double kOzonePeak = 25e3, kOzoneHalfWidth = 15e3;  // [m] the tent 10..25..40 km (integral 15 km)
constexpr int kNodes = 48;                        // 360, 370, ..., 830 nm
inline double node_wavelength(int i) { return 360.0 + 10.0 * i; }
constexpr int kSunColumnSteps = 48;               // quadrature steps of a sun ray's column (column_to_top)
// Ozone absorption cross-sections [m^2] at the nodes: the IUP Bremen reference spectra
// (Serdyuchenko et al. 2014, "High spectral resolution ozone absorption cross-sections - Part 2",
// AMT 7; Gorshelev et al. 2014, Part 1) at 233 K, averaged over each 10 nm bin, as tabulated in
// E. Bruneton's precomputed_atmospheric_scattering (2017) demo. Data, not code.
constexpr double kOzoneCrossSection[kNodes] = {
    1.18e-27,  2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27,  8.451e-27,
    1.582e-26, 2.316e-26, 3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25,  1.602e-25,
    2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25,   4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25,
    5.019e-25, 4.305e-25, 3.74e-25,  3.215e-25, 2.662e-25, 2.238e-25, 1.852e-25, 1.473e-25,
    1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26,  4.228e-26, 3.237e-26,
    2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26, 2.078e-26, 1.383e-26, 7.105e-27};

// Linear interpolation of node values; 0 outside [360, 830] nm.
inline double lerp_nodes(const double* values, double lambda_nm) {
  if (!(lambda_nm >= 360.0 && lambda_nm <= 830.0)) return 0.0;
  const double x = (lambda_nm - 360.0) / 10.0;
  const int i = std::min(int(x), kNodes - 2);
  const double t = x - i;
  return values[i] * (1.0 - t) + values[i + 1] * t;
}

// Integrals [m] of the relative densities along a path: Rayleigh and Mie relative to sea level,
// ozone relative to its peak.
struct Column {
  double r = 0.0, m = 0.0, o = 0.0;
};

inline Column densities(double h) {
  return {std::exp(-h / kRayleighHeight), std::exp(-h / kMieHeight),
          std::max(0.0, 1.0 - std::abs(h - kOzonePeak) / kOzoneHalfWidth)};
}

inline double rayleigh_phase(double mu) { return 3.0 / (16.0 * kPi) * (1.0 + mu * mu); }
// Cornette & Shanks 1992.
inline double mie_phase(double mu) {
  const double g2 = kMieG * kMieG;
  return 3.0 * (1.0 - g2) * (1.0 + mu * mu) / (8.0 * kPi * (2.0 + g2) * std::pow(1.0 + g2 - 2.0 * kMieG * mu, 1.5));
}

inline double beta_rayleigh(double lambda_nm) { return rayleigh_550() * std::pow(550.0 / lambda_nm, 4.0); }

// The composition of one sky: density scales and the ozone column.
struct AirComposition {
  double rayleigh_scale = 1.0, aerosol = 1.0, ozone_du = 300.0;
  double ozone_peak_density() const { return ozone_du * kDobsonUnit / kOzoneHalfWidth; }  // [1/m^3]
  // Optical depth of a path with relative-density integrals c at a wavelength whose ozone
  // cross-section is sigma_ozone [m^2].
  double optical_depth(const Column& c, double lambda_nm, double sigma_ozone) const {
    return rayleigh_scale * beta_rayleigh(lambda_nm) * c.r + aerosol * kMieExtinction * c.m +
           sigma_ozone * ozone_peak_density() * c.o;
  }
};

// Distance along unit d from p (inside the sphere of radius r about the planet's centre) to its surface.
inline double exit_distance(const Vec3d& p, const Vec3d& d, double r) {
  const double b = p.dot(d), c = p.squaredNorm() - r * r;
  return -b + std::sqrt(std::max(0.0, b * b - c));
}

// Whether the planet hides the direction d from p: the ray meets the surface ahead, or p lies on
// (or under) the surface and d points below its horizon (its column would run through the planet).
inline bool hits_earth(const Vec3d& p, const Vec3d& d) {
  const double b = p.dot(d), c = p.squaredNorm() - kEarthRadius * kEarthRadius;
  if (c <= 0.0) return b < 0.0;
  const double disc = b * b - c;
  return disc > 0.0 && -b - std::sqrt(disc) > 0.0;
}

// The standard atmosphere's refraction at the horizon (astronomical_refraction: 33.0' at 550 nm):
// how far below the planet's limb a sun still shines along the render's curved rays.
constexpr double kHorizonRefraction = 33.0 / 60.0 * kPi / 180.0;  // [rad]

// The direction whose straight column carries the sun's light to p: the sun's own where the planet
// does not hide it; where it hides it by less than kHorizonRefraction, the ray grazing the planet
// toward it (the light the curved rays bring comes that way); nullopt for a sun set further. Before,
// on the ground such a sun's column ran through the planet, and a sun 0.5 deg below the horizon
// kept 1.8e-3 of its light at 700 nm, against 0 in the aerial perspective (a trial).
inline std::optional<Vec3d> sun_column_direction(const Vec3d& p, const Vec3d& sun) {
  if (!hits_earth(p, sun)) return sun;
  const double r = p.norm();
  const Vec3d up = p / r;
  const double limb = -std::acos(std::min(1.0, kEarthRadius / r));  // the grazing ray's elevation
  const double e = std::asin(std::clamp(sun.dot(up), -1.0, 1.0));
  Vec3d across = sun - sun.dot(up) * up;
  if (e < limb - kHorizonRefraction || !(across.norm() > 0.0)) return std::nullopt;
  across.normalize();
  return Vec3d(std::cos(limb) * across + std::sin(limb) * up);
}

// Column densities from p (about the planet's centre) along d to the top: midpoint rule with nodes
// t = L s^2 (dense near p, the path's low end for every ray leaving the ground upward).
inline Column column_to_top(const Vec3d& p, const Vec3d& d, int steps) {
  const double length = exit_distance(p, d, kTopRadius);
  Column c;
  for (int i = 0; i < steps; ++i) {
    const double s = (i + 0.5) / steps, t = length * s * s, dt = length * 2.0 * s / steps;
    const Column rho = densities((p + t * d).norm() - kEarthRadius);
    c.r += rho.r * dt, c.m += rho.m * dt, c.o += rho.o * dt;
  }
  return c;
}

// Closed-form relative-density integrals along a straight piece of `length` [m] whose height
// goes linearly from h0 to h1 [m] (exponential densities: length (e^-h0/H - e^-h1/H) / ((h1 - h0)/H);
// the ozone tent: its exact integral over the heights, piecewise linear).
Column column_along(double h0, double h1, double length);

// Linear sRGB [W/(m^2 sr)]-mean of a spectral radiance given at the nodes (linear between them,
// CIE 1931 normalised by integral ybar: color.h's convention); linear in the values.
Vec3d rgb_of_nodes(const double* values);

}  // namespace refracta::air_optics
