// Fresnel reflectance of smooth interfaces and the reflection / refraction directions
// (shared/SHADING.md section 1). Dielectrics: the exact unpolarised formula (Born & Wolf,
// Principles of Optics, 1.5.2); conductors: the exact formula with a complex index eta + i k
// (pbrt-v4's FrComplex). Directions follow pbrt-v4: w points away from the surface.
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace refracta {

// Unpolarised reflectance of a dielectric interface. eta = eta_t / eta_i seen from the side the
// cosine is measured on: cos_i > 0 on the outside (the normal's side); cos_i < 0 means the light
// arrives from inside and the relative index becomes 1 / eta. Total internal reflection gives 1.
inline double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, -1.0, 1.0);
  if (cos_i < 0.0) {
    eta = 1.0 / eta;
    cos_i = -cos_i;
  }
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

// Unpolarised reflectance of a conductor of complex relative index eta + i k, light arriving
// from the outside at |cos_i| (pbrt-v4 FrComplex). k = 0 reproduces fresnel_dielectric outside.
inline double fresnel_complex(double cos_i, std::complex<double> eta) {
  using C = std::complex<double>;
  cos_i = std::clamp(std::abs(cos_i), 0.0, 1.0);
  if (cos_i == 0.0) return 1.0;  // grazing: all reflected (r_s was 0 / 0 at eta = 1, k = 0)
  const double sin2_i = 1.0 - cos_i * cos_i;
  const C sin2_t = sin2_i / (eta * eta);
  const C cos_t = std::sqrt(C(1.0) - sin2_t);
  const C r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const C r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

inline Spectrum fresnel_complex(double cos_i, const Spectrum& eta, const Spectrum& k) {
  Spectrum out;
  for (int i = 0; i < kSpectrumSamples; ++i) out[i] = fresnel_complex(cos_i, std::complex<double>(eta[i], k[i]));
  return out;
}

// Hemispherical (cosine-weighted) reflectance 2 int_0^1 F(mu) mu dmu of a dielectric seen from
// the side where eta = eta_t / eta_i (shared/SHADING.md section 1: 0.091778 for eta = 1.5,
// 0.596346 for 1 / 1.5). 32-point Gauss-Legendre quadrature, split at the critical angle when
// eta < 1 (F = 1 below it) with a square-root substitution above it; error < 1e-9.
double fresnel_diffuse_reflectance(double eta);

// The same with their arguments checked (std::invalid_argument naming the argument): eta finite
// and > 0, k finite and >= 0, cos_i in [-1, 1]. The Python functions of refracta.shading.
double checked_fresnel_dielectric(double cos_i, double eta);
double checked_fresnel_conductor(double cos_i, double eta, double k);
double checked_fresnel_diffuse_reflectance(double eta);

// Mirror reflection of w about the unit normal n.
inline Vec3d reflect(const Vec3d& w, const Vec3d& n) { return -w + 2.0 * w.dot(n) * n; }

// Refraction of w (away from the surface) through the interface with unit normal n and relative
// index eta = eta_t / eta_i seen from n's side (pbrt-v4 Refract; equivalently the seed's
// w_t = (eta_1/eta_2)(-w + (w.n) n) - sqrt(1 - (eta_1/eta_2)^2 (1 - (w.n)^2)) n for the
// arriving direction -w). w below n flips n and inverts eta. Returns false on total internal
// reflection; etap receives the relative index the light actually crossed.
inline bool refract(const Vec3d& w, Vec3d n, double eta, double* etap, Vec3d* wt) {
  double cos_i = n.dot(w);
  if (cos_i < 0.0) {
    eta = 1.0 / eta;
    cos_i = -cos_i;
    n = -n;
  }
  const double sin2_i = std::max(0.0, 1.0 - cos_i * cos_i);
  const double sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0) return false;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  *wt = -w / eta + (cos_i / eta - cos_t) * n;
  if (etap) *etap = eta;
  return true;
}

}  // namespace refracta
