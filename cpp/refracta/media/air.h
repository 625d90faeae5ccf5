// The index of air and the standard atmosphere.
//  - Index: Edlén's formula as revised by Birch & Downs (Metrologia 30, 1993, 155; erratum 31,
//    1994, 315): dry air with 400-450 ppm CO2, plus the water-vapour term. At 550 nm, 15 °C,
//    101 325 Pa it gives n - 1 = 2.77837e-4 (Ciddor 1996: 2.7784e-4).
//  - Temperature: U.S. Standard Atmosphere 1976, its seven layers to 86 km, shifted by the ground
//    temperature; gravity falls as (r0 / (r0 + h))^2.
//  - Saturation vapour pressure: Magnus form of Alduchov & Eskridge (1996).
#pragma once

#include "refracta/core/math.h"

#include <cmath>
#include <type_traits>

namespace refracta {

constexpr double kGravity = 9.80665;           // [m/s^2], standard gravity
constexpr double kGasConstantDryAir = 8314.32 / 28.9644;  // [J/(kg K)], R*/M0 of USSA 1976 (287.05307)
constexpr double kZeroCelsius = 273.15;         // [K]
constexpr double kStandardGroundTemperature = 288.15;  // [K]
constexpr double kStandardLapseRate = 0.0065;          // [K/m], troposphere
constexpr double kStandardPressure = 101325.0;         // [Pa]

// n - 1 and its partial derivatives, for the chain rule of dn/dh.
template <class T>
struct AirIndex {
  T n_minus_1;
  T d_pressure;     // [1/Pa]
  T d_temperature;  // [1/K]
  T d_vapour;       // [1/Pa]
};

// The wavelength's terms of Birch & Downs' formula below, computed once per field: dry air's
// (n_s - 1) / 96095.43 [1/Pa] and water vapour's factor [1/Pa] (its divisions were a tenth of a
// hot-spot field's evaluation when made at every point).
template <class T>
struct EdlenDispersion {
  T dry;
  T water;
};

template <class T>
EdlenDispersion<T> edlen_dispersion(const T& wavelength_nm) {
  const T sigma2 = T(1e6) / (wavelength_nm * wavelength_nm);  // [1/um^2]
  const T dry_standard =
      (T(8342.54) + T(2406147.0) / (T(130.0) - sigma2) + T(15998.0) / (T(38.9) - sigma2)) * 1e-8;
  return {dry_standard / T(96095.43), -(T(3.7345) - T(0.0401) * sigma2) * 1e-10};
}

// Birch & Downs (1993/94) modified Edlén equation. pressure [Pa], temperature [K], partial
// pressure of water vapour [Pa], the wavelength's terms (edlen_dispersion).
template <class T>
AirIndex<T> air_index(const T& pressure, const T& temperature, const T& vapour, const EdlenDispersion<T>& dispersion) {
  const T& a = dispersion.dry;
  const T t = temperature - T(kZeroCelsius);
  const T compress = T(1e-8) * (T(0.601) - T(0.00972) * t);  // [1/Pa]
  const T density = T(1.0) + T(0.003661) * t;
  const T& water = dispersion.water;

  AirIndex<T> out;
  out.n_minus_1 = a * pressure * (T(1.0) + compress * pressure) / density + water * vapour;
  out.d_pressure = a * (T(1.0) + T(2.0) * compress * pressure) / density;
  out.d_temperature = a * pressure *
                      (T(-0.00972e-8) * pressure * density -
                       (T(1.0) + compress * pressure) * T(0.003661)) /
                      (density * density);
  out.d_vapour = water;
  return out;
}

// The same at a vacuum wavelength [nm].
template <class T>
AirIndex<T> air_index(const T& pressure, const T& temperature, const T& vapour, const T& wavelength_nm) {
  return air_index(pressure, temperature, vapour, edlen_dispersion(wavelength_nm));
}

// Saturation vapour pressure over water [Pa] and its derivative [Pa/K] (Alduchov & Eskridge 1996).
template <class T>
void saturation_vapour_pressure(const T& temperature, T* e_s, T* de_dt) {
  using std::exp;
  const T t = temperature - T(kZeroCelsius);
  const T denom = t + T(243.04);
  *e_s = T(610.94) * exp(T(17.625) * t / denom);
  *de_dt = *e_s * T(17.625 * 243.04) / (denom * denom);
}

// U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562), 0 to 86 km: seven layers of constant lapse
// rate in geopotential height H = r0 h / (r0 + h) (r0 = 6 356 766 m; h geometric). Base heights
// [m'] and dT/dH [K/m'] above the troposphere; the troposphere's ground temperature and lapse rate
// are parameters (the standard: 288.15 K, 6.5 K/km'), and the layers above keep the standard
// steps from the tropopause temperature (so a warmer ground shifts the whole column).
constexpr double kGeopotentialRadius = 6356766.0;  // [m], r0 of USSA 1976
constexpr double kTropopause = 11000.0;           // [m']
struct StandardLayer {
  double base;   // [m']
  double slope;  // dT/dH [K/m']
};
constexpr StandardLayer kStandardLayers[] = {
    {11000.0, 0.0}, {20000.0, 0.001}, {32000.0, 0.0028}, {47000.0, 0.0}, {51000.0, -0.0028}, {71000.0, -0.002}};
constexpr double kStandardTop = 84852.0;  // [m'], 86 km geometric

template <class T>
T geopotential_height(const T& h) {
  return T(kGeopotentialRadius) * h / (T(kGeopotentialRadius) + h);
}
inline double geometric_height(double geopotential) {
  return kGeopotentialRadius * geopotential / (kGeopotentialRadius - geopotential);
}
// g(h) / g0 = dH/dh = (r0 / (r0 + h))^2.
template <class T>
T gravity_ratio(const T& h) {
  const T ratio = T(kGeopotentialRadius) / (T(kGeopotentialRadius) + h);
  return ratio * ratio;
}

// Temperature [K] and dT/dh [K/m] (geometric h [m]) of the standard atmosphere with the given ground
// temperature [K] and tropospheric lapse rate [K/m']; above 86 km it stays at the top's value.
template <class T>
void standard_temperature(const T& h, const T& ground, const T& lapse, T* temperature, T* slope) {
  const T geopotential = geopotential_height(h);
  const double hv = value_of(geopotential);
  if (hv <= kTropopause) {
    *temperature = ground - lapse * geopotential;
    *slope = -lapse * gravity_ratio(h);
    return;
  }
  T t = ground - lapse * kTropopause;
  double dt_dh = 0.0;
  const size_t layers = sizeof(kStandardLayers) / sizeof(kStandardLayers[0]);
  for (size_t i = 0; i < layers; ++i) {
    const double base = kStandardLayers[i].base;
    const double next = i + 1 < layers ? kStandardLayers[i + 1].base : kStandardTop;
    if (hv <= next) {
      t += kStandardLayers[i].slope * (geopotential - base);
      dt_dh = kStandardLayers[i].slope;
      break;
    }
    t += kStandardLayers[i].slope * (next - base);  // the whole layer below
  }
  *temperature = t;
  *slope = hv > kStandardTop ? T(0.0) : T(dt_dh) * gravity_ratio(h);
}

}  // namespace refracta

