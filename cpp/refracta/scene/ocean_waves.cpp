// The Tessendorf height field and the sea's meshes (ocean_waves.h).
#include "refracta/scene/ocean_waves.h"

#include "refracta/core/error.h"
#include "refracta/core/rng.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>

namespace refracta {

namespace {

using Complex = std::complex<double>;

// A standard normal pair from one stream (Box-Muller).
Vec2d normal_pair(Rng& rng) {
  const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();  // u1 in (0, 1]
  const double r = std::sqrt(-2.0 * std::log(u1));
  return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2)};
}

// The stream of mode (m, n): its signed wavenumber indices, so a mode keeps its numbers whatever N.
uint64_t mode_stream(long m, long n) { return (uint64_t(uint32_t(int32_t(m))) << 32) | uint64_t(uint32_t(int32_t(n))); }

// In-place unscaled inverse 2-D DFT of an N x N array (row j, column i): rows, then columns.
void inverse_fft_2d(std::vector<Complex>& a, int n) {
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  const size_t size = size_t(n);
  std::vector<Complex> in(size), out(size);
  for (int j = 0; j < n; ++j) {
    std::copy_n(a.begin() + long(j) * n, n, in.begin());
    fft.inv(out, in);
    std::copy_n(out.begin(), n, a.begin() + long(j) * n);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) in[size_t(j)] = a[size_t(j) * size_t(n) + size_t(i)];
    fft.inv(out, in);
    for (int j = 0; j < n; ++j) a[size_t(j) * size_t(n) + size_t(i)] = out[size_t(j)];
  }
}

double smoothstep_fade(double r, double r0, double r1, double* derivative) {
  if (r <= r0) return *derivative = 0.0, 1.0;
  if (r >= r1) return *derivative = 0.0, 0.0;
  const double s = (r - r0) / (r1 - r0);
  *derivative = -6.0 * s * (1.0 - s) / (r1 - r0);
  return 1.0 - s * s * (3.0 - 2.0 * s);
}

}  // namespace

