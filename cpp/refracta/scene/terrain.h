// Terrain: a height field sampled on a regular grid of vertices, traced as Embree grid geometry
// (embree_scene.cpp turns its patches into RTCGrid primitives; this file knows nothing of Embree).
// One float3 position per sample, given per vertex so that a geographic grid carries its
// azimuthal-equidistant, Earth-flattened positions; a sample with a non-finite coordinate is a
// hole (SRTM voids): cells touching it are left out, so no NaN ever reaches Embree. Shading
// normals come from the neighbouring samples (central differences), uvs from an affine map of
// (column, row), so neither is stored: a 3601 x 3601 tile costs 12 bytes per sample here.
//
// Layout: row r, column c is sample r * cols + c; rows run along +z and columns along +x for the
// array form (refracta.terrain), so the surface's front -- (p[r+1][c] - p) x (p[r][c+1] - p) -- is up.
#pragma once

#include "refracta/core/math.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace refracta {

// A rectangle of vertices [row, row + rows) x [col, col + cols) all of whose cells have four valid
// corners: one Embree grid primitive (at most kMaxPatchVertices a side).
struct TerrainPatch {
  uint32_t row, col;
  uint16_t rows, cols;  // vertices, >= 2
};

// Vertices a patch spans at most a side. Embree allows 32767 (RTCGrid's 16-bit width); its BVH
// builder splits every grid into 3 x 3-vertex sub-grids whatever the size, so a smaller patch
// costs nothing and keeps the pieces around holes (rows of single cells) the exception.
constexpr int kMaxPatchVertices = 257;

class TerrainGrid {
 public:
  // positions: 3 * rows * cols floats (x, y, z) [m], row-major; rows, cols >= 2; every finite
  // coordinate within 1e7 m (Embree's float range). uv_from_index maps (col, row, 1) to the
  // texture coordinates (u right, v up). Throws std::invalid_argument on bad input (no valid cell).
  TerrainGrid(int rows, int cols, std::vector<float> positions, const Eigen::Matrix<double, 2, 3>& uv_from_index);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  // The Embree vertex buffer: holes replaced by a valid sample's position (never referenced by a
  // patch), padded for Embree's 16-byte loads.
  const float* vertex_buffer() const { return vertices_.data(); }
  size_t vertex_count() const { return size_t(rows_) * size_t(cols_); }
  const std::vector<TerrainPatch>& patches() const { return patches_; }
  bool valid(int row, int col) const { return valid_[size_t(row) * size_t(cols_) + size_t(col)]; }
  Vec3d position(int row, int col) const;
  // The positions as given (NaN at holes), for pickling.
  std::vector<float> positions_with_holes() const;
  const Eigen::Matrix<double, 2, 3>& uv_from_index() const { return uv_from_index_; }
  Eigen::Vector2d uv(double row, double col) const { return uv_from_index_ * Eigen::Vector3d(col, row, 1.0); }
  // Bounds of the valid samples [m].
  const Vec3d& lower() const { return lower_; }
  const Vec3d& upper() const { return upper_; }
  size_t cell_count() const { return size_t(rows_ - 1) * size_t(cols_ - 1); }

  // The cell (row, col) of Embree's hit at grid coordinates (u, v) in [0, 1] on patch `patch`.
  std::array<int, 2> cell_of(unsigned patch, double u, double v) const;
  // Triangle k (0 or 1) of cell (row, col), as (row, col) of its three vertices, counter-clockwise
  // seen from above; the two share the diagonal (row + 1, col) -- (row, col + 1), as Embree's
  // quads (v0 v1 v3, v2 v3 v1) do.
  std::array<std::array<int, 2>, 3> triangle(int row, int col, int k) const;
  // The smooth unit shading normal at a sample: the cross product of the central differences along the
  // rows and the columns (one-sided beside a hole or an edge); zero when a sample has no neighbour.
  Vec3d normal(int row, int col) const;

 private:
  int rows_, cols_;
  std::vector<float> vertices_;
  std::vector<bool> valid_;
  std::vector<TerrainPatch> patches_;
  Eigen::Matrix<double, 2, 3> uv_from_index_;
  Vec3d lower_, upper_;
};

// The grid Scene._add_terrain_grid builds from arrays: positions of shape (rows, cols, 3) and
// uv_from_index of shape (2, 3), both row-major. ValueError for other shapes.
std::shared_ptr<const TerrainGrid> terrain_grid(const std::vector<size_t>& shape, std::vector<float> positions,
                                                const std::vector<size_t>& uv_shape,
                                                const std::vector<double>& uv_from_index);

}  // namespace refracta
