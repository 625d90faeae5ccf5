// The synthesis of optical turbulence (turbulence.h's grid): a periodic random pattern delta_n(x)
// with the von Karman spectrum, synthesised by FFT on an N^3 grid and prefiltered into the
// coefficients of a cubic B-spline that passes through the synthesised samples.
//
// The spectrum (Andrews & Phillips, "Laser Beam Propagation through Random Media", 2nd ed. 2005,
// eq. 3.27 with 3.20):
//   Phi_n(kappa) = 0.033005 C_n^2 (kappa^2 + kappa0^2)^(-11/6) exp(-kappa^2 / kappa_m^2),
//   kappa0 = 2 pi / L0, kappa_m = 5.92 / l0.
// The pattern: white noise filtered by sqrt(Phi_n dkappa^3) on the N^3 lattice of wavenumbers
// 2 pi i / (N spacing) (the k = 0 mode removed; the lowest modes carry Phi averaged over their
// cell), divided by the cubic B-spline's response so that the spline through the coefficients
// passes through the synthesised samples (Unser, Aldroubi & Eden 1991, "Fast B-spline
// transforms", eq. 10); synthesised for C_n^2 = 1 and scaled by sqrt(cn2) in the layer.
// Units: metres, seconds; C_n^2 in m^(-2/3); wavenumbers in rad/m.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/media/turbulence.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// 5 / (18 pi Gamma(1/3)) = 0.033005: makes D_n(r) = C_n^2 r^(2/3) in the inertial range.
double von_karman_constant();
// kappa_m = 5.92 / l0: the Tatarskii inner-scale cutoff in Andrews & Phillips' convention (eq. 3.27).
constexpr double kInnerScaleFactor = 5.92;

// The von Karman spectrum with a Gaussian inner cutoff, Phi_n(kappa) [m^3]:
// 0.033005 C_n^2 (kappa^2 + kappa0^2)^(-11/6) exp(-kappa^2 / kappa_m^2), kappa0 = 2 pi / L0,
// kappa_m = 5.92 / l0 (Andrews & Phillips 2005, eq. 3.27). kappa [rad/m] (array); inner_scale
// l0 = 0: no cutoff; outer_scale L0 = inf: Kolmogorov at small kappa (infinite at kappa = 0).
double von_karman_spectrum(double kappa, double cn2, double inner_scale, double outer_scale);
// von_karman_spectrum for a caller's numbers: throws std::invalid_argument naming the first bad one
// (kappa finite and >= 0, cn2 finite and >= 0, inner_scale finite and >= 0, outer_scale > 0).
double checked_von_karman_spectrum(double kappa, double cn2, double inner_scale, double outer_scale);

// The lattice turned about the vertical by atan(1 / golden ratio) (31.7 deg): a periodic tile
// repeats along a ray running along a lattice axis (its modes then add up coherently, the variance
// growing as L^2 beyond the tile); a level ray along x or z -- the usual lines of sight -- then
// crosses the tile with slope 1 / golden ratio, whose rational approximations (Fibonacci ratios)
// are the worst of any number (Hurwitz), so it comes back near an earlier crossing as rarely as a
// straight line can. [deg] (31.717...; its radians are atan(1 / golden ratio) exactly)
double default_turbulence_yaw_deg();

// The settings of a turbulence pattern and its placement (refracta.Turbulence), with the hot road's
// defaults (defined once, here, with their reasons). validate() reports every bad value at once, and
// a grid too large for max_bytes. Pickles through its fields.
struct TurbulenceSettings {
  // C_n^2 [m^(-2/3)] at the ground, >= 0 (the pattern is weighted by E(h): C_n^2(h) = cn2 E(h)^2).
  // 1e-10: within centimetres of sun-heated asphalt (C_n^2 ~ 1e-13..1e-12 at 1-2 m in daytime,
  // Andrews & Phillips 2005 ch. 12, rising as h^(-4/3) toward the ground in free convection,
  // Wyngaard et al. 1971).
  double cn2 = 1e-10;
  // The von Karman outer scale L0 [m]; inf: the periodic tile is the outer scale, which keeps the
  // widest inertial range.
  double outer_scale = std::numeric_limits<double>::infinity();
  // The inner scale l0 [m]: the Gaussian cutoff kappa_m = 5.92 / l0; 5 mm near hot ground.
  double inner_scale = 0.005;
  int64_t seed = 0;  // the random pattern (same seed and grid, same pattern)
  // (u, w) [m/s] along x and z: the pattern at time t is shifted by (u t, 0, w t) (Taylor's frozen
  // flow). (0, 2): a light breeze across the examples' line of sight (+x).
  std::array<double, 2> wind = {0.0, 2.0};
  // The grid's cell [m], in [1e-6, 1e4]: the renderer steps half a cell through the layer, so a
  // pixel's cost grows as path length / spacing (benchmarks/bench_realism.py).
  double spacing = 0.05;
  // N (the grid is N^3, one period N * spacing wide), or size [m] (N = ceil(size / spacing)); unset
  // both: 256, whose inertial range spans over a decade (x16 within 15 %), where 128 reaches x8.
  std::optional<int64_t> cells;
  std::optional<double> size;  // [m] the tile, cells = ceil(size / spacing) (None: from cells)
  // The height envelope E(h) = e^(-h/depth) [m]; unset (None): uniform. 0.1 m: the examples' surface layer.
  std::optional<double> depth = 0.1;
  // The largest FFT work arrays allowed [bytes] (a grid needing more is refused); unset (None): half
  // this machine's memory (inf: no limit).
  std::optional<double> max_bytes;
  // The lattice's turn about the vertical [deg], as every angle users give (default_turbulence_yaw_deg());
  // turbulence_layer turns it into the layer's radians, the one conversion.
  double yaw_deg = default_turbulence_yaw_deg();

