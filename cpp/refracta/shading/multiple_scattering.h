// Multiple scattering in the air: the isotropic approximation of Hillaire 2020 ("A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique", EGSR, section 5.5), shared by the
// physical sky (physical_sky.h) and the aerial perspective (aerial_perspective.h) so that both add
// exactly the same light.
//
// At a point x of height h where the sun's zenith cosine is mu_s, and for a top-of-atmosphere
// irradiance of 1 (per wavelength):
// - L_2 = integral over the sphere of L'(x, -w) p_u dw, with
//   L'(x, v) = integral_0^|p - x| T(x, x - t v) sigma_s(x - t v) T_sun(x - t v) p_u dt
//              + T(x, p) albedo / pi T_sun(p) max(0, mu_s(p))     (p: where the ray meets the ground)
//   (the second-order light reaching x, every scattering taken isotropic: p_u = 1 / 4 pi);
// - f_ms = integral over the sphere of [integral T(x, x - t w) sigma_s(x - t w) dt] p_u dw (the
//   fraction of isotropically scattered light that scatters again around x);
// - Psi_ms = L_2 / (1 - f_ms): every higher order as the geometric series of f_ms (the paper's
//   assumptions: the light of orders >= 2 is isotropic, and its neighbourhood is that of x).
// Measured and not taken: the aerosol's forward peak by the similarity relation in the orders
// >= 2 (Mie sigma_s (1 - g), extinction sigma_t - g sigma_s): 1 km fog zenith / horizon 0.30 /
// 0.48 -> 0.37 / 1.09 of the Monte Carlo (0.54 / 1.51 with the beam's excess p_u E (T'_sun - T_sun)
// added), but the clear sky at 10 deg elevation 7.4 % -> 10.8 % low (tests/shading/
// test_sky_multiple_scattering.py): the light of orders >= 2 is not isotropic in fog either way.
// Every in-scatter sample at height h then adds sigma_s(h) Psi_ms(h, mu_s) E_sun to the
// single-scattered light (Hillaire's equation 10), T_view-attenuated as the single scattering is.
//
// The table: kHeights rows, h = 80 km u^2 (fine near the ground, where aerosol and fog live), x
// kCosines columns uniform in mu_s in [-1, 1], x the 48 node wavelengths (air_optics.h); bilinear
// in (h, mu_s), linear in wavelength. Each cell integrates kDirections directions (a midpoint
// product rule in cos(theta) and azimuth about the sun's vertical plane, mirrored across it) with
// kSteps steps each (t = L s^2), each step's attenuation integrated exactly for constant air within
// it (Hillaire's energy-conserving integration), the sun's column to the top by kSunColumnSteps / 3.
#pragma once

#include "refracta/shading/air_optics.h"

#include <cstddef>
#include <vector>

namespace refracta {

class MultipleScattering {
 public:
  static constexpr int kHeights = 32, kCosines = 32;
  static constexpr int kZeniths = 8, kAzimuths = 4;  // kAzimuths over [0, pi], mirrored: 64 directions
  static constexpr int kSteps = 24;
  static constexpr int kOrders = 12;  // scattering orders 2 .. kOrders + 1 integrated explicitly
  static constexpr int kHigherZeniths = 8, kHigherAzimuths = 2, kHigherSteps = 12;  // orders >= 3

  // No multiple scattering (Psi_ms = 0 everywhere).
  MultipleScattering() = default;
  // The table for this composition of the air over a Lambertian ground of `ground_albedo`.
  MultipleScattering(const air_optics::AirComposition& air, double ground_albedo);

  bool enabled() const { return !table_.empty(); }
  // Psi_ms [1/sr] at height h [m] above sea level, sun zenith cosine mu_s, node wavelength w.
  // values: kNodes doubles (every node).
  void at_nodes(double height, double mu_s, double* values) const;
  // At one wavelength [nm] (linear between nodes; 0 outside [360, 830]).
  double at(double height, double mu_s, double lambda_nm) const;

 private:
  struct Cell {
    size_t offset;     // of the (height, cosine) corner below, node 0
    double weight[4];  // bilinear: (h0, c0), (h0, c1), (h1, c0), (h1, c1)
  };
  static Cell cell(double height, double mu_s);
  static double node(const std::vector<double>& table, const Cell& c, int w);

  std::vector<double> table_;  // [height][cosine][node]
};

}  // namespace refracta
