// The periodic cubic B-spline of a turbulence grid (turbulence.h).
#include "refracta/media/turbulence.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <limits>

namespace refracta {

namespace {

// Uniform cubic B-spline weights of the four coefficients around fraction u in [0, 1) and their
// derivatives in u.
void bspline_weights(double u, double w[4], double dw[4]) {
  const double u2 = u * u, u3 = u2 * u, v = 1.0 - u;
  w[0] = v * v * v / 6.0;
  w[1] = (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0;
  w[2] = (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0;
  w[3] = u3 / 6.0;
  dw[0] = -0.5 * v * v;
  dw[1] = 1.5 * u2 - 2.0 * u;
  dw[2] = -1.5 * u2 + u + 0.5;
  dw[3] = 0.5 * u2;
}

}  // namespace

TurbulenceGrid::TurbulenceGrid(std::vector<float> coefficients, std::array<int, 3> shape, double spacing)
    : c_(std::move(coefficients)), n_(shape), spacing_(spacing) {
  for (int a = 0; a < 3; ++a) {
    if (n_[a] < 4) throw_invalid("TurbulenceGrid: every dimension must be >= 4 (got shape (", n_[0], ", ", n_[1], ", ", n_[2], "))");
  }
  if (c_.size() != size_t(n_[0]) * n_[1] * n_[2]) {
    throw_invalid("TurbulenceGrid: ", c_.size(), " coefficients for shape (", n_[0], ", ", n_[1], ", ", n_[2], ")");
  }
  if (!(spacing_ > 0.0) || !std::isfinite(spacing_)) throw_invalid("TurbulenceGrid: spacing must be > 0 m (got ", spacing_, ")");
  for (float c : c_) {
    if (!std::isfinite(c)) throw_invalid("TurbulenceGrid: coefficients must be finite");
    bound_ = std::max(bound_, double(std::abs(c)));
  }
}

Turbulence make_turbulence_layer(std::shared_ptr<const TurbulenceGrid> grid, double scale, const Vec3d& offset,
                                 double depth, double yaw) {
  if (!grid) throw_invalid("TurbulenceLayer: grid must be a TurbulenceGrid (got None)");
  if (!std::isfinite(scale)) throw_invalid("TurbulenceLayer: scale must be finite (got ", scale, ")");
  if (!(depth > 0.0)) throw_invalid("TurbulenceLayer: depth must be > 0 m (got ", depth, ")");
  if (!std::isfinite(yaw)) throw_invalid("TurbulenceLayer: yaw must be finite (got ", yaw, ")");
  Turbulence layer;
  layer.grid = std::move(grid);
  layer.scale = scale;
  layer.depth = depth;
  layer.place(offset, yaw);
  return layer;
}

void TurbulenceGrid::evaluate(const Vec3d& p, double* value, Vec3d* grad) const {
  // Cell and fraction per axis; coefficients i - 1 .. i + 2 (periodic) weigh on [i, i + 1).
  double w[3][4], dw[3][4];
  int index[3][4];
  for (int a = 0; a < 3; ++a) {
    const double t = p[a] / spacing_;
    const double cell = std::floor(t);
    bspline_weights(t - cell, w[a], dw[a]);
    const long n = n_[a];
    // The periodic index of cell - 1 in integers (std::fmod cost as much as a fifth of a shimmer
    // step). Cells beyond a long's range (or NaN) are far outside any scene: NaN out.
    if (!(std::abs(cell) < 9e18)) {
      *value = std::numeric_limits<double>::quiet_NaN();
      *grad = Vec3d::Constant(*value);
      return;
    }
    long first;  // (cell - 1) mod n: a mask for the usual power-of-two grids, else one division
    if ((n & (n - 1)) == 0) {
      first = (long(cell) - 1) & (n - 1);
    } else {
      first = long(cell) % n - 1;  // in [-n, n - 1)
      if (first < 0) first += n;
    }
    for (int k = 0; k < 4; ++k) {
      const long i = first + k;
      index[a][k] = int(i < n ? i : i - n);
    }
  }
  // Sums over j (y) first, as 4-vectors over k (z), then over i (x), and the z weights last:
  // every multiply-add on 4 lanes (Eigen's packets): 6-7 % faster than the scalar triple loop
  // (85.6-86.4 -> 79.6-80.5 ns a call along grazing rays through a 256^3 grid, paired, loaded machine).
  using Array4 = Eigen::Array4d;
  const Array4 wz(w[2][0], w[2][1], w[2][2], w[2][3]), dwz(dw[2][0], dw[2][1], dw[2][2], dw[2][3]);
  const size_t stride_x = size_t(n_[1]) * n_[2];
  const bool contiguous = index[2][3] == index[2][0] + 3;  // no wrap in z: the four are adjacent
  Array4 v = Array4::Zero(), vx = Array4::Zero(), vy = Array4::Zero();
  for (int i = 0; i < 4; ++i) {
    const float* plane = c_.data() + index[0][i] * stride_x;
    Array4 s = Array4::Zero(), sy = Array4::Zero();  // sums over j of the rows, weighted and derived
    for (int j = 0; j < 4; ++j) {
      const float* row = plane + size_t(index[1][j]) * n_[2];
      Array4 r;
      if (contiguous) {
        r = Eigen::Map<const Eigen::Array4f>(row + index[2][0]).cast<double>();
      } else {
        r = Array4(row[index[2][0]], row[index[2][1]], row[index[2][2]], row[index[2][3]]);
      }
      s += w[1][j] * r;
      sy += dw[1][j] * r;
    }
    v += w[0][i] * s;
    vx += dw[0][i] * s;
    vy += w[0][i] * sy;
  }
  const double sum = (v * wz).sum(), dx = (vx * wz).sum(), dy = (vy * wz).sum(), dz = (v * dwz).sum();
  *value = sum;
  *grad = Vec3d(dx, dy, dz) / spacing_;
}

}  // namespace refracta
