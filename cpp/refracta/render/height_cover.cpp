// The highest geometry over a horizontal grid (height_cover.h).
#include "refracta/render/height_cover.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

// Cells along the scene's longer side: the cold sea's 240 km of sea in cells of 940 m, a ship in
// one or two of them, a shadow ray's climb over its 165 m coast in two to four.
constexpr int kCellsAcross = 256;

}  // namespace

HeightCover::HeightCover(const Scene& scene) {
  const Vec3d &lower = scene.lower(), &upper = scene.upper();
  if (!(lower.x() <= upper.x()) || !(lower.z() <= upper.z())) return;  // an empty scene
  x_lo_ = lower.x(), z_lo_ = lower.z();
  cell_ = std::max({upper.x() - lower.x(), upper.z() - lower.z(), 1e-3}) / kCellsAcross;
  columns_ = std::clamp(int(std::ceil((upper.x() - lower.x()) / cell_)), 1, kCellsAcross);
  rows_ = std::clamp(int(std::ceil((upper.z() - lower.z()) / cell_)), 1, kCellsAcross);
  tops_.assign(size_t(columns_) * size_t(rows_), -std::numeric_limits<double>::infinity());
  for (const SceneMesh& m : scene.meshes()) {
    if (scene.removed(m.geometry)) continue;
    const auto& v = m.mesh.vertices;
    for (const auto& t : m.mesh.triangles) {
      const Vec3d &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
      raise(std::min({a.x(), b.x(), c.x()}), std::min({a.z(), b.z(), c.z()}), std::max({a.x(), b.x(), c.x()}),
            std::max({a.z(), b.z(), c.z()}), std::max({a.y(), b.y(), c.y()}));
    }
  }
  for (unsigned g = 0; g < scene.geometry_count(); ++g) {
    if (scene.removed(g)) continue;
    if (const TerrainGrid* terrain = scene.terrain(g)) {
      raise(terrain->lower().x(), terrain->lower().z(), terrain->upper().x(), terrain->upper().z(),
            terrain->upper().y());
    } else if (const Scene::Spheres* spheres = scene.is_spheres(g) ? scene.spheres(g) : nullptr) {
      for (size_t i = 0; i < spheres->centres.size(); ++i) {
        const Vec3d& c = spheres->centres[i];
        const double r = spheres->radii[i];
        raise(c.x() - r, c.z() - r, c.x() + r, c.z() + r, c.y() + r);
      }
    }
  }
}

int HeightCover::column(double x) const { return std::clamp(int(std::floor((x - x_lo_) / cell_)), 0, columns_ - 1); }

int HeightCover::row(double z) const { return std::clamp(int(std::floor((z - z_lo_) / cell_)), 0, rows_ - 1); }

void HeightCover::raise(double x0, double z0, double x1, double z1, double top) {
  // Widened by a hair: a box that touches a cell's border counts on both sides of it (the
  // traversal may pass a corner through either neighbour), and Embree's float vertices (6e-8 of
  // a coordinate off ours) stay inside it.
  const double hair = 1e-6 * (cell_ + std::max({std::abs(x0), std::abs(x1), std::abs(z0), std::abs(z1)}));
  const int c1 = column(x1 + hair), r1 = row(z1 + hair);
  for (int r = row(z0 - hair); r <= r1; ++r) {
    for (int c = column(x0 - hair); c <= c1; ++c) {
      double& cell = tops_[size_t(r) * size_t(columns_) + size_t(c)];
      cell = std::max(cell, top);
    }
  }
}

double HeightCover::highest(double x0, double z0, double x1, double z1) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!(std::isfinite(x0) && std::isfinite(x1) && std::isfinite(z0) && std::isfinite(z1))) return kInf;
  if (tops_.empty()) return -kInf;
  // The part of the segment over the grid (Liang-Barsky): parameters t0 <= t <= t1 of x0 + t dx.
  const double dx = x1 - x0, dz = z1 - z0;
  double t0 = 0.0, t1 = 1.0;
  auto clip = [&](double p, double q) {  // keeps the t where p t <= q
    if (p == 0.0) return q >= 0.0;
    const double t = q / p;
    if (p < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return t0 <= t1;
  };
  // The grid and a cell around it: its far edge x_lo_ + columns_ cell_ may round below the scene's,
  // whose geometry the cells at the edge hold (cells beyond hold nothing: the walk stops there).
  const double x_lo = x_lo_ - cell_, z_lo = z_lo_ - cell_;
  const double x_hi = x_lo_ + (columns_ + 1) * cell_, z_hi = z_lo_ + (rows_ + 1) * cell_;
  if (!clip(-dx, x0 - x_lo) || !clip(dx, x_hi - x0) || !clip(-dz, z0 - z_lo) || !clip(dz, z_hi - z0)) return -kInf;
  // The cells it passes, in order (Amanatides and Woo 1987, "A Fast Voxel Traversal Algorithm").
  const double xa = x0 + t0 * dx, za = z0 + t0 * dz;
  int c = column(xa), r = row(za);
  const int c_end = column(x0 + t1 * dx), r_end = row(z0 + t1 * dz);
  const int step_c = dx > 0.0 ? 1 : -1, step_r = dz > 0.0 ? 1 : -1;
  // The parameter (in units of t) where the segment next crosses a column's and a row's border.
  double next_c = dx != 0.0 ? (x_lo_ + (c + (dx > 0.0 ? 1 : 0)) * cell_ - x0) / dx : kInf;
  double next_r = dz != 0.0 ? (z_lo_ + (r + (dz > 0.0 ? 1 : 0)) * cell_ - z0) / dz : kInf;
  const double per_c = dx != 0.0 ? cell_ / std::abs(dx) : kInf, per_r = dz != 0.0 ? cell_ / std::abs(dz) : kInf;
  double out = -kInf;
  for (int visited = 0;; ++visited) {
    if (visited >= kMostCells) return kInf;
    out = std::max(out, tops_[size_t(r) * size_t(columns_) + size_t(c)]);
    if ((c == c_end && r == r_end) || !(std::min(next_c, next_r) <= t1)) break;
    if (next_c < next_r) {
      c += step_c, next_c += per_c;
    } else {
      r += step_r, next_r += per_r;
    }
    if (c < 0 || c >= columns_ || r < 0 || r >= rows_) break;
  }
  return out;
}

}  // namespace refracta
