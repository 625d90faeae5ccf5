// The index of air and the standard atmosphere.
//  - Index: Edlén's formula as revised by Birch & Downs (Metrologia 30, 1993, 155; erratum 31,
//    1994, 315): dry air with 400-450 ppm CO2, plus the water-vapour term. At 550 nm, 15 °C,
//    101 325 Pa it gives n - 1 = 2.77837e-4 (Ciddor 1996: 2.7784e-4).
//  - Temperature: U.S. Standard Atmosphere 1976, layers to 32 km, shifted by the ground temperature.
//  - Saturation vapour pressure: Magnus form of Alduchov & Eskridge (1996).
#pragma once

#include "refracta/core/math.h"

#include <cmath>

namespace refracta {

constexpr double kGravity = 9.80665;           // [m/s^2], standard gravity
constexpr double kGasConstantDryAir = 287.053;  // [J/(kg K)], R*/M0 of USSA 1976
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

// Birch & Downs (1993/94) modified Edlén equation. pressure [Pa], temperature [K], partial
// pressure of water vapour [Pa], vacuum wavelength [nm].
template <class T>
AirIndex<T> air_index(const T& pressure, const T& temperature, const T& vapour,
                      const T& wavelength_nm) {
  const T sigma2 = T(1e6) / (wavelength_nm * wavelength_nm);  // [1/um^2]
  const T dry_standard =
      (T(8342.54) + T(2406147.0) / (T(130.0) - sigma2) + T(15998.0) / (T(38.9) - sigma2)) * 1e-8;
  const T a = dry_standard / T(96095.43);
  const T t = temperature - T(kZeroCelsius);
  const T compress = T(1e-8) * (T(0.601) - T(0.00972) * t);  // [1/Pa]
  const T density = T(1.0) + T(0.003661) * t;
  const T water = -(T(3.7345) - T(0.0401) * sigma2) * 1e-10;  // [1/Pa]

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

// Saturation vapour pressure over water [Pa] and its derivative [Pa/K] (Alduchov & Eskridge 1996).
template <class T>
void saturation_vapour_pressure(const T& temperature, T* e_s, T* de_dt) {
  using std::exp;
  const T t = temperature - T(kZeroCelsius);
  const T denom = t + T(243.04);
  *e_s = T(610.94) * exp(T(17.625) * t / denom);
  *de_dt = *e_s * T(17.625 * 243.04) / (denom * denom);
}

// U.S. Standard Atmosphere 1976 temperature [K] and dT/dh [K/m] for heights up to 32 km, with the
// troposphere's ground temperature and lapse rate as parameters (the standard: 288.15 K, 6.5 K/km).
// Heights are treated as geopotential (the difference is 0.016 % at 1 km).
template <class T>
void standard_temperature(const T& h, const T& ground, const T& lapse, T* temperature, T* slope) {
  const double kTropopause = 11000.0, kStratopause = 20000.0;
  const double hv = value_of(h);
  if (hv <= kTropopause) {
    *temperature = ground - lapse * h;
    *slope = -lapse;
  } else if (hv <= kStratopause) {
    *temperature = ground - lapse * kTropopause;
    *slope = T(0.0);
  } else {
    *temperature = ground - lapse * kTropopause + T(0.001) * (h - kStratopause);
    *slope = T(0.001);
  }
}

}  // namespace refracta

namespace refracta {

// n(h) and dn/dh of air in hydrostatic balance, from the local pressure [Pa], temperature [K] and
// its height derivative [K/m], relative humidity [0, 1] and wavelength [nm]:
//   dn/dh = dN/dP P' + (dN/dT + dN/de RH e_s'(T)) T',   P' = -g P / (R_d T).
template <class T>
void air_column_index(const T& pressure, const T& temperature, const T& dtemperature_dh,
                      const T& humidity, const T& wavelength_nm, T* n, T* dn_dh) {
  T e_s(0.0), de_dt(0.0);
  if (value_of(humidity) != 0.0) saturation_vapour_pressure(temperature, &e_s, &de_dt);
  const AirIndex<T> air = air_index(pressure, temperature, T(humidity * e_s), wavelength_nm);
  const T dpressure_dh = -T(kGravity / kGasConstantDryAir) * pressure / temperature;
  *n = T(1.0) + air.n_minus_1;
  *dn_dh = air.d_pressure * dpressure_dh +
           (air.d_temperature + air.d_vapour * humidity * de_dt) * dtemperature_dh;
}

}  // namespace refracta
