// The refractive index of water (water.h).
#include "refracta/shading/water.h"

#include "refracta/core/error.h"

#include <cmath>

namespace refracta {

namespace {

void check_range(const char* name, double value, double lo, double hi, const char* unit) {
  if (!(value >= lo && value <= hi)) {
    throw_invalid("water: ", name, " must be in [", lo, ", ", hi, "] ", unit, " (got ", value, ")");
  }
}

}  // namespace

double water_density(double temperature_c) {
  check_range("temperature_c", temperature_c, kWaterMinCelsius, kWaterMaxCelsius, "deg C");
  // Tanaka et al. 2001, eq. 1: rho = a5 [1 - (t + a1)^2 (t + a2) / (a3 (t + a4))].
  constexpr double a1 = -3.983035, a2 = 301.797, a3 = 522528.9, a4 = 69.34881, a5 = 999.974950;
  const double t = temperature_c;
  return a5 * (1.0 - (t + a1) * (t + a1) * (t + a2) / (a3 * (t + a4)));
}

double water_ior(double wavelength_nm, double temperature_c, double salinity) {
  check_range("wavelength", wavelength_nm, kWaterMinWavelength, kWaterMaxWavelength, "nm");
  check_range("salinity", salinity, 0.0, kWaterMaxSalinity, "g/kg");
  const double rho = water_density(temperature_c);  // checks the temperature
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
