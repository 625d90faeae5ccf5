// FFT synthesis of a turbulence grid (turbulence_synthesis.h), on Eigen's FFT module (kissfft).
#include "refracta/media/turbulence_synthesis.h"

#include "refracta/core/memory.h"
#include "refracta/core/math.h"
#include "refracta/core/rng.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>

namespace refracta {

namespace {

using Complex = std::complex<float>;

constexpr int64_t kDefaultCells = 256;
constexpr int64_t kMinCells = 8;
// Far beyond any memory (65536^3 cells need ~5e15 bytes: the memory check refuses them), and within
// an int with room: a larger count would wrap in the int the grid is indexed by.
constexpr int64_t kMaxCells = 65536;

// Lattice index of FFT bin i of n: 0..n/2-1, then -n/2..-1 (numpy.fft.fftfreq(n, 1/n)).
int64_t signed_index(int64_t i, int64_t n) { return i < (n + 1) / 2 ? i : i - n; }

// H(omega) = (4 + 2 cos omega) / 6 at omega = 2 pi index / n: the spectrum of the cubic B-spline's
// samples (Unser et al. 1991), by which the coefficients' spectrum is divided.
double spline_response(int64_t index, int64_t n) { return (4.0 + 2.0 * std::cos(2.0 * kPi * double(index) / double(n))) / 6.0; }

// A standard normal pair from one stream (Box-Muller).
std::pair<double, double> normal_pair(Rng& rng) {
  const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();  // u1 in (0, 1]
  const double r = std::sqrt(-2.0 * std::log(u1));
  return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2)};
}

}  // namespace

double von_karman_constant() { return 5.0 / (18.0 * kPi * std::tgamma(1.0 / 3.0)); }

double default_turbulence_yaw_deg() { return radians_to_degrees(std::atan(0.5 * (std::sqrt(5.0) - 1.0))); }

double von_karman_spectrum(double kappa, double cn2, double inner_scale, double outer_scale) {
  const double kappa0 = std::isinf(outer_scale) ? 0.0 : 2.0 * kPi / outer_scale;
  double phi = von_karman_constant() * cn2 * std::pow(kappa * kappa + kappa0 * kappa0, -11.0 / 6.0);
  if (inner_scale > 0.0) {
    const double x = kappa * inner_scale / kInnerScaleFactor;
    phi *= std::exp(-x * x);
  }
  return phi;
}

double checked_von_karman_spectrum(double kappa, double cn2, double inner_scale, double outer_scale) {
  // A negative C_n^2 made a negative spectrum; NaN and negative scales passed through.
  if (!(kappa >= 0.0 && std::isfinite(kappa))) throw_invalid("von_karman_spectrum: kappa must be finite and >= 0 (got ", kappa, ")");
  if (!(cn2 >= 0.0 && std::isfinite(cn2))) throw_invalid("von_karman_spectrum: cn2 must be finite and >= 0 (got ", cn2, ")");
  if (!(inner_scale >= 0.0 && std::isfinite(inner_scale))) {
    throw_invalid("von_karman_spectrum: inner_scale must be finite and >= 0 m (got ", inner_scale, ")");
  }
  if (!(outer_scale > 0.0)) throw_invalid("von_karman_spectrum: outer_scale must be > 0 m (inf: none; got ", outer_scale, ")");
  return von_karman_spectrum(kappa, cn2, inner_scale, outer_scale);
}

int TurbulenceSettings::cell_count() const {
  if (cells) return int(*cells);
  if (size) return int(std::ceil(*size / spacing - 1e-9));
  return int(kDefaultCells);
}

namespace {
constexpr double kStrongestCn2 = 1.0;  // [m^(-2/3)]
constexpr double kFinestSpacing = 1e-6, kCoarsestSpacing = 1e4;  // [m]
}  // namespace