OceanWaves::OceanWaves(const OceanWavesParameters& parameters) : parameters_(parameters) {
  // Every problem, then one exception.
  std::string problems;
  auto problem = [&](const std::string& message) { problems += (problems.empty() ? "" : "; ") + message; };
  const OceanWavesParameters& p = parameters;
  if (!(p.wind_speed > 0.0 && p.wind_speed <= kMaxWindSpeed)) {
    problem(concat("wind_speed must be in (0, ", kMaxWindSpeed, "] m/s (got ", p.wind_speed, ")"));
  }
  // Scaled by its largest component first: the norm of (1e200, 0) overflowed (a flat sea) and that
  // of (1e-170, 0) underflowed (refused as zero), where only the direction counts (a trial).
  const double largest = p.wind_direction.cwiseAbs().maxCoeff();
  if (!p.wind_direction.allFinite() || !(largest > 0.0)) {
    problem(concat("wind_direction must be a finite, non-zero (x, z) (got (", p.wind_direction.x(), ", ", p.wind_direction.y(), "))"));
  }
  if (!(p.patch_size >= kMinPatchSize && p.patch_size <= kMaxPatchSize)) {
    problem(concat("patch_size must be in [", kMinPatchSize, ", ", kMaxPatchSize, "] m (got ", p.patch_size, ")"));
  }
  const int n = p.resolution;
  if (n < kMinResolution || n > kMaxResolution || (n & (n - 1)) != 0) {
    problem(concat("resolution must be a power of two in [", kMinResolution, ", ", kMaxResolution, "] (got ", n, ")"));
  }
  // Each wave's phase is omega t: beyond ~1e9 s (32 years) its rounding (omega t x 1.1e-16, omega
  // up to ~10 rad/s) passes 1e-6 rad, and by 1e16 s the phases are noise: a different sea, not the
  // same sea later.
  constexpr double kLongestTime = 1e9;  // [s]
  if (!(std::abs(p.time) <= kLongestTime)) {
    problem(concat("time must be finite and within +-", kLongestTime, " s (got ", p.time, ")"));
  }
  if (!problems.empty()) throw_invalid("OceanWaves: ", problems);
  wind_ = (p.wind_direction / largest).normalized();

  // The modes: h~(k) and i k h~(k) (Tessendorf 2001, section 3.4).
  const size_t count = size_t(n) * size_t(n);
  const double dk = 2.0 * kPi / p.patch_size;
  std::vector<Complex> h(count), sx(count), sz(count);
  // Tessendorf's h0(k), mode (m, nn), for the waves that run downwind only: h0(k) exp(i w t)
  // carries a wave travelling toward -k, so h0 holds the spectrum of both halves (2 Phi) where
  // k points upwind and nothing where it points downwind. With both halves each mode was a partly
  // standing wave, half its energy running upwind (a trial: 48 % downwind). Tessendorf 2001, 3.4:
  // "waves moving opposite to the wind [may be] filtered out".
  auto h0 = [&](long m, long nn) {
    const Vec2d k(m * dk, nn * dk);
    if (!(k.dot(wind_) < 0.0)) return Complex(0.0);
    const double phi = 2.0 * spectrum(k);
    if (phi == 0.0) return Complex(0.0);
    Rng rng(p.seed, mode_stream(m, nn));
    const Vec2d xi = normal_pair(rng);
    return Complex(xi.x(), xi.y()) * std::sqrt(0.5 * phi * dk * dk);
  };
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const long m = a < n / 2 ? a : a - n, nn = b < n / 2 ? b : b - n;
      if (m == -n / 2 || nn == -n / 2 || (m == 0 && nn == 0)) continue;  // Nyquist and the mean: empty
      const Vec2d k(m * dk, nn * dk);
      const double phi = spectrum(k);
      expected_height_variance_ += phi * dk * dk;
      expected_slope_variance_ += k.squaredNorm() * phi * dk * dk;
      const double omega_t = std::sqrt(kGravity * k.norm()) * p.time;
      const Complex phase = std::polar(1.0, omega_t);
      const Complex mode = (h0(m, nn) * phase + std::conj(h0(-m, -nn)) * std::conj(phase)) / std::sqrt(2.0);
      const size_t at = size_t(b) * size_t(n) + size_t(a);
      h[at] = mode;
      sx[at] = Complex(0.0, k.x()) * mode;
      sz[at] = Complex(0.0, k.y()) * mode;
    }
  }

  // The field on the nodes: real by Hermitian symmetry (the imaginary parts are rounding).
  inverse_fft_2d(h, n);
  inverse_fft_2d(sx, n);
  inverse_fft_2d(sz, n);
  height_.resize(count), slope_x_.resize(count), slope_z_.resize(count);
  for (size_t i = 0; i < count; ++i) {
    height_[i] = h[i].real(), slope_x_[i] = sx[i].real(), slope_z_[i] = sz[i].real();
    height_variance_ += height_[i] * height_[i];
    slope_variance_ += slope_x_[i] * slope_x_[i] + slope_z_[i] * slope_z_[i];
  }
  height_variance_ /= double(count);
  slope_variance_ /= double(count);
}

double OceanWaves::wind_length() const { return parameters_.wind_speed * parameters_.wind_speed / kGravity; }

double OceanWaves::significant_wave_height() const { return kSignificantHeight * wind_length(); }

double OceanWaves::spectrum_height_variance() const {
  const double hs = significant_wave_height();
  return hs * hs / 16.0;
}

double OceanWaves::spectrum(const Vec2d& k) const {
  if (!k.allFinite()) throw_invalid("OceanWaves.spectrum: k must be finite (got (", k.x(), ", ", k.y(), "))");
  const double k2 = k.squaredNorm();
  if (!(k2 > 0.0)) return 0.0;
  const double lw = wind_length();
  const double cos_wind = k.dot(wind_) / std::sqrt(k2);
  return kPhillipsA * std::exp(-1.0 / (k2 * lw * lw)) / (k2 * k2) * cos_wind * cos_wind;
}

