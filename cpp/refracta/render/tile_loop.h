// The one render loop: square tiles of the image over oneTBB, each pixel computed by a callable
// returning its RGB radiance. Renderers differ only in that callable.
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/math.h"
#include "refracta/core/parallel.h"
#include "refracta/render/pixel_bounds.h"

#include <algorithm>
#include <type_traits>

namespace refracta {

// The number of tiles (the progress's units) render_tiles cuts `bounds` into.
inline int64_t tile_count(const PixelBounds& bounds, int tile) {
  return int64_t((bounds.width() + tile - 1) / tile) * ((bounds.height() + tile - 1) / tile);
}

// radiance(x, y) for every pixel of `bounds` (image coordinates) into an image of the bounds'
// size, its pixel (0, 0) being the bounds' (x0, y0); as many channels as radiance returns values
// (a fixed-size Eigen vector: Vec3d for RGB). Progress: one unit a tile (`total`: parallel_for_each).
template <class PixelRadiance>
Image render_tiles(const PixelBounds& bounds, int tile, WorkControl& control, const PixelRadiance& radiance,
                   ProgressTotal total = ProgressTotal::kSet) {
  using Value = decltype(radiance(0, 0));
  constexpr int kChannels = std::decay_t<Value>::RowsAtCompileTime;
  Image image(bounds.width(), bounds.height(), kChannels);
  const int tiles_x = (bounds.width() + tile - 1) / tile;
  parallel_for_each(tile_count(bounds, tile), 1, control, [&](int64_t index) {
    const int x0 = bounds.x0 + int(index % tiles_x) * tile, y0 = bounds.y0 + int(index / tiles_x) * tile;
    for (int y = y0; y < std::min(y0 + tile, bounds.y1); ++y) {
      for (int x = x0; x < std::min(x0 + tile, bounds.x1); ++x) {
        poll_cancel();  // one tile of slow pixels must not hold Ctrl-C up
        const auto value = radiance(x, y);
        float* out = image.at(x - bounds.x0, y - bounds.y0);
        for (int c = 0; c < kChannels; ++c) out[c] = float(value[c]);
      }
    }
  }, total);
  return image;
}

template <class PixelRadiance>
Image render_tiles(int width, int height, int tile, WorkControl& control, const PixelRadiance& radiance) {
  return render_tiles(PixelBounds{0, 0, width, height}, tile, control, radiance);
}

}  // namespace refracta