void TurbulenceSettings::validate() const {
  Problems problems("Turbulence");
  // The strongest turbulence measured over hot ground is ~1e-10 m^(-2/3). Up to 1: the unit
  // realisation whose statistics are checked (n swings by ~1 then); 1e300 was accepted.
  problems.check(cn2 >= 0.0 && cn2 <= kStrongestCn2, "cn2 must be in [0, ", kStrongestCn2, "] m^(-2/3) (got ", cn2, ")");
  // The spectrum lives between the scales: an inner scale at or beyond the outer one (or beyond
  // 10 km, past any tile) left an all-zero pattern without a word (a trial).
  problems.check(inner_scale > 0.0 && inner_scale <= kCoarsestSpacing, "inner_scale must be in (0, ", kCoarsestSpacing,
                 "] m (got ", inner_scale, ")");
  problems.check(outer_scale > inner_scale || !(inner_scale > 0.0),
                 "outer_scale must exceed inner_scale, or be inf (got outer_scale ", outer_scale, ", inner_scale ",
                 inner_scale, ")");
  problems.check(seed >= 0, "seed must be a whole number >= 0 (got ", seed, ")");
  problems.check(std::isfinite(wind[0]) && std::isfinite(wind[1]), "wind must be (u, w) [m/s] along x and z, finite (got (",
                 wind[0], ", ", wind[1], "))");
  // A cell from a micrometre (far below any inner scale of air) to 10 km (tiles beyond the scene's
  // reach); 1e-300 and 1e300 overflowed the synthesis ("coefficients must be finite").
  problems.check(spacing >= kFinestSpacing && spacing <= kCoarsestSpacing, "spacing must be in [", kFinestSpacing, ", ",
                 kCoarsestSpacing, "] m (got ", spacing, ")");
  // From a micrometre (1e-300 gave gradients of 1e293) to the scene's reach.
  if (depth) {
    problems.check(*depth >= kFinestSpacing && *depth <= kSceneReach, "depth must be in [", kFinestSpacing, ", ",
                   kSceneReach, "] m or None (uniform) (got ", *depth, ")");
  }
  if (cells && size) {
    problems.add("give cells or size, not both (got cells=", *cells, ", size=", *size, ")");
  } else if (cells) {
    problems.check(*cells >= kMinCells && *cells <= kMaxCells, "cells must be a whole number in [", kMinCells, ", ",
                   kMaxCells, "] (got ", *cells, ")");
  } else if (size) {
    problems.check(*size > 0.0 && std::isfinite(*size), "size must be > 0 m and finite (got ", *size, ")");
    problems.check(!(*size / spacing > double(kMaxCells)), "size / spacing must be at most ", kMaxCells,
                   " cells (got size=", *size, ", spacing=", spacing, ")");
    // A smaller tile would be widened to the fewest cells: the size asked for would not be the tile's.
    problems.check(!(std::ceil(*size / spacing - 1e-9) < double(kMinCells)), "size / spacing must be at least ",
                   kMinCells, " cells (got size=", *size, ", spacing=", spacing, ")");
  }
  if (max_bytes) problems.check(*max_bytes > 0.0, "max_bytes must be > 0 (math.inf: no limit; got ", *max_bytes, ")");
  // Beyond a turn or so an angle only loses digits (1e300 deg has none left below 360).
  problems.check(std::abs(yaw_deg) <= 360.0, "yaw_deg must be in [-360, 360] (got ", yaw_deg, ")");
  problems.throw_if_any();
  // Refused before anything is allocated. Half of this machine by default (no limit where its
  // memory cannot be read).
  const int n = cell_count();
  const double needed = turbulence_memory_needed(n);
  const double limit = max_bytes ? *max_bytes : physical_memory_bytes() / 2.0;
  if (limit > 0.0 && needed > limit) {
    throw_invalid("Turbulence: a ", n, "^3 grid needs about ", whole_bytes(needed), " bytes (", readable_bytes(needed),
                  ") for its FFT work arrays, more than the limit of ", whole_bytes(limit), " bytes (",
                  readable_bytes(limit), max_bytes ? "" : ", half of this machine",
                  "); use fewer cells or raise max_bytes");
  }
}

double turbulence_memory_needed(int64_t cells) {
  if (cells < kMinCells) throw_invalid("memory_needed: cells must be >= ", kMinCells, " (got ", cells, ")");
  const double n = double(cells);
  const int64_t half = cells / 2 + 1;  // the half spectrum's length along z (whole division)
  return 4.0 * n * n * n + 8.0 * n * n * double(half) + 4.0 * n * n * n + 16e6;
}