namespace {

long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// A level of detail's nodes over [i0, i1] x [j0, j1] at `spacing`: each node's displaced position,
// shading normal, squared slope and whether it is displaced at all.
struct LevelNode {
  double y = 0.0;
  Vec2d slope = Vec2d::Zero();
  bool displaced = false;
};

// Adds one level's triangles to `out`: each cell's two (counter-clockwise seen from above) to a
// band by `band_of` their centroid's distance from the centre (-1 for the flat plane, which also
// takes triangles with no displaced vertex); cells for which `skip(i, j)` holds are left out.
template <class Node, class Band, class Skip>
void add_level(long i0, long i1, long j0, long j1, double spacing, const Vec2d& centre, double height, Node node, Band band_of, Skip skip,
               SeaMeshes& out, std::vector<double>& slope_sum, std::vector<long>& triangles) {
  const long ni = i1 - i0 + 1, nj = j1 - j0 + 1;
  std::vector<Vec3d> position(size_t(ni * nj)), normal(size_t(ni * nj));
  std::vector<double> slope2(size_t(ni * nj));
  std::vector<char> displaced(size_t(ni * nj));
  for (long j = 0; j < nj; ++j) {
    for (long i = 0; i < ni; ++i) {
      const LevelNode n = node(i0 + i, j0 + j);
      const size_t v = size_t(j * ni + i);
      position[v] = Vec3d(double(i0 + i) * spacing, height + n.y, double(j0 + j) * spacing);
      normal[v] = Vec3d(-n.slope.x(), 1.0, -n.slope.y()).normalized();
      slope2[v] = n.slope.squaredNorm();
      displaced[v] = n.displaced;
    }
  }
  const size_t bands = out.bands.size();
  std::vector<std::vector<int>> remap(bands + 1, std::vector<int>(position.size(), -1));
  auto add_triangle = [&](size_t a, size_t b, size_t v) {
    const size_t corners[3] = {a, b, v};
    size_t band = bands;  // the flat plane
    if (displaced[a] || displaced[b] || displaced[v]) {
      const Vec3d centroid = (position[a] + position[b] + position[v]) / 3.0;
      band = size_t(band_of(Vec2d(centroid.x() - centre.x(), centroid.z() - centre.y()).norm()));
      slope_sum[band] += (slope2[a] + slope2[b] + slope2[v]) / 3.0;
      ++triangles[band];
    }
    Mesh& mesh = band < bands ? out.bands[band] : out.flat;
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& id = remap[band][corners[k]];
      if (id < 0) {
        id = int(mesh.vertices.size());
        mesh.vertices.push_back(position[corners[k]]);
        if (band < bands) mesh.normals.push_back(normal[corners[k]]);
      }
      t[size_t(k)] = id;
    }
    mesh.triangles.push_back(t);
  };
  for (long j = 0; j + 1 < nj; ++j) {
    for (long i = 0; i + 1 < ni; ++i) {
      if (skip(i0 + i, j0 + j)) continue;
      const size_t v00 = size_t(j * ni + i), v10 = v00 + 1, v01 = v00 + size_t(ni), v11 = v01 + 1;
      // (x, z) -> (x + 1, z + 1) -> (x + 1, z): up-facing (ground_mesh's winding).
      add_triangle(v00, v11, v10);
      add_triangle(v00, v01, v11);
    }
  }
}

// The band of a distance r in a level whose waves fade over [fade_start, radius]: `first` for the
// full waves, then kFadeBands rings.
int fade_band(double r, double fade_start, double radius, int first) {
  if (r < fade_start) return first;
  // In double before the cast: beyond the radius the quotient grows without bound.
  return first + 1 + int(std::min(double(kFadeBands - 1), (r - fade_start) / (radius - fade_start) * kFadeBands));
}

}  // namespace

