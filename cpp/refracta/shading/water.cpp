// The optics of water: index, density, absorption, backscattering, body reflectance, Cox-Munk
// slopes (water.h).
#include "refracta/shading/water.h"

#include "refracta/core/error.h"
#include "refracta/core/spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace refracta {

void check_water_range(const char* function, const char* name, double value, double lo, double hi, const char* unit) {
  if (!(value >= lo && value <= hi)) {
    throw_invalid(function, ": ", name, " must be in [", lo, ", ", hi, "] ", unit, " (got ", value, ")");
  }
}

namespace {

// Pure-water absorption [1/m] every 5 nm from 360 to 830 nm (water.h cites the sources): Smith &
// Baker 1981 at 360-370 nm, 375 nm joined linearly to Pope & Fry 1997's 380-725 nm, Kou et al.
// 1993 from 730 nm.
constexpr double kAbsorptionStart = 360.0, kAbsorptionStep = 5.0;  // [nm]
constexpr std::array<double, 95> kAbsorption = {
    0.0379,  0.03395, 0.0300,  0.020685, 0.01137, 0.00941, 0.00851, 0.00813, 0.00663, 0.0053,   // 360-405
    0.00473, 0.00444, 0.00454, 0.00478,  0.00495, 0.0053,  0.00635, 0.00751, 0.00922, 0.00962,  // 410-455
    0.00979, 0.01011, 0.0106,  0.0114,   0.0127,  0.0136,  0.0150,  0.0173,  0.0204,  0.0256,   // 460-505
    0.0325,  0.0396,  0.0409,  0.0417,   0.0434,  0.0452,  0.0474,  0.0511,  0.0565,  0.0596,   // 510-555
    0.0619,  0.0642,  0.0695,  0.0772,   0.0896,  0.1100,  0.1351,  0.1672,  0.2224,  0.2577,   // 560-605
    0.2644,  0.2678,  0.2755,  0.2834,   0.2916,  0.3012,  0.3108,  0.3250,  0.3400,  0.3710,   // 610-655
    0.4100,  0.4290,  0.4390,  0.4480,   0.4650,  0.4860,  0.5160,  0.5590,  0.6240,  0.7040,   // 660-705
    0.8270,  1.0070,  1.2310,  1.4890,   1.9624,  2.5304,  2.7680,  2.8338,  2.8484,  2.8794,   // 710-755
    2.8605,  2.8582,  2.8234,  2.7565,   2.6905,  2.5933,  2.4656,  2.3552,  2.2462,  2.2011,   // 760-805
    2.1875,  2.23308, 2.3294,  2.6199,   3.21308};                                             // 810-830

}  // namespace

double water_absorption(double wavelength_nm) {
  check_water_range("water_absorption", "wavelength", wavelength_nm, kLambdaMin, kLambdaMax, "nm");
  const double x = (wavelength_nm - kAbsorptionStart) / kAbsorptionStep;
  const size_t i = std::min(size_t(x), kAbsorption.size() - 2);
  const double t = x - double(i);
  return (1.0 - t) * kAbsorption[i] + t * kAbsorption[i + 1];
}

double water_backscattering(double wavelength_nm, double salinity) {
  check_water_range("water_backscattering", "wavelength", wavelength_nm, kLambdaMin, kLambdaMax, "nm");
  check_water_range("water_backscattering", "salinity", salinity, 0.0, kWaterMaxSalinity, "g/kg");
  // Morel 1974: pure water 0.00222 1/m at 500 nm, sea water of 35-39 g/kg 30 % more, lambda^-4.32.
  const double b500 = 0.00222 * (1.0 + 0.3 * salinity / 37.0);
  return 0.5 * b500 * std::pow(wavelength_nm / 500.0, -4.32);
}

double water_body_reflectance(double wavelength_nm, double salinity) {
  const double bb = water_backscattering(wavelength_nm, salinity);
  return 0.33 * bb / (water_absorption(wavelength_nm) + bb);
}

double cox_munk_mean_square_slope(double wind_speed) {
  check_water_range("cox_munk_mean_square_slope", "wind_speed", wind_speed, 0.0, kWaterMaxWindSpeed, "m/s");
  return 0.003 + 5.12e-3 * wind_speed;
}

double water_density(double temperature_c) {
  check_water_range("water_density", "temperature_c", temperature_c, kWaterMinCelsius, kWaterMaxCelsius, "deg C");
  // Tanaka et al. 2001, eq. 1: rho = a5 [1 - (t + a1)^2 (t + a2) / (a3 (t + a4))].
  constexpr double a1 = -3.983035, a2 = 301.797, a3 = 522528.9, a4 = 69.34881, a5 = 999.974950;
  const double t = temperature_c;
  return a5 * (1.0 - (t + a1) * (t + a1) * (t + a2) / (a3 * (t + a4)));
}

double water_ior(double wavelength_nm, double temperature_c, double salinity) {
  check_water_range("water_ior", "wavelength", wavelength_nm, kWaterMinWavelength, kWaterMaxWavelength, "nm");
  check_water_range("water_ior", "salinity", salinity, 0.0, kWaterMaxSalinity, "g/kg");
  check_water_range("water_ior", "temperature_c", temperature_c, kWaterMinCelsius, kWaterMaxCelsius, "deg C");
  const double rho = water_density(temperature_c);
  // IAPWS R9-97: reduced density, temperature and wavelength, and the coefficients of eq. A1.
  constexpr double a0 = 0.244257733, a1 = 9.74634476e-3, a2 = -3.73234996e-3, a3 = 2.68678472e-4,
                   a4 = 1.58920570e-3, a5 = 2.45934259e-3, a6 = 0.900704920, a7 = -1.66626219e-2;
  constexpr double lambda_uv = 0.2292020, lambda_ir = 5.432937;
  const double d = rho / 1000.0, theta = (temperature_c + 273.15) / 273.15;
  const double l2 = (wavelength_nm / 589.0) * (wavelength_nm / 589.0);
  const double a = d * (a0 + a1 * d + a2 * theta + a3 * l2 * theta + a4 / l2 + a5 / (l2 - lambda_uv * lambda_uv) +
                        a6 / (l2 - lambda_ir * lambda_ir) + a7 * d * d);
  const double pure = std::sqrt((1.0 + 2.0 * a) / (1.0 - a));
  // Quan & Fry 1995, eq. 3: the terms in S.
  constexpr double n1 = 1.779e-4, n2 = -1.05e-6, n3 = 1.6e-8, n6 = 0.01155;
  const double t = temperature_c;
  return pure + (n1 + n2 * t + n3 * t * t) * salinity + n6 * salinity / wavelength_nm;
}

}  // namespace refracta
