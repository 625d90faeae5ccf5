// The visibility buffer as images (raster_images.h).
#include "refracta/raster/raster_images.h"

#include "refracta/core/error.h"
#include "refracta/core/image.h"

namespace refracta {

RasterImages rasterize_images(const Scene& scene, const Camera& camera, double guard_band, std::optional<int> tile,
                              WorkControl& control) {
  if (tile && (*tile < 1 || *tile > kMaxTile)) {
    throw_invalid("tile must be a whole number in [1, ", kMaxTile, "] (got ", *tile, ")");
  }
  const RasterView view = RasterView::from_camera(camera, guard_band);
  // The buffer, then its images: float depth, int64 geometry and primitive, three float barycentrics.
  check_image_memory(view.width(), view.height(), kVisibilityBytesPerPixel + 32.0, "rasterize");
  RasterImages out;
  const VisibilityBuffer buffer = rasterize(scene, view, control, tile.value_or(kRasterTile), &out.stats);
  const Eigen::Index h = buffer.height, w = buffer.width;
  out.depth.resize(h, w);
  out.geometry.resize(h, w);
  out.primitive.resize(h, w);
  out.barycentric.resize(h * w, 3);
  for (Eigen::Index i = 0; i < h * w; ++i) {
    const bool covered = buffer.geometry[size_t(i)] != VisibilityBuffer::kNone;
    out.depth.data()[i] = buffer.depth[size_t(i)];
    out.geometry.data()[i] = covered ? int64_t(buffer.geometry[size_t(i)]) : -1;
    out.primitive.data()[i] = covered ? int64_t(buffer.primitive[size_t(i)]) : -1;
    const float b1 = buffer.b1[size_t(i)], b2 = buffer.b2[size_t(i)];
    out.barycentric.row(i) << (covered ? 1.0f - b1 - b2 : 0.0f), b1, b2;
  }
  out.offset = {view.offset_x(), view.offset_y()};
  return out;
}

}  // namespace refracta
