// RasterView constructors.
#include "refracta/raster/raster_view.h"

#include "refracta/core/error.h"

#include <cmath>
#include <limits>

namespace refracta {

RasterView RasterView::from_camera(const Camera& camera, double guard_band, double near) {
  if (!(guard_band >= 0.0 && guard_band <= 2.0)) throw_invalid("guard_band must be in [0, 2] (got ", guard_band, ")");
  if (!(near > 0.0) || !std::isfinite(near)) throw_invalid("near must be > 0 (got ", near, ")");
  RasterView view;
  view.origin_ = camera.position();
  view.forward_ = camera.forward();
  view.right_ = camera.right();
  view.up_ = camera.up();
  view.offset_x_ = int(std::ceil(guard_band * camera.width()));
  view.offset_y_ = int(std::ceil(guard_band * camera.height()));
  view.width_ = camera.width() + 2 * view.offset_x_;
  view.height_ = camera.height() + 2 * view.offset_y_;
  const double tan_y = camera.tan_half(), tan_x = tan_y * camera.width() / camera.height();
  view.half_x_ = tan_x * view.width_ / camera.width();
  view.half_y_ = tan_y * view.height_ / camera.height();
  view.near_ = near;
  view.perspective_ = true;
  return view;
}

RasterView RasterView::framed(const Vec3d& origin, const Vec3d& direction, const Vec3d& up, const char* what) {
  if (!is_finite(origin) || !is_finite(direction) || direction.norm() == 0.0) {
    throw_invalid(what, " view: origin and direction must be finite, direction non-zero");
  }
  RasterView view;
  view.forward_ = direction.normalized();
  const Vec3d side = view.forward_.cross(up);
  if (side.norm() < 1e-9) throw_invalid(what, " view: up must not be parallel to the direction");
  view.right_ = side.normalized();
  view.up_ = view.right_.cross(view.forward_);
  view.origin_ = origin;
  return view;
}

RasterView RasterView::perspective(const Vec3d& origin, const Vec3d& direction, const Vec3d& up, double tan_half,
                                   int size, double near) {
  if (!(tan_half > 0.0) || !std::isfinite(tan_half) || size < 1 || !(near > 0.0)) {
    throw_invalid("perspective view: the field of view must be in (0, 180) deg, size >= 1, near > 0");
  }
  RasterView view = framed(origin, direction, up, "perspective");
  view.half_x_ = view.half_y_ = tan_half;
  view.width_ = view.height_ = size;
  view.near_ = near;
  view.perspective_ = true;
  return view;
}

RasterView RasterView::orthographic(const Vec3d& centre, const Vec3d& direction, const Vec3d& up, double half_width,
                                    double half_height, int width, int height) {
  if (!(half_width > 0.0) || !(half_height > 0.0) || width < 1 || height < 1) {
    throw_invalid("orthographic view: extents must be > 0 and size at least 1x1");
  }
  RasterView view = framed(centre, direction, up, "orthographic");
  view.half_x_ = half_width;
  view.half_y_ = half_height;
  view.width_ = width;
  view.height_ = height;
  view.near_ = -std::numeric_limits<double>::infinity();
  view.perspective_ = false;
  return view;
}

}  // namespace refracta
