// A float RGB(A) image in row-major order, top row first (as numpy (H, W, C)).
#pragma once

#include "refracta/core/memory.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace refracta {

// The largest square tile a render or a rasterization is cut into [pixels]: 2^16, wider than any
// use has for one. With a tile near 2^31 the tile count (side + tile - 1) / tile overflowed an int:
// an image came back unrendered (black) and the rasterizer's bins were indexed at -1.
constexpr int kMaxTile = 1 << 16;

struct Image {
  int width = 0, height = 0, channels = 3;
  std::vector<float> pixels;  // width * height * channels

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0.0f) {}
  float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * channels]; }
};

// `image` with the one channel of `extra` (the same size) appended as its last.
inline Image with_channel(const Image& image, const Image& extra) {
  Image out(image.width, image.height, image.channels + 1);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::copy_n(image.at(x, y), image.channels, out.at(x, y));
      out.at(x, y)[image.channels] = extra.at(x, y)[0];
    }
  }
  return out;
}

// Refuses, before anything is allocated, an image of width x height pixels whose buffers
// (bytes_per_pixel in all) would not fit in physical memory: std::invalid_argument (ValueError)
// naming `what`, the size and the bytes. Without the guard a 100000 x 100000 render asked the
// allocator for 120 GB and was killed, or swapped for minutes.
inline void check_image_memory(int64_t width, int64_t height, double bytes_per_pixel, const char* what) {
  const double bytes = double(width) * double(height) * bytes_per_pixel;
  if (double memory; beyond_memory(bytes, &memory)) {
    throw std::invalid_argument(std::string(what) + ": a " + std::to_string(width) + " x " + std::to_string(height) +
                                " image needs at least " + whole_bytes(bytes) + " bytes (" + whole_bytes(bytes / 1e9) +
                                " GB), more than this machine's " + whole_bytes(memory / 1e9) + " GB of memory");
  }
}

}  // namespace refracta
