// Waves larger than a pixel: a wind sea as a displaced surface (issue 19 section 2), for the close
// sea that a Beckmann roughness alone (shading/water_surface.h) renders as a flat, blurred mirror.
// Used through `refracta.OceanWaves(...)` and `Scene.add_sea(...)` (bindings/bind_ocean.cpp).
//
// The height field (Tessendorf 2001, "Simulating Ocean Water", SIGGRAPH course notes, sections
// 3.3-3.4): on a periodic N x N patch of side L, nodes x = (i, j) L/N,
//   h(x, t) = sum_k h~(k, t) exp(i k.x),   k = 2 pi (m, n) / L,  -N/2 < m, n < N/2,  k != 0,
//   h~(k, t) = [h0(k) exp(i w t) + conj(h0(-k)) exp(-i w t)] / sqrt(2),   w = sqrt(g k) (deep water),
//   h0(k) = (xi_r + i xi_i) sqrt(Phi'(k) dk^2 / 2),   xi ~ N(0, 1),  dk = 2 pi / L,
// where the term h0(k) exp(i (k.x + w t)) travels toward -k: the sea runs downwind, Phi'(k) =
// 2 Phi(k) for k.w^ < 0 (upwind k: a wave travelling downwind) and 0 otherwise (Tessendorf's
// filter of the waves against the wind), so each mode is one travelling wave, not a partly standing
// one, and h is real (h~(-k) = conj h~(k)) with E|h~(k)|^2 = Phi(k) dk^2: the field's variance is
// the spectrum summed over the patch's modes (Tessendorf's h~(k, t), his factor 1/sqrt(2) put on
// the sum of the two travelling halves and his h0 holding 2 Phi on the upwind half-plane only, so
// that Phi is the two-sided spectrum whose integral is the variance). Slopes by the same inverse
// FFT of i k h~ (his gradient): exact on the nodes, not finite differences. Synthesised by Eigen's
// FFT (kissfft) rows then columns.
//
// The spectrum: Phillips 1957 as Tessendorf writes it (section 3.4),
//   Phi(k) = A exp(-1 / (k L_w)^2) / k^4 |k^.w^|^2,   L_w = U^2 / g,
// U [m/s] the wind speed, w^ its horizontal direction. Its integral over the plane is
// A pi L_w^2 / 2 (substitute s = 1/k^2), and A is fixed by the significant wave height of a fully
// developed sea, Pierson & Moskowitz 1964: H_s = 4 sigma_h ~ 0.21 U^2 / g, so
//   A = 2 (0.21 / 4)^2 / pi = 1.755e-3 (dimensionless, the same for every wind).
// U is taken as the Water material's wind 12.5 m above the sea (Cox-Munk's height; Pierson &
// Moskowitz's 19.5 m wind is ~3 % stronger in a neutral log profile: H_s ~6 % low, left so).
// The small-wave cutoff is the grid's: modes beyond the patch's Nyquist wavenumber pi N / L are
// not synthesised (Tessendorf's exp(-k^2 l^2) damping is not used), and the Nyquist row and
// column and k = 0 carry nothing (i k h~ would not be Hermitian there). The slopes of the waves
// shorter than two cells belong to the microfacets: Water(resolved_slope_variance=...) keeps
// Cox & Munk's total minus what the mesh resolves. The large-wave cutoff is the patch: waves
// longer than L are missing (k Phi(k) peaks at wavelength 2 pi L_w sqrt(3/2): 20 m at 5 m/s, 78 m at 10).
// Model limits (a trial against Pierson-Moskowitz and Cox-Munk): in frequency this spectrum is
// PM's form with beta = 1 (PM: 0.74) and a tail 36 % higher, so at equal U its H_s is PM's but its
// peak period 7 % shorter (0.946 g/U against 0.877); the cos^2 spreading puts 3/4 of the resolved
// slope variance along the wind, where Cox-Munk measured 55 % (glitter seen downwind ~10 % narrower).
// A patch holding under 80 % of the variance warns (patch_caveat).
// Left out: choppy (horizontal) displacement, JONSWAP, swell, foam.
//
// Deterministic from the seed: each mode's two normals come from a stream named by its signed
// integer wavenumber (m, n), so a finer grid (resolution) keeps the longer waves and adds shorter
// ones, and a larger time moves the same sea.
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/sampling.h"  // Vec2d
#include "refracta/scene/embree_scene.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

struct OceanWavesParameters {
  // [m/s] 12.5 m above the sea, in (0, kMaxWindSpeed]; no default here: the binding gives the
  // Water material's (shading/ sits above scene/).
  double wind_speed = std::numeric_limits<double>::quiet_NaN();
  Vec2d wind_direction{1.0, 0.0};  // horizontal (x, z), any non-zero length (normalised)
  // [m] The patch's side. 100 m holds the spectral peak (20 m at 5 m/s, 78 m at 10 m/s) and,
  // at 256 nodes, resolves waves down to 0.78 m (two cells of 0.39 m).
  double patch_size = 100.0;
  int resolution = 256;  // nodes along each side: a power of two in [kMinResolution, kMaxResolution]
  uint64_t seed = 0;
  double time = 0.0;  // [s] the waves' phase (deep-water dispersion): animation
};

