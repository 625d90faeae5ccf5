// Terrain grids (terrain.h): validation, holes, the patches Embree traces, per-sample normals.
#include "refracta/scene/terrain.h"

#include "refracta/core/error.h"
#include "refracta/scene/embree_scene.h"  // kSceneReach

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

// Floats of padding after the last vertex: Embree reads vertices with 16-byte loads.
constexpr size_t kVertexPadding = 4;

}  // namespace

TerrainGrid::TerrainGrid(int rows, int cols, std::vector<float> positions, const Eigen::Matrix<double, 2, 3>& uv_from_index)
    : rows_(rows), cols_(cols), vertices_(std::move(positions)), uv_from_index_(uv_from_index) {
  if (rows < 2 || cols < 2) throw_invalid("add_terrain: a terrain needs at least 2 x 2 samples (got ", rows, " x ", cols, ")");
  const size_t n = size_t(rows) * size_t(cols);
  // Embree's grid start index and the hit's primitive (2 per cell) are 32-bit.
  if (2 * n >= size_t(std::numeric_limits<uint32_t>::max())) {
    throw_invalid("add_terrain: ", rows, " x ", cols, " samples are more than one grid holds (2^31); split it into tiles");
  }
  if (vertices_.size() != 3 * n) {
    throw_invalid("add_terrain: positions must hold 3 * rows * cols = ", 3 * n, " floats (got ", vertices_.size(), ")");
  }
  if (!uv_from_index_.allFinite()) throw_invalid("add_terrain: uv_from_index must be finite");
  // Holes, bounds and the 1e7 m range.
  valid_.assign(n, false);
  lower_ = Vec3d::Constant(std::numeric_limits<double>::infinity()), upper_ = -lower_;
  size_t first_valid = n;
  for (size_t i = 0; i < n; ++i) {
    const Vec3d p(vertices_[3 * i], vertices_[3 * i + 1], vertices_[3 * i + 2]);
    if (!is_finite(p)) continue;
    if (p.cwiseAbs().maxCoeff() > kSceneReach) {
      throw_invalid("add_terrain: sample (row ", i / size_t(cols), ", column ", i % size_t(cols), ") at (", p.x(), ", ", p.y(),
                    ", ", p.z(), ") is beyond 1e7 m from the origin (Embree's single precision)");
    }
    valid_[i] = true;
    if (first_valid == n) first_valid = i;
    lower_ = lower_.cwiseMin(p), upper_ = upper_.cwiseMax(p);
  }
  if (first_valid == n) throw_invalid("add_terrain: every sample is a hole (NaN or void): nothing to add");
  for (size_t i = 0; i < n; ++i) {  // finite stand-ins, never part of a patch
    if (!valid_[i]) std::copy_n(&vertices_[3 * first_valid], 3, &vertices_[3 * i]);
  }
  vertices_.resize(3 * n + kVertexPadding, 0.0f);

  // Patches: whole blocks where every cell is valid, else runs of valid cells one row high.
  const auto cell_valid = [&](int r, int c) { return valid(r, c) && valid(r + 1, c) && valid(r, c + 1) && valid(r + 1, c + 1); };
  constexpr int kBlock = kMaxPatchVertices - 1;  // cells
  for (int br = 0; br < rows - 1; br += kBlock) {
    const int nr = std::min(kBlock, rows - 1 - br);
    for (int bc = 0; bc < cols - 1; bc += kBlock) {
      const int nc = std::min(kBlock, cols - 1 - bc);
      bool whole = true;
      for (int r = br; r < br + nr && whole; ++r) {
        for (int c = bc; c < bc + nc && whole; ++c) whole = cell_valid(r, c);
      }
      if (whole) {
        patches_.push_back({uint32_t(br), uint32_t(bc), uint16_t(nr + 1), uint16_t(nc + 1)});
        continue;
      }
      for (int r = br; r < br + nr; ++r) {
        for (int c = bc; c < bc + nc;) {
          if (!cell_valid(r, c)) {
            ++c;
            continue;
          }
          int end = c;
          while (end < bc + nc && cell_valid(r, end)) ++end;
          patches_.push_back({uint32_t(r), uint32_t(c), uint16_t(2), uint16_t(end - c + 1)});
          c = end;
        }
      }
    }
  }
  if (patches_.empty()) throw_invalid("add_terrain: no cell has four valid corners (the holes leave no surface)");
}

Vec3d TerrainGrid::position(int row, int col) const {
  const size_t i = 3 * (size_t(row) * size_t(cols_) + size_t(col));
  return Vec3d(vertices_[i], vertices_[i + 1], vertices_[i + 2]);
}

std::vector<float> TerrainGrid::positions_with_holes() const {
  std::vector<float> out(vertices_.begin(), vertices_.begin() + std::ptrdiff_t(3 * vertex_count()));
  for (size_t i = 0; i < vertex_count(); ++i) {
    if (!valid_[i]) out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = std::numeric_limits<float>::quiet_NaN();
  }
  return out;
}

std::array<int, 2> TerrainGrid::cell_of(unsigned patch, double u, double v) const {
  const TerrainPatch& p = patches_.at(patch);
  const int dc = std::clamp(int(std::floor(u * (p.cols - 1))), 0, p.cols - 2);
  const int dr = std::clamp(int(std::floor(v * (p.rows - 1))), 0, p.rows - 2);
  return {int(p.row) + dr, int(p.col) + dc};
}

std::array<std::array<int, 2>, 3> TerrainGrid::triangle(int row, int col, int k) const {
  if (k == 0) return {{{row, col}, {row + 1, col}, {row, col + 1}}};
  return {{{row + 1, col + 1}, {row, col + 1}, {row + 1, col}}};
}

Vec3d TerrainGrid::normal(int row, int col) const {
  // Central differences where both neighbours are valid, one-sided where one is.
  const auto difference = [&](int r0, int c0, int r1, int c1) -> Vec3d {
    const bool in0 = r0 >= 0 && c0 >= 0 && valid(r0, c0), in1 = r1 < rows_ && c1 < cols_ && valid(r1, c1);
    const Vec3d lo = in0 ? position(r0, c0) : position(row, col), hi = in1 ? position(r1, c1) : position(row, col);
    return hi - lo;
  };
  const Vec3d along_rows = difference(row - 1, col, row + 1, col);  // +z for the array form
  const Vec3d along_cols = difference(row, col - 1, row, col + 1);  // +x
  const Vec3d n = along_rows.cross(along_cols);                     // z x x = +y: up
  const double length = n.norm();
  return length > 0.0 ? Vec3d(n / length) : n;  // unit, so interpolation weighs each corner alike
}

std::shared_ptr<const TerrainGrid> terrain_grid(const std::vector<size_t>& shape, std::vector<float> positions,
                                                const std::vector<size_t>& uv_shape,
                                                const std::vector<double>& uv_from_index) {
  if (shape.size() != 3 || shape[2] != 3) {
    throw_invalid("add_terrain: positions must be a (rows, cols, 3) array (got ndim ", shape.size(), ")");
  }
  if (uv_shape.size() != 2 || uv_shape[0] != 2 || uv_shape[1] != 3) {
    throw_invalid("add_terrain: uv_from_index must be a (2, 3) array");
  }
  const Eigen::Map<const Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> uv(uv_from_index.data());
  return std::make_shared<const TerrainGrid>(int(shape[0]), int(shape[1]), std::move(positions), uv);
}

}  // namespace refracta
