// The optics of liquid water, for water surfaces (Dielectric / Water materials, water_surface.h)
// and for users comparing with measurements: the refractive index of pure water by the IAPWS
// formulation of 1997, its density at atmospheric pressure by Tanaka et al. 2001, and the salinity
// increment of Quan & Fry 1995; the absorption and backscattering of pure (sea) water and the
// irradiance reflectance of a deep body of it; the Cox & Munk 1954 slope statistics of the wind-
// roughened sea surface.
#pragma once

namespace refracta {

// Ranges the formulas are used in (each inside its source's validity).
// Down to -2 C: sea water of 35 g/kg freezes at -1.9 C (UNESCO 1983), and the cold seas of
// superior mirages sit there. Tanaka et al.'s density fit (0-40 C) is extrapolated those 2 K: at
// -5 C it gives 999.263 kg/m^3 against supercooled water's measured ~999.27 (Hare & Sorensen
// 1987), a difference worth 2e-6 in n; IAPWS R9-97 itself holds from -12 C.
constexpr double kWaterMinCelsius = -2.0, kWaterMaxCelsius = 40.0;
constexpr double kWaterMinWavelength = 200.0, kWaterMaxWavelength = 1100.0;  // IAPWS R9-97 [nm]
constexpr double kWaterMaxSalinity = 40.0;  // [g/kg]; Quan & Fry fitted 0-35, linear in S

// Throws std::invalid_argument "<function>: <name> must be in [lo, hi] <unit> (got value)" unless
// lo <= value <= hi (NaN too): the checks of the functions below, and of Water's parameters.
void check_water_range(const char* function, const char* name, double value, double lo, double hi, const char* unit);

// Density of air-free pure water at 101 325 Pa [kg/m^3], temperature [deg C] in
// [-2, 40] (above): Tanaka, Girard, Davis, Peuto & Bignell 2001,
// "Recommended table for the density of water between 0 C and 40 C", Metrologia 38, eq. 1
// (999.97495 kg/m^3 at its maximum near 4 C, 998.2067 at 20 C). Outside the range:
// std::invalid_argument (ValueError in Python).
double water_density(double temperature_c);

// The water functions' defaults: pure water (salinity 0) at 20 deg C, the usual reference
// temperature of refractive indices (n_D at 20 deg C). shading.Water's sea has its own defaults.
constexpr double kPureWaterSalinity = 0.0;       // [g/kg]
constexpr double kWaterTableTemperature = 20.0;  // [deg C]

// Refractive index of water relative to vacuum at a vacuum wavelength [nm] in [200, 1100],
// temperature [deg C] in [-2, 40] and salinity [g/kg, ~PSU] in [0, 40], at atmospheric pressure.
// Pure water by IAPWS R9-97, "Release on the
// Refractive Index of Ordinary Water Substance as a Function of Wavelength, Temperature and
// Pressure" (the Lorentz-Lorenz form (n^2 - 1)/(n^2 + 2) = rho_bar A(rho_bar, T_bar, lambda_bar),
// eq. A1), at water_density(t); sea water plus the salinity terms of Quan & Fry 1995, Applied
// Optics 34(18), eq. 3, (n1 + n2 t + n3 t^2) S + n6 S / lambda (fitted 0-35 g/kg, 0-30 C, 400-700
// nm, relative to air: the 3e-4 difference from vacuum in the increment is far below the fit's
// accuracy).
// Outside the ranges: std::invalid_argument (ValueError in Python) naming the argument.
double water_ior(double wavelength_nm, double temperature_c = kWaterTableTemperature,
                 double salinity = kPureWaterSalinity);

// Absorption coefficient of pure water [1/m] at a wavelength [nm] in [360, 830],
// linear between 5 nm nodes: Pope & Fry 1997 ("Absorption spectrum (380-700 nm) of
// pure water. II. Integrating cavity measurements", Applied Optics 36(33), 8710-8723) from 380 to
// 725 nm; Smith & Baker 1981 ("Optical properties of the clearest natural waters (200-800 nm)",
// Applied Optics 20(2), 177-184) below; Kou, Labrie & Chylek 1993 (Applied Optics 32(19)) above,
// as NASA's ocean-colour processing joins them (0.00635 at 440 nm, 0.0565 at 550, 0.624 at 700).
// The small temperature and salinity dependence of absorption is left out. Outside the range:
// std::invalid_argument (ValueError in Python).
double water_absorption(double wavelength_nm);

// Backscattering coefficient of pure (sea) water [1/m]: half the molecular scattering
// b_w(lambda) = b_w(500) (lambda / 500)^-4.32 of Morel 1974 ("Optical properties of pure water and
// pure sea water", in Optical Aspects of Oceanography, Jerlov & Steemann Nielsen eds.), whose phase
// function is symmetric front-to-back; b_w(500) = 0.00222 1/m for pure water, and sea water
// (S = 35-39 g/kg) scatters 30 % more: b_w(500) = 0.00222 (1 + 0.3 S / 37). Zhang et al. 2009
// (Optics Express 17(7)) derive the same lambda^-4.32 slope from fluctuation theory. Wavelength in
// [360, 830] nm (water_absorption's range, with which it makes the water body's colour), salinity
// in [0, kWaterMaxSalinity = 40] g/kg; outside: std::invalid_argument (ValueError in Python).
double water_backscattering(double wavelength_nm, double salinity = kPureWaterSalinity);

// Irradiance reflectance R = E_u / E_d just beneath the surface of an optically deep, homogeneous
// water body: R = 0.33 b_b / (a + b_b) (Morel & Prieur 1977, "Analysis of variations in ocean
// color", Limnology and Oceanography 22(4), R = 0.33 b_b / a; written with Gordon, Brown & Jacobs
// 1975's variable X = b_b / (a + b_b), Applied Optics 14(2), so that R stays below 0.33 where
// backscattering rivals absorption). Pure water of the given salinity: blue (0.13 at 420 nm),
// 0.0054 at 550 nm, 4.4e-4 at 650 nm for S = 35). Throws outside 360-830 nm or 0-40 g/kg.
double water_body_reflectance(double wavelength_nm, double salinity = kPureWaterSalinity);

// Wind speeds the Cox-Munk statistics are used for [m/s]: they measured 1-14 m/s; beyond 30 m/s
// foam and spray cover the sea, which they do not describe.
constexpr double kWaterMaxWindSpeed = 30.0;

// Total (upwind + crosswind) mean-square slope of a clean sea surface at wind speed U [m/s],
// 12.5 m above the sea: sigma^2 = 0.003 + 5.12e-3 U (Cox & Munk 1954, "Measurement of the roughness
// of the sea surface from photographs of the sun's glitter", JOSA 44(11), 838-850, eq. for
// sigma_u^2 + sigma_c^2, +-0.004). U in [0, 30]; ValueError naming wind_speed otherwise.
double cox_munk_mean_square_slope(double wind_speed);

}  // namespace refracta