// A wind sea's waves on a periodic square patch (scene/ocean_waves.h): a height field synthesised
// by FFT from the Phillips spectrum, as Tessendorf 2001 ("Simulating Ocean Water") does,
//
//     Phi(k) = A exp(-1 / (k L_w)^2) / k^4 |k^.w^|^2 [m^4],   L_w = wind_speed^2 / g,
//
// with A = 2 (0.21 / 4)^2 / pi = 1.755e-3 fixed by the significant wave height of a fully developed
// sea, H_s = 4 sigma_h = 0.21 U^2 / g (Pierson & Moskowitz 1964; Phillips 1957 for the k^-4 form).
// Each mode is a complex normal with E|h~(k)|^2 = Phi(k) dk^2 (dk = 2 pi / patch_size), Hermitian
// so the field is real; slopes by the FFT of i k h~ (exact on the nodes). Modes run up to the
// patch's Nyquist wavenumber pi resolution / patch_size (shorter waves are the Water material's
// microfacets) and down to 2 pi / patch_size (longer waves are missing). Deterministic from seed
// (each mode's numbers depend only on seed and its integer wavenumber, so a finer resolution keeps
// the long waves); time [s] moves the waves by deep-water dispersion w = sqrt(g k), every one of
// them downwind. A patch too small for the wind warns (its longer waves missing: patch_size of
// 10 U^2/g keeps ~92 % of the sea's variance). No choppy displacement.
//
// wind_speed [m/s] in (0, 30] (12.5 m above the sea, as Water's); wind_direction (x, z) horizontal,
// any non-zero length; patch_size [m] in [0.01, 1e7]; resolution a power of two in [8, 1024]. Arrays are
// indexed [j, i] at node x = i * spacing, z = j * spacing (rows along z).
class OceanWaves {
 public:
  static constexpr double kGravity = 9.80665;  // [m/s^2] standard gravity
  static constexpr double kMaxWindSpeed = 30.0;  // [m/s] as Cox-Munk's range (shading/water.h)
  // 8 nodes: the least that holds a wave; 1024: three N x N complex arrays of 16 MB during synthesis.
  static constexpr int kMinResolution = 8, kMaxResolution = 1024;
  // A patch holds gravity waves, which Phillips' spectrum describes, down to the capillary
  // crossover (1.7 cm); the largest is the scene's reach.
  static constexpr double kMinPatchSize = 0.01, kMaxPatchSize = kSceneReach;
  // Pierson-Moskowitz: H_s = kSignificantHeight U^2 / g for a fully developed sea.
  static constexpr double kSignificantHeight = 0.21;
  // Phillips' A fixed by Pierson-Moskowitz: A pi L_w^2 / 2 = (H_s / 4)^2.
  static constexpr double kPhillipsA = 2.0 * (kSignificantHeight / 4.0) * (kSignificantHeight / 4.0) / kPi;

  // Validates every parameter (std::invalid_argument naming each bad one) and synthesises.
  explicit OceanWaves(const OceanWavesParameters& parameters);

  const OceanWavesParameters& parameters() const { return parameters_; }
  double wind_speed() const { return parameters_.wind_speed; }  // [m/s]
  double patch_size() const { return parameters_.patch_size; }  // [m]
  int resolution() const { return parameters_.resolution; }
  uint64_t seed() const { return parameters_.seed; }
  double time() const { return parameters_.time; }  // [s]
  double spacing() const { return parameters_.patch_size / parameters_.resolution; }  // [m] between nodes
  Vec2d wind_direction() const { return wind_; }                                     // unit
  double wind_length() const;            // L_w = U^2 / g [m]
  double significant_wave_height() const;  // Pierson-Moskowitz H_s [m]

  // Phi(k) [m^4] at a horizontal wavenumber (kx, kz) [rad/m]; 0 at k = 0.
  double spectrum(const Vec2d& k) const;
  // The field's expected variances: sum of Phi dk^2 (and of k^2 Phi dk^2) over the synthesised
  // modes [m^2] and [-]. The spectrum's whole integral, (H_s / 4)^2, is spectrum_height_variance().
  double expected_height_variance() const { return expected_height_variance_; }
  double expected_slope_variance() const { return expected_slope_variance_; }
  double spectrum_height_variance() const;
  // This realisation's variances over the patch's nodes (mean 0 by construction: k = 0 is empty).
  double height_variance() const { return height_variance_; }
  double slope_variance() const { return slope_variance_; }  // mean of (dh/dx)^2 + (dh/dz)^2

