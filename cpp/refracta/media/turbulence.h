// Optical turbulence as a frozen-flow refractive-index fluctuation (issue 10): a periodic
// (tileable) 3-D pattern delta_n(x) -- a uniform cubic B-spline over a grid of coefficients,
// C2, with its exact gradient -- carried by the wind and weighted by a height envelope:
//   n_turbulence(x, t) = scale * E(h) * B(x - wind t),
//   E(h) = e^(-h/depth) above the ground (2 - e^(h/depth) below: C1, bounded), or 1 (no envelope).
// The coefficients come from Python (refracta.Turbulence: a von Karman spectrum synthesised by
// FFT and prefiltered so that the spline passes through the synthesised samples); this side
// evaluates them, templated on the scalar like the models (a Jet position gets the linearisation
// value + grad . dx, since the pattern is data, not a parameter).
#pragma once

#include "refracta/core/math.h"
#include "refracta/media/local_region.h"

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace refracta {

// A periodic uniform cubic B-spline over an nx x ny x nz grid (index (i ny + j) nz + k, x = axis 0,
// y up = axis 1, z = axis 2) of cells `spacing` [m] wide; one period is nx * spacing along x, etc.
// In Python TurbulenceGrid(coefficients (nx, ny, nz) float32, spacing [m]), built by
// refracta.Turbulence; evaluate(points) gives the spline's values and gradients (for tests and
// plots).
class TurbulenceGrid {
 public:
  // Throws std::invalid_argument for a size mismatch, a dimension < 4, a spacing <= 0 or a
  // non-finite coefficient.
  TurbulenceGrid(std::vector<float> coefficients, std::array<int, 3> shape, double spacing);

  // The spline's value and gradient [1/m] at p [m] (periodic in every axis).
  void evaluate(const Vec3d& p, double* value, Vec3d* grad) const;
  // max |coefficient|: the spline's values are bounded by it (its weights are >= 0, sum 1).
  double bound() const { return bound_; }
  const std::array<int, 3>& shape() const { return n_; }
  double spacing() const { return spacing_; }
  const std::vector<float>& coefficients() const { return c_; }

 private:
  std::vector<float> c_;
  std::array<int, 3> n_;
  double spacing_, bound_ = 0.0;
};

// A turbulence's region stops where its envelope is below this fraction of its value at the
// ground: the neglected tail changes rays' deflections by about that fraction (random fluctuations
// add no systematic bending), far below the realisations' own scatter.
constexpr double kNegligibleTurbulence = 1e-3;

// A grid placed in the air (Python's TurbulenceLayer): delta_n = scale * E(h) * grid(R_yaw (p -
// offset)), E(h) = e^(-h/depth) above the ground (none for depth = inf): scaled, shifted by the
// wind, the lattice turned by yaw [rad] about the vertical (the layer's internal unit:
// refracta.Turbulence takes yaw_deg [deg]). Made by refracta.Turbulence (its `layer`).
struct Turbulence {
  std::shared_ptr<const TurbulenceGrid> grid;
  double scale = 1.0;             // delta_n per unit of the grid's values
  Vec3d offset = Vec3d::Zero();   // wind * t [m]: the pattern at p is the grid's at p - offset
  double depth = std::numeric_limits<double>::infinity();  // envelope e-folding depth [m]; inf: none
  // The lattice's axes turned by this angle [rad] about the vertical: a periodic tile repeats along
  // a ray that runs along a lattice axis, so that the same modes add up coherently; turned by an
  // angle whose tangent is far from simple fractions, level rays along x or z cross it
  // quasi-periodically (refracta.Turbulence chooses it).
  double yaw = 0.0;
  // Of offset and yaw (place keeps them together): the offset in the lattice's frame, reduced
  // modulo the tile (a tile's shift is no shift), so that any finite time keeps the lattice
  // point within the grid's index range.
  double cos_yaw = 1.0, sin_yaw = 0.0;
  Vec3d lattice_offset = Vec3d::Zero();

  void place(const Vec3d& shift, double angle) {
    offset = shift;
    yaw = angle;
    cos_yaw = std::cos(angle);
    sin_yaw = std::sin(angle);
    lattice_offset = to_lattice(shift);
    for (int a = 0; a < 3; ++a) {
      const double period = grid->shape()[size_t(a)] * grid->spacing();
      const double r = std::fmod(lattice_offset[a], period);
      lattice_offset[a] = r < 0.0 ? r + period : r;
    }
  }

  // p [m] turned into the lattice's frame (about the vertical, by yaw).
  Vec3d to_lattice(const Vec3d& p) const {
    return Vec3d(cos_yaw * p.x() + sin_yaw * p.z(), p.y(), -sin_yaw * p.x() + cos_yaw * p.z());
  }
  // The grid's point for p [m]: turned, then shifted by the wind.
  Vec3d lattice_point(const Vec3d& p) const { return to_lattice(p) - lattice_offset; }

  // delta_n and its gradient at p, for double or Jet positions.
  template <class T>
  void evaluate(const Vec3<T>& p, T* dn, Vec3<T>* grad) const {
    using std::exp;
    const double c = cos_yaw, s = sin_yaw;
    double b;
    Vec3d lattice_grad;
    grid->evaluate(lattice_point(Vec3d(value_of(p.x()), value_of(p.y()), value_of(p.z()))), &b, &lattice_grad);
    const Vec3d db(c * lattice_grad.x() - s * lattice_grad.z(), lattice_grad.y(), s * lattice_grad.x() + c * lattice_grad.z());
    T e(1.0), de_dh(0.0);
    if (std::isfinite(depth)) {
      if (value_of(p.y()) > 0.0) {
        e = exp(-p.y() / depth);
        de_dh = -e / depth;
      } else {
        const T rise = exp(p.y() / depth);
        e = T(2.0) - rise;
        de_dh = -rise / depth;
      }
    }
    // The pattern is data: its value at a Jet position is the linearisation b + db . (p - p.a).
    T pattern(b);
    for (int k = 0; k < 3; ++k) pattern += db[k] * (p[k] - T(value_of(p[k])));
    *dn = T(scale) * e * pattern;
    *grad = Vec3<T>(T(scale * db.x()) * e, T(scale) * (de_dh * pattern + e * T(db.y())), T(scale * db.z()) * e);
  }

  // Where it matters: the slab below the height where the envelope falls to kNegligibleTurbulence
  // (6.9 depths); everywhere without an envelope. Steps inside: at most four cells (scale 8 cells),
  // the tolerance doing the rest: unlike an isolated spot the pattern varies on every step, so
  // rk45's error estimate sees it. Measured on the hot road's rays through the default
  // refracta.Turbulence (5 cm cells, 600 m): 4-cell steps move a path's end by <= 2.3e-4 m from
  // half-cell steps, where the turbulence itself moves it by 3e-3 to 1.7 m.
  LocalRegion region() const {
    LocalRegion slab;
    slab.top = std::isfinite(depth) ? -std::log(kNegligibleTurbulence) * depth : std::numeric_limits<double>::infinity();
    slab.scale = 8.0 * grid->spacing();
    return slab;
  }
};

// A layer from its numbers, checked (std::invalid_argument naming the field): a grid, a finite
// scale, depth > 0 [m] (inf: no envelope), a finite yaw [rad].
Turbulence make_turbulence_layer(std::shared_ptr<const TurbulenceGrid> grid, double scale, const Vec3d& offset,
                                 double depth, double yaw);

// Values and gradients [1/m] at many points [m] of anything with evaluate(p, &value, &grad) (a
// TurbulenceGrid, a Turbulence).
struct PointValues {
  std::vector<double> values;
  std::vector<Vec3d> gradients;
};
template <class Source>
PointValues evaluate_at(const Source& source, const std::vector<Vec3d>& points) {
  PointValues out{std::vector<double>(points.size()), std::vector<Vec3d>(points.size())};
  for (size_t i = 0; i < points.size(); ++i) source.evaluate(points[i], &out.values[i], &out.gradients[i]);
  return out;
}

}  // namespace refracta