  // N: cells, or from size and spacing, or 256.
  int cell_count() const;
  // Throws std::invalid_argument listing every bad field, and a grid too large for max_bytes.
  void validate() const;
};

// Bytes the synthesis of a cells^3 grid holds at its peak, a bound: the float32 noise (whose buffer
// then becomes the coefficients), its complex64 half spectrum, a copy of the coefficients, and
// 16 MB of tables and per-thread rows.
double turbulence_memory_needed(int64_t cells);

// The variance sigma^2 [m^(2/3) for C_n^2 = 1] of each Fourier mode of the samples on the lattice
// of a grid: Phi_n(|kappa|) dkappa^3; the lowest modes (every index within 4 of 0) Phi_n averaged
// over their cell of wavenumber space (8^3 midpoints: the spectrum varies by orders of magnitude
// across those cells, and the point value loses much of their variance -- when introduced, the
// ensemble D at a quarter of the tile rose from 0.90 to 0.95 C_n^2 r^(2/3) at N = 256); 0 at kappa = 0.
// On the vertical axis (i = k = 0, y being up) the modes would be layers as wide as the scene,
// which the wind never moves: each seed added its own lasting change to the mean profile n(h) (rms
// 5e-6 over 4 km x 4 km at the default 256^3 of 5 cm; the hot road's surface gradient moved by
// -13 % to +42 % from seed to seed) and a vertical tilt that grew as L^2 along every level path (5x
// the horizontal one at 300 m, 12x at 600 m; a trial of 7 December). Their cells hold the
// horizontal scales beyond the lattice's period, which it cannot show; their variance goes to the
// four modes beside them, (+-1, j, 0) and (0, j, +-1), whose horizontal scale is the period: each
// vertical wavenumber keeps its variance (the pattern's vertical spectrum, and so D_n for vertical
// separations, are unchanged; for horizontal ones D_n rises toward half a tile), and no mode is
// constant along a level path at an irrational slope to the lattice (the default yaw's x and z; at
// yaw 0 the (0, j, +-1) modes are constant along x, and tilt still grows as L^2 there).
class TurbulenceSpectrum {
 public:
  TurbulenceSpectrum(int64_t cells, double spacing, double inner_scale, double outer_scale);
  // At signed lattice indices (i, j, k).
  double mode_variance(int64_t i, int64_t j, int64_t k) const;
  // At (i, j[a], k[b]) for every a and b: a (j.size(), k.size()) matrix.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mode_variances(
      int64_t i, const std::vector<int64_t>& j, const std::vector<int64_t>& k) const;
  int64_t cells() const { return cells_; }

  static constexpr int kCellAveraged = 4;
  static constexpr int kCellSamples = 8;

 private:
  // Phi_n over the mode's cell (cell-averaged near 0), before the layers' variance is moved.
  double cell_variance(int64_t i, int64_t j, int64_t k) const;
  int64_t cells_;
  double dk_, inner_scale_, outer_scale_;
  std::vector<double> cell_table_;  // (2 kCellAveraged + 1)^3
};

// The spline coefficients of the pattern for C_n^2 = 1 [m^(1/3)], an N^3 grid of `spacing`. The
// white noise is drawn per slab of constant x index from refracta::Rng(seed, slab), so the
// pattern does not depend on the thread count. Polls `control` (Ctrl-C).
std::shared_ptr<TurbulenceGrid> synthesise_turbulence(const TurbulenceSettings& settings, WorkControl& control);

// The layer the fields add: the grid scaled by sqrt(cn2), carried by the wind to time t [s].
Turbulence turbulence_layer(const TurbulenceSettings& settings, std::shared_ptr<const TurbulenceGrid> grid,
                            double time);

}  // namespace refracta