  // At node (i, j), x = i spacing, z = j spacing, any integers (periodic): h [m] and (dh/dx, dh/dz).
  double height(long i, long j) const { return height_[index(i, j)]; }
  // Every node's height [m] (resolution^2, row j then column i) and slopes (dh/dx, dh/dz) interleaved.
  const std::vector<double>& heights() const { return height_; }
  std::vector<double> slopes() const;
  // "OceanWaves(wind_speed=..., ...)": the parameters as Python's constructor takes them.
  std::string describe() const;
  // Why the patch misrepresents a fully developed sea, if it does: it holds under kLeastHeldVariance
  // of the height variance of the spectrum's waves its grid resolves, those longer than patch_size
  // missing (a trial: the default 100 m patch at 20 m/s, H_s 4.4 m instead of 8.6). Bindings warn.
  std::optional<std::string> patch_caveat() const;
  static constexpr double kLeastHeldVariance = 0.8;
  Vec2d slope(long i, long j) const {
    const size_t n = index(i, j);
    return {slope_x_[n], slope_z_[n]};
  }

 private:
  size_t index(long i, long j) const {
    const long n = parameters_.resolution;
    return size_t(((j % n) + n) % n) * size_t(n) + size_t(((i % n) + n) % n);
  }
  OceanWavesParameters parameters_;
  Vec2d wind_;
  std::vector<double> height_, slope_x_, slope_z_;  // row j (z), column i (x)
  double expected_height_variance_ = 0.0, expected_slope_variance_ = 0.0;
  double height_variance_ = 0.0, slope_variance_ = 0.0;
};

// Where a sea's displaced surface goes (Scene.add_sea), in two levels of detail around `centre`
// (the camera's foot):
// - fine: the waves tiled on a square grid of the patch's nodes out to detail_radius; over its
//   outer kFadeFraction (a smoothstep in the distance from centre) they blend into
// - coarse: the same sea at a quarter of the resolution (OceanWaves' per-wavenumber streams make it
//   exactly the fine field's longer modes: a low-pass, not a subsample), on nodes kCoarseStep
//   times apart, out to kCoarseRadius detail_radius, fading to 0 over its outer kFadeFraction;
// - beyond, the flat plane y = height out to the square of side `size` centred on the origin (as
//   Scene.add_ground), in rings around the grids' square.
// The fine grid's border lies on coarse nodes and there equals the coarse field interpolated
// linearly along the coarse triangles' edges, and the coarse border is flat: no crack. Each level's
// waves shorter than two of its cells are left to the microfacets (Scene.add_sea gives every band
// the Water whose resolved_slope_variance is what its normals show): the statistical roughness
// grows with distance as the resolved slopes fall. Without a coarse level (resolution < 32) the
// fine waves fade to the flat plane directly.
struct SeaLayout {
  double height = 0.0;         // [m] the mean sea level
  double size = 2.0e5;         // [m] the flat sea's side: 100 km each way reaches past a 2 m eye's horizon (5 km) and a ship's
  // [m] Where the fine waves end. From a 2 m eye (640 px over 40 deg) a 0.39 m cell is a pixel tall
  // at 27 m; beyond 50 m the coarse level's 1.56 m cells take over (a pixel at 55 m), out to 200 m.
  double detail_radius = 50.0;
  Vec2d centre{0.0, 0.0};      // [m] (x, z) of the detail's centre
};

struct SeaMeshes {
  // Per level (fine, then coarse when present) kFadeBands + 1 displaced meshes (some may be
  // empty): the level's full waves, then rings of its fade outward; vertex normals from the
  // field's slopes (with the blend's and fade's gradients).
  std::vector<Mesh> bands;
  // Each band's mean-square slope as its shading normals show it, (n_x^2 + n_z^2) / n_y^2 averaged
  // over its triangles' vertices (a level's triangles all have the same projected area).
  std::vector<double> band_slope_variance;
  Mesh flat;  // the far plane, with the grids' flat corners
};

// A level's waves fade over the outer 30 % of its radius in 3 rings, each shaded with the slope
// variance it shows (the smoothstep's weight varies by ~0.3 across a ring).
constexpr double kFadeFraction = 0.3;
constexpr int kFadeBands = 3;
// The coarse level: nodes 4 fine cells apart (a quarter of the resolution), out to 4 detail_radius
// (where its cells are as tall on screen as the fine ones at detail_radius).
constexpr long kCoarseStep = 4;
constexpr double kCoarseRadius = 4.0;
// At most 2^20 cells per level (2M triangles, ~150 MB with Embree's copy): detail_radius / spacing <= 508.
constexpr long kMaxSeaCells = 1L << 20;

// The meshes of a sea; validates the layout (std::invalid_argument naming height, size,
// detail_radius or centre).
SeaMeshes sea_meshes(const OceanWaves& waves, const SeaLayout& layout);

}  // namespace refracta
