// The refractive index of liquid water, for water surfaces (Dielectric / Water materials) and for
// users comparing with measurements: pure water by the IAPWS formulation of 1997, its density at
// atmospheric pressure by Tanaka et al. 2001, and the salinity increment of Quan & Fry 1995.
#pragma once

namespace refracta {

// Ranges the formulas are used in (each inside its source's validity).
constexpr double kWaterMinCelsius = 0.0, kWaterMaxCelsius = 40.0;    // Tanaka et al.'s density fit
constexpr double kWaterMinWavelength = 200.0, kWaterMaxWavelength = 1100.0;  // IAPWS R9-97 [nm]
constexpr double kWaterMaxSalinity = 40.0;  // [g/kg]; Quan & Fry fitted 0-35, linear in S

// Density of air-free pure water at 101 325 Pa [kg/m^3], temperature [deg C] in
// [kWaterMinCelsius, kWaterMaxCelsius]: Tanaka, Girard, Davis, Peuto & Bignell 2001,
// "Recommended table for the density of water between 0 C and 40 C", Metrologia 38, eq. 1
// (999.97495 kg/m^3 at its maximum near 4 C, 998.2067 at 20 C). Throws std::invalid_argument
// outside the range.
double water_density(double temperature_c);

// Refractive index of water relative to vacuum at a vacuum wavelength [nm] in
// [kWaterMinWavelength, kWaterMaxWavelength], temperature [deg C] and salinity [g/kg, ~PSU] in
// [0, kWaterMaxSalinity], at atmospheric pressure:
// - pure water: IAPWS R9-97, "Release on the Refractive Index of Ordinary Water Substance as a
//   Function of Wavelength, Temperature and Pressure" (the Lorentz-Lorenz form
//   (n^2 - 1)/(n^2 + 2) = rho_bar A(rho_bar, T_bar, lambda_bar), eq. A1), at water_density(t);
// - sea water: plus the salinity terms of Quan & Fry 1995, Applied Optics 34(18), eq. 3,
//   (n1 + n2 t + n3 t^2) S + n6 S / lambda (fitted 0-35 g/kg, 0-30 C, 400-700 nm, relative to
//   air: the 3e-4 difference from vacuum in the increment is far below the fit's accuracy).
// Throws std::invalid_argument naming the argument outside its range.
double water_ior(double wavelength_nm, double temperature_c = 20.0, double salinity = 0.0);

}  // namespace refracta
