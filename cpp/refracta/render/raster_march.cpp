// raster_march: the original mirage editor's renderer (Choi 2017), rebuilt on the CPU. The scene
// is rasterized once from the camera (with a guard band) and shaded per raster pixel; then each
// image pixel's curved ray is marched with the integrator, every step projected into the raster
// view, and the first step that lands behind the depth buffer picks the colour there (the
// crossing refined on the continuous path by bisection).
// Inherent limits, kept on purpose: what no raster pixel shows (outside the view and guard band,
// hidden behind nearer surfaces, below the horizon of a curved Earth) cannot appear, and a step
// that passes behind a thin object's depth counts as a hit on it.
#include "refracta/core/error.h"
#include "refracta/raster/rasterizer.h"
#include "refracta/rays/trace.h"
#include "refracta/render/caster.h"
#include "refracta/render/integrator.h"
#include "refracta/render/raised_sky.h"
#include "refracta/render/renderer.h"
#include "refracta/render/tile_loop.h"

#include <tbb/enumerable_thread_specific.h>

#include <cmath>

namespace refracta {

namespace {

struct RasterFrame {
  const Scene* scene = nullptr;
  RasterView view;
  VisibilityBuffer buffer;
  Image colour;

  // The raster pixel a world point projects to and whether the point lies behind its surface: on
  // or beyond the plane of the triangle that pixel shows, along the point's own line of sight
  // (exact for the drawn triangle). At grazing angles a ground pixel spans hundreds of metres of
  // depth: its centre's depth (or one interpolated between centres, which fails beside the sky at
  // the horizon) put points just above the ground behind it, and a mirage's rays turning a
  // centimetre above the road were taken as hitting it (a trial).
  bool behind(const Vec3d& x, int* px, int* py) const {
    const Vec3d p = view.to_view(x);
    if (view.perspective() && p.z() <= view.near()) return false;
    double u, v;
    view.to_pixel(p, &u, &v);
    if (!(u >= 0.0 && v >= 0.0 && u < buffer.width && v < buffer.height)) return false;
    *px = int(u), *py = int(v);
    const size_t i = buffer.index(*px, *py);
    if (buffer.geometry[i] == VisibilityBuffer::kNone) return false;
    if (!view.perspective()) return p.z() >= buffer.depth[i];
    const SceneMesh& mesh = scene->meshes().at(buffer.geometry[i]);
    const auto& tri = mesh.mesh.triangles.at(buffer.primitive[i]);
    const Vec3d a = view.to_view(mesh.mesh.vertices[tri[0]]), b = view.to_view(mesh.mesh.vertices[tri[1]]),
                c = view.to_view(mesh.mesh.vertices[tri[2]]);
    const Vec3d normal = (b - a).cross(c - a);
    // The line of sight through p, s p, meets the plane at s = n.a / n.p: p is behind it for s <= 1.
    const double toward = normal.dot(p), plane = normal.dot(a);
    if (toward == 0.0) return false;  // along the plane
    const double s_plane = plane / toward;
    return s_plane > 0.0 && s_plane <= 1.0;
  }
};

// The crossing of the depth buffer inside segment a -> b (b behind, a not): bisection on u.
void refine_crossing(const RasterFrame& frame, const RayNode<double>& a, const RayNode<double>& b, int* px, int* py) {
  const PathSegment<double> segment(a, b);
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (lo + hi);
    int x, y;
    if (frame.behind(segment.position(mid), &x, &y)) {
      hi = mid, *px = x, *py = y;
    } else {
      lo = mid;
    }
  }
}

}  // namespace

