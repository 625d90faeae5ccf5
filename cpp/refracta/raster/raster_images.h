// The camera's visibility buffer as images, for inspection from Python (refracta.raster).
#pragma once

#include "refracta/raster/rasterizer.h"
#include "refracta/scene/camera.h"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <utility>

namespace refracta {

struct RasterImages {
  template <class T>
  using Rows = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Rows<float> depth;                    // (H, W) view depth [m], +inf where empty
  Rows<int64_t> geometry, primitive;    // (H, W), -1 where empty
  Rows<float> barycentric;              // (H * W, 3) the triangle's vertex weights, row y * W + x; 0 where empty
  std::pair<int, int> offset{0, 0};     // the camera image's pixel (0, 0) inside the buffers
  RasterStats stats;
};

// Rasterizes the scene seen by `camera`, its image widened by guard_band (a fraction of it) on
// each side, in tiles of `tile` pixels (unset: kRasterTile). Throws std::invalid_argument for a
// tile < 1.
RasterImages rasterize_images(const Scene& scene, const Camera& camera, double guard_band, std::optional<int> tile,
                              WorkControl& control);

}  // namespace refracta
