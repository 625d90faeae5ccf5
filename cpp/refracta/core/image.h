// A float RGB(A) image in row-major order, top row first (as numpy (H, W, C)).
#pragma once

#include <cstddef>
#include <vector>

namespace refracta {

struct Image {
  int width = 0, height = 0, channels = 3;
  std::vector<float> pixels;  // width * height * channels

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0.0f) {}
  float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * channels]; }
};

}  // namespace refracta
