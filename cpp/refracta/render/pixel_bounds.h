// A rectangle of an image's pixels (pbrt-v4's film "pixelbounds"): renders of part of an image,
// every pixel exactly as in the whole render, for tiles rendered on other machines.
#pragma once

namespace refracta {

// Pixels [x0, x1) x [y0, y1) of an image, x right, y down (pixel (i, j) as Camera's).
struct PixelBounds {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

}  // namespace refracta
