// Sampling routines shared by every layer: warps of uniform numbers onto discs, hemispheres,
// spheres, cones and triangles with their densities, piecewise-constant 1-D and 2-D
// distributions, and the power heuristic. Conventions follow pbrt-v4 (sampling.h): u in [0, 1).
#pragma once

#include "refracta/core/math.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace refracta {

using Vec2d = Eigen::Vector2d;

// Shirley & Chiu 1997 concentric map of [0,1)^2 onto the unit disc (area-preserving).
inline Vec2d sample_uniform_disk_concentric(const Vec2d& u) {
  const double ox = 2.0 * u.x() - 1.0, oy = 2.0 * u.y() - 1.0;
  if (ox == 0.0 && oy == 0.0) return Vec2d::Zero();
  double r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox, theta = 0.25 * kPi * (oy / ox);
  } else {
    r = oy, theta = 0.5 * kPi - 0.25 * kPi * (ox / oy);
  }
  return Vec2d(r * std::cos(theta), r * std::sin(theta));
}

// Malley's method: a cosine-weighted direction about +z; pdf = cos(theta)/pi.
inline Vec3d sample_cosine_hemisphere(const Vec2d& u) {
  const Vec2d d = sample_uniform_disk_concentric(u);
  const double z = std::sqrt(std::max(0.0, 1.0 - d.squaredNorm()));
  return Vec3d(d.x(), d.y(), z);
}
inline double cosine_hemisphere_pdf(double cos_theta) { return std::max(cos_theta, 0.0) / kPi; }

inline Vec3d sample_uniform_sphere(const Vec2d& u) {
  const double z = 1.0 - 2.0 * u.x(), r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y();
  return Vec3d(r * std::cos(phi), r * std::sin(phi), z);
}
inline double uniform_sphere_pdf() { return 1.0 / (4.0 * kPi); }

// Barycentric weights (b0, b1, b2) of a uniform point on a triangle (Heitz 2019's
// low-distortion map, pbrt-v4 SampleUniformTriangle).
inline Vec3d sample_uniform_triangle(const Vec2d& u) {
  double b0, b1;
  if (u.x() < u.y()) {
    b0 = u.x() / 2.0, b1 = u.y() - b0;
  } else {
    b1 = u.y() / 2.0, b0 = u.x() - b1;
  }
  return Vec3d(b0, b1, 1.0 - b0 - b1);
}

// Veach 1997, ch. 9: the power heuristic with beta = 2, for nf samples of pdf f_pdf and ng of g_pdf.
inline double power_heuristic(int nf, double f_pdf, int ng, double g_pdf) {
  const double f = nf * f_pdf, g = ng * g_pdf;
  if (std::isinf(f * f)) return 1.0;
  const double denominator = f * f + g * g;
  return denominator > 0.0 ? f * f / denominator : 0.0;
}

// A piecewise-constant density on [min, max] from non-negative weights (pbrt-v4
// PiecewiseConstant1D). All-zero weights give the uniform density.
class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  explicit PiecewiseConstant1D(const std::vector<double>& weights, double min = 0.0, double max = 1.0)
      : func_(weights), cdf_(weights.size() + 1), min_(min), max_(max) {
    const size_t n = func_.size();
    for (double& f : func_) f = std::abs(f);
    cdf_[0] = 0.0;
    for (size_t i = 1; i <= n; ++i) cdf_[i] = cdf_[i - 1] + func_[i - 1] * (max - min) / double(n);
    integral_ = cdf_[n];
    if (integral_ == 0.0) {
      for (size_t i = 1; i <= n; ++i) cdf_[i] = double(i) / double(n);
    } else {
      for (size_t i = 1; i <= n; ++i) cdf_[i] /= integral_;
    }
  }
  size_t size() const { return func_.size(); }
  double integral() const { return integral_; }
  // A point x in [min, max) with its density; `offset` receives the cell.
  double sample(double u, double* pdf = nullptr, size_t* offset = nullptr) const {
    const size_t n = func_.size();
    const size_t o = size_t(std::clamp<std::ptrdiff_t>(
        std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin() - 1, 0, std::ptrdiff_t(n) - 1));
    if (offset) *offset = o;
    double du = u - cdf_[o];
    if (cdf_[o + 1] - cdf_[o] > 0.0) du /= cdf_[o + 1] - cdf_[o];
    if (pdf) *pdf = cell_pdf(o);
    return min_ + (double(o) + du) / double(n) * (max_ - min_);
  }
  // Density of the cell holding x (per unit of x).
  double pdf(double x) const {
    const size_t n = func_.size();
    const double t = (x - min_) / (max_ - min_);
    if (!(t >= 0.0 && t <= 1.0)) return 0.0;
    return cell_pdf(std::min(size_t(t * double(n)), n - 1));
  }
  // Probability of picking cell i when sampling (discrete use: a light or a triangle).
  double cell_probability(size_t i) const { return cdf_[i + 1] - cdf_[i]; }

 private:
  double cell_pdf(size_t i) const {
    return integral_ > 0.0 ? func_[i] / integral_ : 1.0 / (max_ - min_);
  }
  std::vector<double> func_, cdf_;
  double min_ = 0.0, max_ = 1.0, integral_ = 0.0;
};

// A piecewise-constant density on [0,1]^2 from a row-major nu x nv grid of weights (v rows of u
// cells): marginal over v, conditionals over u (pbrt-v4 PiecewiseConstant2D).
class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  PiecewiseConstant2D(const std::vector<double>& weights, int nu, int nv) {
    conditional_.reserve(nv);
    std::vector<double> marginal(nv);
    for (int v = 0; v < nv; ++v) {
      conditional_.emplace_back(std::vector<double>(weights.begin() + size_t(v) * nu, weights.begin() + size_t(v + 1) * nu));
      marginal[v] = conditional_.back().integral();
    }
    marginal_ = PiecewiseConstant1D(marginal);
  }
  double integral() const { return marginal_.integral(); }
  // (u, v) in [0,1)^2 with its density.
  Vec2d sample(const Vec2d& u, double* pdf = nullptr) const {
    double pdf_v, pdf_u;
    size_t v;
    const double y = marginal_.sample(u.y(), &pdf_v, &v);
    const double x = conditional_[v].sample(u.x(), &pdf_u);
    if (pdf) *pdf = pdf_u * pdf_v;
    return Vec2d(x, y);
  }
  double pdf(const Vec2d& p) const {
    const int nv = int(conditional_.size());
    const int v = std::clamp(int(p.y() * nv), 0, nv - 1);
    return integral() > 0.0 ? conditional_[v].pdf(p.x()) * marginal_.pdf(p.y()) : 1.0;
  }

 private:
  std::vector<PiecewiseConstant1D> conditional_;
  PiecewiseConstant1D marginal_;
};

}  // namespace refracta