SeaMeshes sea_meshes(const OceanWaves& waves, const SeaLayout& layout) {
  const double spacing = waves.spacing(), radius = layout.detail_radius, half = 0.5 * layout.size;
  const Vec2d& c = layout.centre;
  // The coarse level: the same sea at a quarter of the resolution (exactly the fine field's longer
  // modes: the streams are per wavenumber), when that is a valid OceanWaves.
  std::unique_ptr<OceanWaves> coarse;
  if (waves.resolution() / kCoarseStep >= OceanWaves::kMinResolution) {
    OceanWavesParameters p = waves.parameters();
    p.resolution /= kCoarseStep;
    coarse = std::make_unique<OceanWaves>(p);
  }
  const double coarse_spacing = kCoarseStep * spacing, coarse_radius = kCoarseRadius * radius;
  const double outermost = coarse ? coarse_radius + coarse_spacing : radius + spacing;
  std::string problems;
  auto problem = [&](const std::string& message) { problems += (problems.empty() ? "" : "; ") + message; };
  // Within the scene's reach, as every vertex must be (a trial's 1e300 was reported as a mesh vertex).
  if (!(std::abs(layout.height) <= kSceneReach)) {
    problem(concat("height must lie within ", kSceneReach, " m of 0 (got ", layout.height, ")"));
  }
  if (!c.allFinite()) problem(concat("centre must be a finite (x, z) (got (", c.x(), ", ", c.y(), "))"));
  if (c.allFinite() && !(c.cwiseAbs().maxCoeff() <= kSceneReach)) {
    problem(concat("centre must lie within the scene's reach of ", kSceneReach, " m of the origin (got (", c.x(), ", ",
                   c.y(), "))"));
  }
  const double max_radius = 0.5 * std::sqrt(double(kMaxSeaCells)) * spacing - kCoarseStep * spacing;
  // Below one spacing the patch holds no wave node of its own (a trial's 1e-9 m crashed here).
  if (!(radius >= spacing) || !(radius <= max_radius)) {
    problem(concat("detail_radius must be at least the waves' spacing ", spacing, " m and at most ", max_radius,
                   " m (", kMaxSeaCells, " cells of that spacing) (got ", radius, ")"));
  }
  if (!(layout.size > 0.0 && layout.size <= 2.0 * kSceneReach)) {
    problem(concat("size must be > 0 and at most ", 2.0 * kSceneReach, " m, the scene's reach either side (got ",
                   layout.size, ")"));
  } else if (problems.empty() && !(c.cwiseAbs().maxCoeff() + outermost + spacing < half)) {
    problem(concat("size must exceed 2 (|centre| + ", coarse ? "4 detail_radius + 5 spacing" : "detail_radius + 2 spacing",
                   ") in x and z, ", 2.0 * (c.cwiseAbs().maxCoeff() + outermost + spacing), " m (got ", layout.size, ")"));
  }
  if (!problems.empty()) throw_invalid("add_sea: ", problems);

  SeaMeshes out;
  const int levels = coarse ? 2 : 1;
  out.bands.resize(size_t(levels) * size_t(kFadeBands + 1));
  std::vector<double> slope_sum(out.bands.size(), 0.0);
  std::vector<long> triangles(out.bands.size(), 0);

  // The fine level: the patch's nodes (waves anchored to the world, not to the centre) covering
  // the square around the centre, its border on coarse nodes. Within it the waves blend from the
  // fine field h to the coarse one c (bilinear between coarse nodes; 0 without a coarse level):
  // y = c + w (h - c), so that on its border (w = 0) it is linear along the coarse triangles' edges.
  const long step = coarse ? kCoarseStep : 1;
  auto outward = [&](double v, double sign) {  // the node index just beyond v, a multiple of step
    const double n = v / (spacing * double(step));
    return long(sign < 0 ? std::floor(n) : std::ceil(n)) * step;
  };
  const long i0 = outward(c.x() - radius, -1), i1 = outward(c.x() + radius, 1);
  const long j0 = outward(c.y() - radius, -1), j1 = outward(c.y() + radius, 1);
  const double fade_start = (1.0 - kFadeFraction) * radius;
  auto coarse_at = [&](long i, long j, Vec2d* slope) {  // c and its slope at fine node (i, j)
    if (!coarse) return *slope = Vec2d::Zero(), 0.0;
    const long I = floor_div(i, kCoarseStep), J = floor_div(j, kCoarseStep);
    const double a = double(i - I * kCoarseStep) / kCoarseStep, b = double(j - J * kCoarseStep) / kCoarseStep;
    const double w[4] = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
    const long di[4] = {0, 1, 0, 1}, dj[4] = {0, 0, 1, 1};
    double h = 0.0;
    *slope = Vec2d::Zero();
    for (int k = 0; k < 4; ++k) {
      if (w[k] == 0.0) continue;
      h += w[k] * coarse->height(I + di[k], J + dj[k]);
      *slope += w[k] * coarse->slope(I + di[k], J + dj[k]);
    }
    return h;
  };
  auto fine_node = [&](long i, long j) {
    const Vec2d d(double(i) * spacing - c.x(), double(j) * spacing - c.y());
    const double r = d.norm();
    double dw;
    const double w = smoothstep_fade(r, fade_start, radius, &dw);
    Vec2d coarse_slope;
    const double ch = coarse_at(i, j, &coarse_slope);
    const double h = waves.height(i, j);
    LevelNode n;
    n.y = ch + w * (h - ch);
    n.slope = coarse_slope + w * (waves.slope(i, j) - coarse_slope);  // the product rule
    if (r > 0.0) n.slope += (h - ch) * dw * d / r;
    n.displaced = w > 0.0 || coarse;
    return n;
  };
  add_level(i0, i1, j0, j1, spacing, c, layout.height, fine_node,
            [&](double r) { return fade_band(r, fade_start, radius, 0); }, [](long, long) { return false; }, out, slope_sum, triangles);

  // The coarse level around it, out to coarse_radius, fading to the flat sea.
  double x0 = double(i0) * spacing, x1 = double(i1) * spacing, z0 = double(j0) * spacing, z1 = double(j1) * spacing;
  if (coarse) {
    const double coarse_fade_start = (1.0 - kFadeFraction) * coarse_radius;
    const long hole_i0 = i0 / kCoarseStep, hole_i1 = i1 / kCoarseStep, hole_j0 = j0 / kCoarseStep, hole_j1 = j1 / kCoarseStep;
    const long ci0 = long(std::floor((c.x() - coarse_radius) / coarse_spacing)), ci1 = long(std::ceil((c.x() + coarse_radius) / coarse_spacing));
    const long cj0 = long(std::floor((c.y() - coarse_radius) / coarse_spacing)), cj1 = long(std::ceil((c.y() + coarse_radius) / coarse_spacing));
    auto coarse_node = [&](long i, long j) {
      const Vec2d d(double(i) * coarse_spacing - c.x(), double(j) * coarse_spacing - c.y());
      const double r = d.norm();
      double dw;
      const double w = smoothstep_fade(r, coarse_fade_start, coarse_radius, &dw);
      const double h = coarse->height(i, j);
      LevelNode n;
      n.y = w * h;
      n.slope = w * coarse->slope(i, j);
      if (r > 0.0) n.slope += h * dw * d / r;
      n.displaced = w > 0.0;
      return n;
    };
    add_level(ci0, ci1, cj0, cj1, coarse_spacing, c, layout.height, coarse_node,
              [&](double r) { return fade_band(r, coarse_fade_start, coarse_radius, kFadeBands + 1); },
              [&](long i, long j) { return i >= hole_i0 && i + 1 <= hole_i1 && j >= hole_j0 && j + 1 <= hole_j1; }, out, slope_sum,
              triangles);
    x0 = double(ci0) * coarse_spacing, x1 = double(ci1) * coarse_spacing, z0 = double(cj0) * coarse_spacing, z1 = double(cj1) * coarse_spacing;
  }
  out.band_slope_variance.assign(out.bands.size(), 0.0);
  for (size_t b = 0; b < out.bands.size(); ++b) {
    if (triangles[b] > 0) out.band_slope_variance[b] = slope_sum[b] / double(triangles[b]);
  }

  // The flat plane around the grid: nested squares from the grid's border out to the sea's edge,
  // each ring twice as wide as the last, four trapezoids of two triangles each. (One ring of
  // slivers 100 km long and 100 m wide lost 13 % of grazing rays near the grid to Embree's float
  // precision.) The grid's border vertices lie on the first ring's straight inner edges at y =
  // height: a T-junction, closed to rounding.
  const double y = layout.height;
  const Vec3d outer[4] = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
  const Vec3d inner[4] = {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
  const double inner_half = 0.5 * std::min(x1 - x0, z1 - z0);
  const int rings = std::max(1, int(std::ceil(std::log2(half / inner_half))));
  auto square = [&](int ring, int corner) {  // the ring-th square's corner: widths doubling outward
    const double f = (std::exp2(ring) - 1.0) / (std::exp2(rings) - 1.0);
    return Vec3d(inner[corner] + f * (outer[corner] - inner[corner]));
  };
  Mesh& flat = out.flat;
  for (int ring = 0; ring < rings; ++ring) {
    for (int k = 0; k < 4; ++k) {
      const int base = int(flat.vertices.size());
      flat.vertices.insert(flat.vertices.end(), {square(ring + 1, k), square(ring + 1, (k + 1) % 4), square(ring, (k + 1) % 4),
                                                 square(ring, k)});
      // outer[k] -> inner[k + 1] -> outer[k + 1] and outer[k] -> inner[k] -> inner[k + 1]: up-facing
      flat.triangles.push_back({base, base + 2, base + 1});
      flat.triangles.push_back({base, base + 3, base + 2});
    }
  }
  return out;
}

std::vector<double> OceanWaves::slopes() const {
  std::vector<double> out(2 * slope_x_.size());
  for (size_t n = 0; n < slope_x_.size(); ++n) {
    out[2 * n] = slope_x_[n];
    out[2 * n + 1] = slope_z_[n];
  }
  return out;
}

std::optional<std::string> OceanWaves::patch_caveat() const {
  // The spectrum's share below a wavenumber K is exp(-1 / (K L_w)^2) (its integral from K to
  // infinity, with s = 1/k^2): what the patch holds of the waves its grid resolves (up to the
  // Nyquist wavenumber pi N / L; the short waves' cut is the resolution's, by design) is its
  // synthesised variance over that share. Waves longer than L are missing: exp(-(L / (2 pi
  // L_w))^2) of them, 8 % at L = 10 L_w.
  const double nyquist = kPi * parameters_.resolution / parameters_.patch_size;
  const double resolvable = std::exp(-1.0 / (nyquist * nyquist * wind_length() * wind_length()));
  const double held = expected_height_variance_ / (spectrum_height_variance() * resolvable);
  if (!(held < kLeastHeldVariance)) return std::nullopt;  // also 0 / 0: a grid too coarse to resolve any of it
  const auto tenths = [](double x) { return std::round(10.0 * x) / 10.0; };
  return concat("OceanWaves: the ", parameters_.patch_size, " m patch holds ", std::round(100.0 * held),
                " % of the height variance of a fully developed sea's waves its grid resolves at ",
                parameters_.wind_speed, " m/s (H_s ", tenths(4.0 * std::sqrt(expected_height_variance_)), " m, not ",
                tenths(significant_wave_height()), "): its waves longer than the patch are missing; a patch_size of ",
                "10 L_w = ", std::ceil(10.0 * wind_length()),
                " m keeps ~92 % (raise resolution alike to keep the spacing)");
}

std::string OceanWaves::describe() const {
  const OceanWavesParameters& p = parameters_;
  return concat("OceanWaves(wind_speed=", exact(p.wind_speed), ", wind_direction=(", exact(p.wind_direction.x()), ", ",
                exact(p.wind_direction.y()), "), patch_size=", exact(p.patch_size), ", resolution=", p.resolution,
                ", seed=", p.seed, ", time=", exact(p.time), ")");
}

}  // namespace refracta