TurbulenceSpectrum::TurbulenceSpectrum(int64_t cells, double spacing, double inner_scale, double outer_scale)
    : cells_(cells), dk_(2.0 * kPi / (double(cells) * spacing)), inner_scale_(inner_scale), outer_scale_(outer_scale) {
  constexpr int m = kCellAveraged, s = kCellSamples, w = 2 * m + 1;
  cell_table_.assign(size_t(w) * w * w, 0.0);
  double offsets[s];
  for (int q = 0; q < s; ++q) offsets[q] = (q + 0.5) / s - 0.5;
  const double volume = dk_ * dk_ * dk_;
  for (int a = 0; a < w; ++a) {
    for (int b = 0; b < w; ++b) {
      for (int c = 0; c < w; ++c) {
        if (a == m && b == m && c == m) continue;  // the mean: no structure
        double sum = 0.0;
        for (int qa = 0; qa < s; ++qa) {
          const double x = a - m + offsets[qa];
          for (int qb = 0; qb < s; ++qb) {
            const double y = b - m + offsets[qb];
            for (int qc = 0; qc < s; ++qc) {
              const double z = c - m + offsets[qc];
              sum += von_karman_spectrum(dk_ * std::sqrt(x * x + y * y + z * z), 1.0, inner_scale_, outer_scale_);
            }
          }
        }
        cell_table_[(size_t(a) * w + b) * w + c] = sum / (s * s * s) * volume;
      }
    }
  }
}

double TurbulenceSpectrum::mode_variance(int64_t i, int64_t j, int64_t k) const {
  // The horizontal layers' variance goes to their four horizontal neighbours (the header says why).
  if (i == 0 && k == 0) return 0.0;
  const double own = cell_variance(i, j, k);
  return std::abs(i) + std::abs(k) == 1 ? own + 0.25 * cell_variance(0, j, 0) : own;
}

double TurbulenceSpectrum::cell_variance(int64_t i, int64_t j, int64_t k) const {
  constexpr int m = kCellAveraged, w = 2 * m + 1;
  if (std::abs(i) <= m && std::abs(j) <= m && std::abs(k) <= m) {
    return cell_table_[(size_t(i + m) * w + size_t(j + m)) * w + size_t(k + m)];
  }
  return von_karman_spectrum(dk_ * std::sqrt(double(i * i + j * j + k * k)), 1.0, inner_scale_, outer_scale_) *
         dk_ * dk_ * dk_;
}

Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> TurbulenceSpectrum::mode_variances(
    int64_t i, const std::vector<int64_t>& j, const std::vector<int64_t>& k) const {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> out(j.size(), k.size());
  for (size_t a = 0; a < j.size(); ++a) {
    for (size_t b = 0; b < k.size(); ++b) out(Eigen::Index(a), Eigen::Index(b)) = mode_variance(i, j[a], k[b]);
  }
  return out;
}

