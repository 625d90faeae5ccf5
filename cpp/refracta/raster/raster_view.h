// A view to rasterize from: a pinhole camera (perspective) or a directional light (orthographic),
// as an orthonormal frame, image extents and a pixel grid. Pixel (i, j) covers [i, i+1) x [j, j+1)
// with v down, like Camera.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/camera.h"

namespace refracta {

class RasterView {
 public:
  // The camera's view, widened by guard_band (a fraction of the image size added on each side;
  // the pixel grid grows with it so pixels keep their size). near [m]: the clipping distance.
  static RasterView from_camera(const Camera& camera, double guard_band = 0.0, double near = kCameraNear);
  // A camera's clipping distance [m]: depths are stored linearly (float, 6e-8 relative at every
  // depth), so it costs no precision; at 5 cm a lens 2 cm above a hot plate saw sky through it.
  static constexpr double kCameraNear = 1e-4;
  // A square perspective view from `origin` along `direction` with half field of view
  // atan(tan_half) each way, on a size x size grid (a spot light's shadow map).
  static RasterView perspective(const Vec3d& origin, const Vec3d& direction, const Vec3d& up, double tan_half,
                                int size, double near);
  // An orthographic view along `direction` centred on `centre`, covering half_width x half_height
  // [m] across, on a width x height grid (a directional light's shadow map).
  static RasterView orthographic(const Vec3d& centre, const Vec3d& direction, const Vec3d& up, double half_width,
                                 double half_height, int width, int height);

  bool perspective() const { return perspective_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double near() const { return near_; }
  // Pixels of the camera image that pixel (0, 0) of this view is offset by (the guard band).
  int offset_x() const { return offset_x_; }
  int offset_y() const { return offset_y_; }

  // (x, y, depth) in the view frame: x right, y up, depth along the view axis [m] (for an
  // orthographic view, from the plane through the centre).
  Vec3d to_view(const Vec3d& world) const {
    const Vec3d d = world - origin_;
    return Vec3d(d.dot(right_), d.dot(up_), d.dot(forward_));
  }
  // Pixel coordinates (u, v) of a view-frame point (perspective: depth must be > 0).
  void to_pixel(const Vec3d& view, double* u, double* v) const {
    const double scale = perspective_ ? 1.0 / view.z() : 1.0;
    *u = 0.5 * width_ * (1.0 + view.x() * scale / half_x_);
    *v = 0.5 * height_ * (1.0 - view.y() * scale / half_y_);
  }
  // The half extents at depth 1 (perspective: tangents of the half angles) or in metres.
  double half_x() const { return half_x_; }
  double half_y() const { return half_y_; }
  // The width of one pixel [m] at view depth z.
  double pixel_width(double z) const { return 2.0 * half_x_ * (perspective_ ? z : 1.0) / width_; }

 private:
  // A view at origin looking along direction with `up` roughly up (validated; extents unset).
  static RasterView framed(const Vec3d& origin, const Vec3d& direction, const Vec3d& up, const char* what);

  Vec3d origin_, right_, up_, forward_;
  double half_x_ = 1.0, half_y_ = 1.0, near_ = 0.05;
  int width_ = 1, height_ = 1, offset_x_ = 0, offset_y_ = 0;
  bool perspective_ = true;
};

}  // namespace refracta
