// CIE tables, Planck, XYZ <-> sRGB and Jakob-Hanika reflectance upsampling (spectral.h).
#include "refracta/shading/spectral.h"

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"

#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

namespace refracta {

namespace spectral {

namespace {

#include "refracta/shading/cie_tables.inc"

static_assert(kCieSamples == kTableSamples && kCieLambdaMin == 360 && kCieLambdaMax == 830,
              "spectral.h's table constants must match cie_tables.inc");

constexpr double kRange = kTableMax - kTableMin;  // [nm]

// Linear interpolation in a 1 nm table; 0 outside it.
double lerp_table(const double* table, double lambda_nm) {
  if (!(lambda_nm >= kTableMin && lambda_nm <= kTableMax)) return 0.0;
  const double x = lambda_nm - kTableMin;
  const int i = std::min(int(x), kTableSamples - 2);
  const double t = x - i;
  return table[i] * (1.0 - t) + table[i + 1] * t;
}

// Trapezoidal weight of the 1 nm sample i.
double trapezoid(int i) { return (i == 0 || i == kTableSamples - 1) ? 0.5 : 1.0; }

struct Constants {
  double y_integral = 0.0;       // integral y [nm]
  double d65_y_integral = 0.0;   // integral y D65 [nm]
  Eigen::Matrix3d xyz_to_rgb, rgb_to_xyz;
  Vec3d white_xyz;               // XYZ of linear sRGB (1, 1, 1): the CIELAB reference white
  Constants() {
    for (int i = 0; i < kTableSamples; ++i) {
      y_integral += trapezoid(i) * kCieY[i];
      d65_y_integral += trapezoid(i) * kCieY[i] * kCieD65[i];
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) xyz_to_rgb(r, c) = kXyzToSrgb[3 * r + c];
    }
    rgb_to_xyz = xyz_to_rgb.inverse();
    white_xyz = rgb_to_xyz * Vec3d::Ones();
  }
};

const Constants& constants() {
  static const Constants c;
  return c;
}

// --- Reflectance quadrature ----------------------------------------------------------------------
// Nodes every `step` nm and weights w_k = sum_j b_k(lambda_j) cmf_j D65_j trapezoid_j / integral(y
// D65): the 1 nm integral of the spectrum's interpolant on the nodes, with b_k the piecewise-
// quadratic Lagrange basis over pairs of intervals when their number is even (5 nm: 94 intervals;
// error O(h^4) instead of the hat basis' O(h^2)), else the hat basis.
struct Quadrature {
  std::vector<double> t;   // normalised wavelength of each node in [0, 1]
  std::vector<Vec3d> w;    // XYZ weight of each node
};

Quadrature make_quadrature(int step) {
  const Constants& k = constants();
  const int intervals = (kTableSamples - 1) / step, nodes = intervals + 1;
  const bool quadratic = intervals % 2 == 0 && step > 1;
  Quadrature q;
  q.t.resize(nodes);
  q.w.assign(nodes, Vec3d::Zero());
  for (int n = 0; n < nodes; ++n) q.t[n] = double(n * step) / kRange;
  for (int j = 0; j < kTableSamples; ++j) {
    const Vec3d fine = trapezoid(j) * kCieD65[j] / k.d65_y_integral * Vec3d(kCieX[j], kCieY[j], kCieZ[j]);
    if (quadratic) {
      // Nodes 2m, 2m+1, 2m+2 around lambda_j; u in [0, 2] its position in node steps.
      const int m = std::min(j / (2 * step), intervals / 2 - 1);
      const double u = double(j - 2 * m * step) / step;
      q.w[2 * m] += 0.5 * (u - 1.0) * (u - 2.0) * fine;
      q.w[2 * m + 1] += -u * (u - 2.0) * fine;
      q.w[2 * m + 2] += 0.5 * u * (u - 1.0) * fine;
      continue;
    }
    const int n = j / step, r = j % step;
    if (r == 0) {
      q.w[n] += fine;
    } else {
      const double a = double(r) / step;
      q.w[n] += (1.0 - a) * fine;
      q.w[n + 1] += a * fine;
    }
  }
  return q;
}

const Quadrature& quadrature(int step) {
  static const Quadrature q1 = make_quadrature(1), q2 = make_quadrature(2), q5 = make_quadrature(5),
                          q10 = make_quadrature(10);
  switch (step) {
    case 1: return q1;
    case 2: return q2;
    case 5: return q5;
    case 10: return q10;
    default: throw_invalid("quadrature_step_nm must be 1, 2, 5 or 10 (got ", step, ")");
  }
}

// --- CIELAB --------------------------------------------------------------------------------------
constexpr double kLabDelta = 6.0 / 29.0;

double lab_f(double t) {
  return t > kLabDelta * kLabDelta * kLabDelta ? std::cbrt(t) : t / (3.0 * kLabDelta * kLabDelta) + 4.0 / 29.0;
}
double lab_df(double t) {
  if (t > kLabDelta * kLabDelta * kLabDelta) {
    const double c = std::cbrt(t);
    return 1.0 / (3.0 * c * c);
  }
  return 1.0 / (3.0 * kLabDelta * kLabDelta);
}

Vec3d xyz_to_lab(const Vec3d& xyz, Eigen::Matrix3d* jacobian = nullptr) {
  const Vec3d& wp = constants().white_xyz;
  const double fx = lab_f(xyz.x() / wp.x()), fy = lab_f(xyz.y() / wp.y()), fz = lab_f(xyz.z() / wp.z());
  if (jacobian) {
    const double dx = lab_df(xyz.x() / wp.x()) / wp.x(), dy = lab_df(xyz.y() / wp.y()) / wp.y(),
                 dz = lab_df(xyz.z() / wp.z()) / wp.z();
    *jacobian << 0.0, 116.0 * dy, 0.0,  //
        500.0 * dx, -500.0 * dy, 0.0,   //
        0.0, 200.0 * dy, -200.0 * dz;
  }
  return Vec3d(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

double sigmoid(double x) {
  if (std::isinf(x)) return x > 0.0 ? 1.0 : 0.0;
  return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x));
}

// CIELAB of the sigmoid-polynomial reflectance c, and its Jacobian d Lab / d c.
Vec3d lab_of(const Coefficients& c, const Quadrature& q, Eigen::Matrix3d* jacobian) {
  Vec3d xyz = Vec3d::Zero();
  Eigen::Matrix3d dxyz = Eigen::Matrix3d::Zero();
  for (size_t n = 0; n < q.t.size(); ++n) {
    const double t = q.t[n], x = (c[0] * t + c[1]) * t + c[2];
    const double r2 = 1.0 + x * x, root = std::sqrt(r2);
    const double s = 0.5 + x / (2.0 * root), ds = 0.5 / (r2 * root);
    xyz += s * q.w[n];
    if (jacobian) {
      const Vec3d g = ds * q.w[n];
      dxyz.col(0) += g * (t * t);
      dxyz.col(1) += g * t;
      dxyz.col(2) += g;
    }
  }
  Eigen::Matrix3d dlab;
  const Vec3d lab = xyz_to_lab(xyz, jacobian ? &dlab : nullptr);
  if (jacobian) *jacobian = dlab * dxyz;
  return lab;
}

// Gauss-Newton iterations and their stopping rules.
constexpr int kMaxIterations = 60;
constexpr int kMaxHalvings = 30;
constexpr double kResidualTolerance = 1e-7;  // [Delta E]: far below the 1e-3 RGB target (~0.1 Delta E)
constexpr double kCoefficientBound = 1e6;    // beyond, the sigmoid is a step for any lambda step

bool is_grey(const Vec3d& rgb) { return rgb.x() == rgb.y() && rgb.y() == rgb.z(); }

Coefficients grey_coefficients(double g) {
  if (g <= 0.0) return {0.0, 0.0, -std::numeric_limits<double>::infinity()};
  if (g >= 1.0) return {0.0, 0.0, std::numeric_limits<double>::infinity()};
  return {0.0, 0.0, (g - 0.5) / std::sqrt(g * (1.0 - g))};
}

void check_unit_rgb(const Vec3d& rgb) {
  for (int i = 0; i < 3; ++i) {
    if (!(rgb[i] >= 0.0 && rgb[i] <= 1.0)) throw_invalid("rgb must be in [0, 1] (got ", rgb[i], ")");
  }
}

double smoothstep(double x) { return x * x * (3.0 - 2.0 * x); }

}  // namespace

Vec3d cie_xyz(double lambda_nm) {
  return Vec3d(lerp_table(kCieX, lambda_nm), lerp_table(kCieY, lambda_nm), lerp_table(kCieZ, lambda_nm));
}
double cie_y_integral() { return constants().y_integral; }
double d65(double lambda_nm) { return lerp_table(kCieD65, lambda_nm); }
double d65_normalised(double lambda_nm) {
  return lerp_table(kCieD65, lambda_nm) * constants().y_integral / constants().d65_y_integral;
}

double checked_temperature(double temperature, const char* what) {
  if (!(temperature > 0.0 && temperature <= kHottestBlackbody)) {
    throw_invalid(what, " must be in (0, ", kHottestBlackbody, "] K (got ", temperature, ")");
  }
  return temperature;
}

double planck(double lambda_nm, double temperature) {
  checked_temperature(temperature, "temperature");
  if (!(lambda_nm > 0.0) || !std::isfinite(lambda_nm)) throw_invalid("wavelength must be > 0 nm (got ", lambda_nm, ")");
  constexpr double h = 6.62607015e-34, c = 299792458.0, kb = 1.380649e-23;  // SI 2019, exact
  const double l = lambda_nm * 1e-9;                                         // [m]
  const double exponent = h * c / (l * kb * temperature);
  if (exponent > 700.0) return 0.0;  // e^700 ~ 1e304: the radiance underflows
  return 2.0 * h * c * c / (l * l * l * l * l) / std::expm1(exponent) * 1e-9;  // per nm
}

Vec3d xyz_to_linear_srgb(const Vec3d& xyz) { return constants().xyz_to_rgb * xyz; }
Vec3d linear_srgb_to_xyz(const Vec3d& rgb) { return constants().rgb_to_xyz * rgb; }

Vec3d xyz_of_radiance(const std::vector<double>& v) {
  if (v.size() != size_t(kTableSamples)) throw_invalid("a 1 nm spectrum needs ", kTableSamples, " values (got ", v.size(), ")");
  Vec3d xyz = Vec3d::Zero();
  for (int i = 0; i < kTableSamples; ++i) xyz += trapezoid(i) * v[i] * Vec3d(kCieX[i], kCieY[i], kCieZ[i]);
  return xyz / constants().y_integral;
}

Vec3d planckian_white(double kelvin) {
  if (!(kelvin > 0.0) || !std::isfinite(kelvin)) throw_invalid("colour temperature must be > 0 K (got ", kelvin, ")");
  std::vector<double> spectrum(kTableSamples);
  for (int i = 0; i < kTableSamples; ++i) spectrum[i] = planck(kTableMin + i, kelvin);
  const Vec3d xyz = xyz_of_radiance(spectrum);
  if (!(xyz.y() > 0.0)) throw_invalid("colour temperature ", kelvin, " K has no visible light");
  return xyz / xyz.y();
}

Vec3d daylight_white(double kelvin) {
  if (!(kelvin >= 4000.0 && kelvin <= 25000.0)) {
    throw_invalid("CIE daylight needs a correlated colour temperature in [4000, 25000] K (got ", kelvin, ")");
  }
  // CIE 015:2004 eq. 3.3 (x_D) and 3.4 (y_D).
  const double t = 1e3 / kelvin;
  const double x = kelvin <= 7000.0 ? ((-4.6070 * t + 2.9678) * t + 0.09911) * t + 0.244063
                                    : ((-2.0064 * t + 1.9018) * t + 0.24748) * t + 0.237040;
  const double y = -3.0 * x * x + 2.87 * x - 0.275;
  return Vec3d(x / y, 1.0, (1.0 - x - y) / y);
}

namespace {
// Bradford's cone responses from XYZ (Lam 1985).
Eigen::Matrix3d bradford_cones() {
  Eigen::Matrix3d m;
  m << 0.8951, 0.2664, -0.1614,  //
      -0.7502, 1.7135, 0.0367,   //
      0.0389, -0.0685, 1.0296;
  return m;
}
}  // namespace

bool adaptable_white(const Vec3d& white) {
  const Vec3d cones = bradford_cones() * white;
  return cones.minCoeff() > 0.0 && is_finite(cones);
}

Eigen::Matrix3d bradford_adaptation(const Vec3d& source_white, const Vec3d& target_white) {
  const Eigen::Matrix3d m = bradford_cones();
  const Vec3d source = m * source_white, target = m * target_white;
  if (!adaptable_white(source_white) || !adaptable_white(target_white)) {
    throw_invalid("a white to adapt must have positive cone responses (got XYZ ", source_white.transpose(), " -> ",
                  target_white.transpose(), ")");
  }
  return m.inverse() * target.cwiseQuotient(source).asDiagonal() * m;
}

Vec3d xyz_of_reflectance(const std::vector<double>& v) {
  if (v.size() != size_t(kTableSamples)) throw_invalid("a 1 nm spectrum needs ", kTableSamples, " values (got ", v.size(), ")");
  Vec3d xyz = Vec3d::Zero();
  for (int i = 0; i < kTableSamples; ++i) xyz += trapezoid(i) * v[i] * kCieD65[i] * Vec3d(kCieX[i], kCieY[i], kCieZ[i]);
  return xyz / constants().d65_y_integral;
}

double sigmoid_polynomial(const Coefficients& c, double lambda_nm) {
  const double t = (lambda_nm - kTableMin) / kRange;
  if (std::isinf(c[2]) && c[0] == 0.0 && c[1] == 0.0) return c[2] > 0.0 ? 1.0 : 0.0;
  return sigmoid((c[0] * t + c[1]) * t + c[2]);
}

// --- Fits ----------------------------------------------------------------------------------------
FitResult fit_reflectance(const Vec3d& rgb, const Coefficients& start, int quadrature_step_nm) {
  check_unit_rgb(rgb);
  const Quadrature& q = quadrature(quadrature_step_nm);
  FitResult result;
  if (is_grey(rgb)) {
    result.c = grey_coefficients(rgb.x());
    return result;
  }
  const Vec3d target = xyz_to_lab(linear_srgb_to_xyz(rgb));
  Coefficients c = start;
  for (double& v : c) {
    if (!std::isfinite(v)) v = 0.0;
  }
  Eigen::Matrix3d jacobian;
  Vec3d r = target - lab_of(c, q, &jacobian);
  double norm = r.norm();
  int it = 0;
  for (; it < kMaxIterations && norm > kResidualTolerance; ++it) {
    const Vec3d step = jacobian.fullPivLu().solve(r);
    if (!step.allFinite()) break;
    // Step halving: accept the first fraction of the Gauss-Newton step that lowers the residual.
    bool accepted = false;
    double fraction = 1.0;
    for (int h = 0; h < kMaxHalvings && !accepted; ++h, fraction *= 0.5) {
      Coefficients trial{c[0] + fraction * step[0], c[1] + fraction * step[1], c[2] + fraction * step[2]};
      if (std::abs(trial[0]) > kCoefficientBound || std::abs(trial[1]) > kCoefficientBound ||
          std::abs(trial[2]) > kCoefficientBound) {
        continue;
      }
      Eigen::Matrix3d trial_jacobian;
      const Vec3d trial_r = target - lab_of(trial, q, &trial_jacobian);
      if (trial_r.norm() < norm) {
        c = trial, r = trial_r, norm = trial_r.norm(), jacobian = trial_jacobian;
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  result.c = c;
  result.residual = norm;
  result.iterations = it;
  return result;
}

FitResult fit_reflectance_robust(const Vec3d& rgb) {
  check_unit_rgb(rgb);
  if (is_grey(rgb)) return fit_reflectance(rgb);
  constexpr int kContinuationSteps = 8;  // enough for the sRGB primaries from their mean grey
  const Vec3d grey = Vec3d::Constant(rgb.mean());
  Coefficients c = grey_coefficients(grey.x());
  for (int k = 1; k <= kContinuationSteps; ++k) {
    const Vec3d target = grey + (rgb - grey) * (double(k) / kContinuationSteps);
    c = fit_reflectance(target, c, 5).c;
  }
  FitResult fine = fit_reflectance(rgb, c, 1);
  // Fallback from the centre of the space, should continuation end in a worse basin.
  if (fine.residual > 1e-3) {
    FitResult other = fit_reflectance(rgb, {0.0, 0.0, 0.0}, 1);
    if (other.residual < fine.residual) fine = other;
  }
  return fine;
}

// --- The table -----------------------------------------------------------------------------------
RgbToSpectrumTable::RgbToSpectrumTable(int resolution, int quadrature_step_nm, int polish_steps)
    : res_(resolution), quadrature_step_(quadrature_step_nm), polish_steps_(polish_steps) {
  if (resolution < 3 || resolution > 256) throw_invalid("table resolution must be in [3, 256] (got ", resolution, ")");
  quadrature(quadrature_step_nm);  // validates the step
  const auto start = std::chrono::steady_clock::now();
  const int n = res_;
  z_.resize(n);
  for (int k = 0; k < n; ++k) z_[k] = smoothstep(smoothstep(double(k) / (n - 1)));
  xy_.resize(n);
  for (int k = 0; k < n; ++k) xy_[k] = smoothstep(double(k) / (n - 1));
  c_.assign(size_t(3) * n * n * n * 3, 0.0);
  std::vector<double> worst(size_t(3) * n * n, 0.0);
  // One chain per (l, x, y): fit at z = z_{k0} by continuation, then walk up and down in z, each
  // fit warm-started by its neighbour (rgb2spec_opt's order).
  const int k0 = n / 5;
  tbb::parallel_for(tbb::blocked_range<int>(0, 3 * n * n), [&](const tbb::blocked_range<int>& range) {
    const DefaultFloatingPointMode fp_mode;  // parallel.h: whatever mode the worker was left in
    for (int chain = range.begin(); chain != range.end(); ++chain) {
      const int l = chain / (n * n), j = (chain / n) % n, i = chain % n;
      const double x = xy_[i], y = xy_[j];
      auto rgb_at = [&](int k) {
        Vec3d rgb;
        const double z = std::max(z_[k], z_[1]);  // z_0 = 0 (black) takes z_1's colour (< 3e-5 for res 32)
        rgb[l] = z, rgb[(l + 1) % 3] = x * z, rgb[(l + 2) % 3] = y * z;
        return rgb;
      };
      auto store = [&](int k, const FitResult& fit) {
        double* out = &c_[((size_t(l) * n + k) * n * n + size_t(j) * n + i) * 3];
        // White's exact c2 = +inf would poison the interpolation: 1e4 gives s = 1 - 2.5e-9.
        constexpr double kWhite = 1e4;
        for (int d = 0; d < 3; ++d) out[d] = std::isfinite(fit.c[d]) ? fit.c[d] : std::copysign(kWhite, fit.c[d]);
        if (std::isfinite(fit.residual)) worst[chain] = std::max(worst[chain], fit.residual);
      };
      // Continuation from grey at k0 (fit_reflectance_robust's path at the coarse quadrature).
      const Vec3d rgb0 = rgb_at(k0);
      const Vec3d grey = Vec3d::Constant(rgb0.mean());
      Coefficients c = grey_coefficients(grey.x());
      constexpr int kSteps = 8;
      FitResult fit;
      for (int s = 1; s <= kSteps; ++s) {
        fit = fit_reflectance(grey + (rgb0 - grey) * (double(s) / kSteps), c, quadrature_step_nm);
        c = fit.c;
      }
      store(k0, fit);
      const Coefficients c0 = c;
      for (int k = k0 + 1; k < n; ++k) {
        fit = fit_reflectance(rgb_at(k), c, quadrature_step_nm);
        c = fit.c;
        store(k, fit);
      }
      c = c0;
      for (int k = k0 - 1; k >= 0; --k) {
        fit = fit_reflectance(rgb_at(k), c, quadrature_step_nm);
        c = fit.c;
        store(k, fit);
      }
    }
  });
  worst_residual_ = *std::max_element(worst.begin(), worst.end());
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Coefficients RgbToSpectrumTable::coefficients(const Vec3d& rgb_in) const {
  Vec3d rgb;
  for (int d = 0; d < 3; ++d) rgb[d] = std::isnan(rgb_in[d]) ? 0.0 : std::clamp(rgb_in[d], 0.0, 1.0);
  if (is_grey(rgb)) return grey_coefficients(rgb.x());
  int l = 0;
  if (rgb[1] > rgb[l]) l = 1;
  if (rgb[2] > rgb[l]) l = 2;
  const int n = res_;
  const double z = rgb[l];
  const double x = rgb[(l + 1) % 3] / z, y = rgb[(l + 2) % 3] / z;
  auto cell = [n](const std::vector<double>& nodes, double v) {
    return int(std::clamp<std::ptrdiff_t>(std::upper_bound(nodes.begin(), nodes.end(), v) - nodes.begin() - 1, 0, n - 2));
  };
  const int xi = cell(xy_, x), yi = cell(xy_, y), zi = cell(z_, z);
  const double dx = (x - xy_[xi]) / (xy_[xi + 1] - xy_[xi]), dy = (y - xy_[yi]) / (xy_[yi + 1] - xy_[yi]),
               dz = (z - z_[zi]) / (z_[zi + 1] - z_[zi]);
  Coefficients out{0.0, 0.0, 0.0};
  for (int corner = 0; corner < 8; ++corner) {
    const int ox = corner & 1, oy = (corner >> 1) & 1, oz = corner >> 2;
    const double w = (ox ? dx : 1.0 - dx) * (oy ? dy : 1.0 - dy) * (oz ? dz : 1.0 - dz);
    const double* c = &c_[((size_t(l) * n + zi + oz) * n * n + size_t(yi + oy) * n + xi + ox) * 3];
    for (int d = 0; d < 3; ++d) out[d] += w * c[d];
  }
  // Polish: Gauss-Newton steps from the interpolated coefficients (the interpolation alone is
  // up to 3.5e-3 off in RGB at res 32), keeping the best iterate (a step from a poor start may
  // overshoot; the last one is checked by one more evaluation).
  if (polish_steps_ > 0) {
    const Quadrature& q = quadrature(quadrature_step_);
    const Vec3d target = xyz_to_lab(linear_srgb_to_xyz(rgb));
    Coefficients best = out;
    double best_norm = std::numeric_limits<double>::infinity();
    for (int it = 0; it <= polish_steps_; ++it) {
      Eigen::Matrix3d jacobian;
      const Vec3d r = target - lab_of(out, q, it < polish_steps_ ? &jacobian : nullptr);
      if (!(r.norm() < best_norm)) break;
      best = out, best_norm = r.norm();
      if (it == polish_steps_) break;
      const Vec3d step = jacobian.partialPivLu().solve(r);
      if (!step.allFinite()) break;
      for (int d = 0; d < 3; ++d) out[d] += step[d];
    }
    out = best;
  }
  return out;
}

const RgbToSpectrumTable& rgb_to_spectrum_table() {
  static std::once_flag once;
  static std::unique_ptr<RgbToSpectrumTable> table;
  // Isolated: its first caller is often a render's tile, and a thread waiting in the table's own
  // parallel loop must not take another tile that waits on this call_once (a deadlock, oneTBB's
  // documented lazy-initialisation trap).
  std::call_once(once, [] {
    tbb::this_task_arena::isolate([] {
      table = std::make_unique<RgbToSpectrumTable>(kTableResolution, kTableQuadratureStep, kTablePolishSteps);
    });
  });
  return *table;
}

}  // namespace spectral

}  // namespace refracta