std::shared_ptr<TurbulenceGrid> synthesise_turbulence(const TurbulenceSettings& settings, WorkControl& control) {
  settings.validate();
  const int64_t n = settings.cell_count(), h = n / 2 + 1;
  const TurbulenceSpectrum spectrum(n, settings.spacing, settings.inner_scale, settings.outer_scale);
  std::vector<float> field(size_t(n * n * n));
  std::vector<Complex> half(size_t(n * n * h));  // (i, j, kz): the half spectrum
  auto at = [&](int64_t i, int64_t j, int64_t kz) -> Complex& { return half[size_t((i * n + j) * h + kz)]; };
  control.total = 3 * n;  // three passes over slabs
  control.done = 0;
  auto stage = [&](const auto& body) {
    WorkControl pass;
    parallel_for_each(n, 1, pass, body);
    control.done += n;
  };

  // White noise, slab by slab (x index i); its transform along z (real, half) and along y.
  stage([&](int64_t i) {
    Eigen::FFT<float> fft;
    fft.SetFlag(Eigen::FFT<float>::HalfSpectrum);
    Rng rng(uint64_t(settings.seed), uint64_t(i));
    float* slab = field.data() + size_t(i * n * n);
    for (int64_t q = 0; q < n * n; q += 2) {
      const auto [a, b] = normal_pair(rng);
      slab[q] = float(a);
      if (q + 1 < n * n) slab[q + 1] = float(b);
    }
    for (int64_t j = 0; j < n; ++j) fft.fwd(&at(i, j, 0), slab + j * n, n);
    std::vector<Complex> in(static_cast<size_t>(n)), out(static_cast<size_t>(n));
    for (int64_t kz = 0; kz < h; ++kz) {
      for (int64_t j = 0; j < n; ++j) in[size_t(j)] = at(i, j, kz);
      fft.fwd(out.data(), in.data(), n);
      for (int64_t j = 0; j < n; ++j) at(i, j, kz) = out[size_t(j)];
    }
  });
  // Along x: transform, filter by sqrt(N^3 sigma^2) (<|W_k|^2> = N^3 for the unnormalised
  // transform of unit white noise; Hermitian by construction) over the spline's response, back.
  stage([&](int64_t j) {
    Eigen::FFT<float> fft;
    std::vector<Complex> in(static_cast<size_t>(n)), out(static_cast<size_t>(n));
    const int64_t sj = signed_index(j, n);
    const double volume = double(n) * double(n) * double(n);
    for (int64_t kz = 0; kz < h; ++kz) {
      for (int64_t i = 0; i < n; ++i) in[size_t(i)] = at(i, j, kz);
      fft.fwd(out.data(), in.data(), n);
      const double response = spline_response(sj, n) * spline_response(kz, n);
      for (int64_t i = 0; i < n; ++i) {
        const int64_t si = signed_index(i, n);
        const double gain = std::sqrt(volume * spectrum.mode_variance(si, sj, kz)) / (spline_response(si, n) * response);
        out[size_t(i)] *= float(gain);
      }
      fft.inv(in.data(), out.data(), n);
      for (int64_t i = 0; i < n; ++i) at(i, j, kz) = in[size_t(i)];
    }
  });
  // Back along y and z, into the noise's buffer.
  stage([&](int64_t i) {
    Eigen::FFT<float> fft;
    fft.SetFlag(Eigen::FFT<float>::HalfSpectrum);
    std::vector<Complex> in(static_cast<size_t>(n)), out(static_cast<size_t>(n));
    for (int64_t kz = 0; kz < h; ++kz) {
      for (int64_t j = 0; j < n; ++j) in[size_t(j)] = at(i, j, kz);
      fft.inv(out.data(), in.data(), n);
      for (int64_t j = 0; j < n; ++j) at(i, j, kz) = out[size_t(j)];
    }
    float* slab = field.data() + size_t(i * n * n);
    for (int64_t j = 0; j < n; ++j) fft.inv(slab + j * n, &at(i, j, 0), n);
  });
  half = std::vector<Complex>();
  const int count = int(n);
  return std::make_shared<TurbulenceGrid>(std::move(field), std::array<int, 3>{count, count, count}, settings.spacing);
}

Turbulence turbulence_layer(const TurbulenceSettings& settings, std::shared_ptr<const TurbulenceGrid> grid, double time) {
  if (!grid) throw_invalid("Turbulence: no grid");
  // The settings' pattern only: another grid (16^3 under settings of 32^3) was taken as theirs.
  const int n = settings.cell_count();
  if (grid->shape() != std::array<int, 3>{n, n, n} || grid->spacing() != settings.spacing) {
    throw_invalid("Turbulence: the grid (", grid->shape()[0], "^3 cells of ", grid->spacing(),
                  " m) is not the settings' (", n, "^3 of ", settings.spacing, " m)");
  }
  if (!std::isfinite(time)) throw_invalid("Turbulence.at_time: t must be finite (got ", time, ")");
  if (!(std::isfinite(settings.wind[0] * time) && std::isfinite(settings.wind[1] * time))) {
    throw_invalid("Turbulence.at_time: the wind carries the pattern beyond any distance by t = ", time, " s");
  }
  Turbulence layer;
  layer.grid = std::move(grid);
  layer.scale = std::sqrt(settings.cn2);
  layer.depth = settings.depth ? *settings.depth : std::numeric_limits<double>::infinity();
  layer.place(Vec3d(settings.wind[0] * time, 0.0, settings.wind[1] * time), degrees_to_radians(settings.yaw_deg));
  return layer;
}

}  // namespace refracta