Image render_raster_march(const RenderScene& render_scene, const Camera& camera, const FieldPtr& field,
                          const RenderOptions& options, WorkControl& control, RenderStats* stats) {
  if (options.spectral) throw_invalid("raster_march renders RGB only (spectral=True needs method='curved')");
  const Scene& scene = render_scene.geometry;
  RasterFrame frame{&scene, RasterView::from_camera(camera, options.guard_band), {}, {}};
  // The whole guard-banded view is rasterized, whatever pixel_bounds the image has: its visibility
  // buffer (20 bytes a pixel) must fit too.
  check_image_memory(frame.view.width(), frame.view.height(), kVisibilityBytesPerPixel, "render (raster_march's view)");
  frame.buffer = rasterize(scene, frame.view, control);
  const Vec3d eye = camera.position();
  // Raster pixels are shaded by the straight-ray integrator (what the original did: the colour
  // of the rasterized surface), spp samples each, seeded as their image pixel.
  RenderOptions straight = options;
  straight.method = RenderMethod::kStraight;
  const Caster caster(scene, nullptr, straight);
  const std::unique_ptr<Integrator> integrator = make_integrator(render_scene, caster, straight);
  integrator->lighting().use_raised_sky(RaisedSky::for_camera(render_scene, camera.position().y()));
  tbb::enumerable_thread_specific<ScratchBuffer> scratch_per_thread;
  const double pixel_angle = options.texture_filter ? camera.pixel_angle() : 0.0;
  frame.colour = render_tiles(frame.view.width(), frame.view.height(), options.tile, control, [&](int x, int y) {
    PathEnd end;
    end.hit = surface_at(scene, frame.buffer, x, y, eye);
    if (!end.hit) return Vec3d::Zero().eval();
    end.direction = (end.hit->point - eye).normalized();
    end.length = end.hit->t;
    // Seeded as the image pixel it covers (as the straight renderer seeds it), guard-band pixels after them.
    const int ix = x - frame.view.offset_x(), iy = y - frame.view.offset_y();
    const bool in_image = ix >= 0 && iy >= 0 && ix < camera.width() && iy < camera.height();
    const uint64_t stream = in_image ? uint64_t(iy) * uint64_t(camera.width()) + uint64_t(ix)
                                     : uint64_t(camera.width()) * uint64_t(camera.height()) +
                                           uint64_t(y) * uint64_t(frame.view.width()) + uint64_t(x);
    Sampler sampler{Rng(options.seed, stream)};
    // spp lighting samples at the raster pixel's surface point (no jitter: the point is the pixel's).
    Spectrum sum = Spectrum::Zero();
    for (int s = 0; s < options.spp; ++s) {
      // Polled every 64 samples as in the film loop: a tile at 4096 spp took 1.7 s to see Ctrl-C.
      if ((s & 63) == 63 && control.cancel.load(std::memory_order_relaxed)) throw Cancelled();
      SampledWavelengths lambda = SampledWavelengths::rgb();
      sum += integrator->li_after(eye, end.direction, end, pixel_angle, lambda, sampler, scratch_per_thread.local(),
                                  nullptr);
    }
    return Vec3d((sum / options.spp).head<3>().matrix());
  });
  const SampledWavelengths rgb = SampledWavelengths::rgb();
  auto sky = [&](const Vec3d& dir) {
    PathEnd escaped;
    escaped.direction = dir;
    return Vec3d(integrator->lighting().escaped(escaped, dir, nullptr, eye.y(), 0.0, true, rgb).head<3>().matrix());
  };
  auto colour_at = [&](int px, int py) {
    const float* c = frame.colour.at(px, py);
    return Vec3d(c[0], c[1], c[2]);
  };

  TraceOptions trace_options;
  trace_options.trace = options.march;
  trace_options.step = options.march == TraceMethod::kRk4 ? options.step : 0.0;
  trace_options.tol = options.tol;
  trace_options.max_length =
      options.march == TraceMethod::kRk4 ? options.step * options.max_steps : options.max_length;
  trace_options.cancel = &control.cancel;
  // Nothing is rasterized below the lowest geometry: the march ends 1 m under it (as curved rays
  // do, caster.cpp) instead of descending out of the field's modelled air.
  trace_options.stop_height = std::min(scene.lowest(), eye.y()) - 1.0;
  control.done = 0;
  // pixel_bounds limits the march; the raster (and its shading) stays the whole view's.
  const PixelBounds bounds = options.bounds_in(camera.width(), camera.height());
  if (stats) stats->samples = int64_t(bounds.width()) * bounds.height();
  return render_tiles(bounds, options.tile, control, [&](int x, int y) {
    const Vec3d dir = camera.direction(x + 0.5, y + 0.5);
    if (!field) {  // a straight ray projects onto its own pixel all along
      const int px = x + frame.view.offset_x(), py = y + frame.view.offset_y();
      return frame.buffer.covered(px, py) ? colour_at(px, py) : sky(dir);
    }
    std::optional<Vec3d> radiance;
    Vec3d last = dir;
    trace(*field, eye, dir, trace_options, [&](const RayNode<double>& a, const RayNode<double>& b) {
      int px, py;
      last = b.v.normalized();
      if (!frame.behind(b.x, &px, &py)) return true;
      refine_crossing(frame, a, b, &px, &py);
      radiance = colour_at(px, py);
      return false;
    });
    return radiance ? *radiance : sky(last);
  });
}

}  // namespace refracta