namespace refracta {

// n of air and its sensitivities to pressure [1/Pa] and temperature [1/K] (water vapour at the
// relative humidity following the temperature), at pressure [Pa], temperature [K], relative
// humidity [0, 1] and the wavelength's terms (edlen_dispersion).
template <class T>
void air_index_at(const T& pressure, const T& temperature, const T& humidity, const EdlenDispersion<T>& dispersion,
                  T* n, T* dn_dpressure, T* dn_dtemperature) {
  T e_s(0.0), de_dt(0.0);
  // Dry air skips the vapour for a plain number only: a Jet's derivative in humidity is e_s even
  // at humidity 0 (skipped, it was 0, and humidity free from its default looked idle: a trial).
  const bool dry = std::is_same_v<T, double> && value_of(humidity) == 0.0;
  if (!dry) saturation_vapour_pressure(temperature, &e_s, &de_dt);
  const AirIndex<T> air = air_index(pressure, temperature, T(humidity * e_s), dispersion);
  *n = T(1.0) + air.n_minus_1;
  *dn_dpressure = air.d_pressure;
  *dn_dtemperature = air.d_temperature + air.d_vapour * humidity * de_dt;
}

// dP/dh [Pa/m] of air in hydrostatic balance: -g(h) P / (R_d T).
template <class T>
T hydrostatic_pressure_slope(const T& h, const T& pressure, const T& temperature) {
  return -T(kGravity / kGasConstantDryAir) * gravity_ratio(h) * pressure / temperature;
}

}  // namespace refracta
