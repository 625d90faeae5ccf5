// The one render loop: square tiles of the image over oneTBB, each pixel computed by a callable
// returning its RGB radiance. Renderers differ only in that callable.
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/math.h"
#include "refracta/core/parallel.h"

#include <algorithm>

namespace refracta {

template <class PixelRadiance>
Image render_tiles(int width, int height, int tile, WorkControl& control, const PixelRadiance& radiance) {
  Image image(width, height, 3);
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  parallel_for_each(int64_t(tiles_x) * tiles_y, 1, control, [&](int64_t index) {
    const int x0 = int(index % tiles_x) * tile, y0 = int(index / tiles_x) * tile;
    for (int y = y0; y < std::min(y0 + tile, height); ++y) {
      for (int x = x0; x < std::min(x0 + tile, width); ++x) {
        const Vec3d value = radiance(x, y);
        float* out = image.at(x, y);
        for (int c = 0; c < 3; ++c) out[c] = float(value[c]);
      }
    }
  });
  return image;
}

}  // namespace refracta
