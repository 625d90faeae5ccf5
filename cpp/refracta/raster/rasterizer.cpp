// The rasterizer: clip, project, bin, fill.
#include "refracta/raster/rasterizer.h"

#include "refracta/core/error.h"
#include "refracta/core/image.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

namespace refracta {

namespace {

// A polygon vertex during clipping: view-frame position and the barycentric weights it carries.
struct ClipVertex {
  Vec3d p;
  Vec3d bary;
};

// A clipped triangle in pixel coordinates.
struct ScreenTriangle {
  double u[3], v[3], depth[3];
  Vec3d bary[3];
  uint32_t geometry, primitive;
  bool transparent = false;
  bool cutout = false;  // Scene::set_cutout: drawn where its opacity is at least 1/2
};

// A rasterized cut-out's threshold: the ray renderers' stochastic test, made binary for one sample.
constexpr double kCutoutDrawn = 0.5;

// Guard band of the clipping planes: screen coordinates stay within 4x the view (exact
// arithmetic of edge functions in double for any realistic image size).
constexpr double kGuard = 4.0;

// Sutherland-Hodgman against the half-space plane(p) >= 0.
template <class Plane>
void clip(std::vector<ClipVertex>* polygon, const Plane& plane) {
  std::vector<ClipVertex> out;
  const size_t n = polygon->size();
  for (size_t i = 0; i < n; ++i) {
    const ClipVertex& a = (*polygon)[i];
    const ClipVertex& b = (*polygon)[(i + 1) % n];
    const double fa = plane(a.p), fb = plane(b.p);
    if (fa >= 0.0) out.push_back(a);
    if ((fa >= 0.0) != (fb >= 0.0)) {
      // From the edge's lexicographically smaller end: the two triangles that share the edge walk
      // it in opposite directions, and must cut it at the same point to the last bit (no crack).
      const bool forward = std::lexicographical_compare(a.p.data(), a.p.data() + 3, b.p.data(), b.p.data() + 3);
      const ClipVertex& from = forward ? a : b;
      const ClipVertex& to = forward ? b : a;
      const double f_from = forward ? fa : fb, f_to = forward ? fb : fa;
      const double t = f_from / (f_from - f_to);
      out.push_back({from.p + t * (to.p - from.p), from.bary + t * (to.bary - from.bary)});
    }
  }
  *polygon = std::move(out);
}

void clip_to_view(const RasterView& view, std::vector<ClipVertex>* polygon) {
  const double gx = kGuard * view.half_x(), gy = kGuard * view.half_y();
  if (view.perspective()) {
    const double near = view.near();
    clip(polygon, [near](const Vec3d& p) { return p.z() - near; });
    clip(polygon, [gx](const Vec3d& p) { return gx * p.z() - p.x(); });
    clip(polygon, [gx](const Vec3d& p) { return gx * p.z() + p.x(); });
    clip(polygon, [gy](const Vec3d& p) { return gy * p.z() - p.y(); });
    clip(polygon, [gy](const Vec3d& p) { return gy * p.z() + p.y(); });
  } else {
    clip(polygon, [gx](const Vec3d& p) { return gx - p.x(); });
    clip(polygon, [gx](const Vec3d& p) { return gx + p.x(); });
    clip(polygon, [gy](const Vec3d& p) { return gy - p.y(); });
    clip(polygon, [gy](const Vec3d& p) { return gy + p.y(); });
  }
}

// Edge function of (a -> b) at p: twice the signed area of (a, b, p). Evaluated from the edge's
// lexicographically smaller end and negated for the other direction, so that the two triangles
// sharing an edge get exactly opposite values at a pixel centre: with the top-left rule one of them
// owns every pixel on it (a camera looking along the diagonal of a ground's two triangles showed
// the sky through a row of pixels: rounding put them outside both, a trial).
inline double edge(double ax, double ay, double bx, double by, double px, double py) {
  if (ax < bx || (ax == bx && ay < by)) return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
  return -((ax - bx) * (py - by) - (ay - by) * (px - bx));
}

// Top-left rule for a triangle of positive area in (u right, v down) pixel coordinates: pixels
// exactly on an edge belong to it only if it is a top edge (horizontal, interior below) or a left edge.
inline bool owns_boundary(double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  return (dy == 0.0 && dx < 0.0) || dy > 0.0;
}

// Calls emit(x, y, depth, barycentrics) for every pixel centre the triangle covers in the tile.
template <class Emit>
void fill(const ScreenTriangle& t, bool perspective, int x0, int y0, int x1, int y1, int64_t* fragments,
          const Emit& emit) {
  double area = edge(t.u[0], t.v[0], t.u[1], t.v[1], t.u[2], t.v[2]);
  if (area == 0.0 || !std::isfinite(area)) return;
  int i0 = 0, i1 = 1, i2 = 2;
  if (area < 0.0) std::swap(i1, i2), area = -area;
  const double ax = t.u[i0], ay = t.v[i0], bx = t.u[i1], by = t.v[i1], cx = t.u[i2], cy = t.v[i2];
  const int xa = std::max(x0, int(std::floor(std::min({ax, bx, cx}) - 0.5))),
            xb = std::min(x1, int(std::ceil(std::max({ax, bx, cx}) - 0.5)) + 1);
  const int ya = std::max(y0, int(std::floor(std::min({ay, by, cy}) - 0.5))),
            yb = std::min(y1, int(std::ceil(std::max({ay, by, cy}) - 0.5)) + 1);
  const bool own0 = owns_boundary(bx, by, cx, cy), own1 = owns_boundary(cx, cy, ax, ay),
             own2 = owns_boundary(ax, ay, bx, by);
  const int order[3] = {i0, i1, i2};
  for (int y = ya; y < yb; ++y) {
    const double py = y + 0.5;
    for (int x = xa; x < xb; ++x) {
      const double px = x + 0.5;
      const double w0 = edge(bx, by, cx, cy, px, py), w1 = edge(cx, cy, ax, ay, px, py),
                   w2 = edge(ax, ay, bx, by, px, py);
      if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
      if ((w0 == 0.0 && !own0) || (w1 == 0.0 && !own1) || (w2 == 0.0 && !own2)) continue;
      ++*fragments;
      const double l[3] = {w0 / area, w1 / area, w2 / area};
      double depth;
      Vec3d bary;
      if (perspective) {  // attributes are linear in screen space once divided by depth
        double inv = 0.0;
        Vec3d sum = Vec3d::Zero();
        for (int k = 0; k < 3; ++k) {
          inv += l[k] / t.depth[order[k]];
          sum += (l[k] / t.depth[order[k]]) * t.bary[order[k]];
        }
        depth = 1.0 / inv;
        bary = sum * depth;
      } else {
        depth = l[0] * t.depth[order[0]] + l[1] * t.depth[order[1]] + l[2] * t.depth[order[2]];
        bary = l[0] * t.bary[order[0]] + l[1] * t.bary[order[1]] + l[2] * t.bary[order[2]];
      }
      emit(x, y, depth, bary);
    }
  }
}

}  // namespace

int64_t FragmentLists::total() const {
  int64_t n = 0;
  for (const auto& list : lists) n += int64_t(list.size());
  return n;
}

namespace {

// rasterize's work; `surfaces` false: the depths alone (the other buffers left empty).
VisibilityBuffer draw(const Scene& scene, const RasterView& view, WorkControl& control, int tile, RasterStats* stats,
                      const std::vector<bool>* transparent, FragmentLists* fragments, bool surfaces) {
  if (transparent && !fragments) throw_invalid("rasterize: transparent geometry needs fragment lists");
  if (tile < 1 || tile > kMaxTile) throw_invalid("tile must be in [1, ", kMaxTile, "] pixels (got ", tile, ")");
  // Clip and project every triangle.
  std::vector<ScreenTriangle> screen;
  int64_t submitted = 0;
  std::vector<ClipVertex> polygon;
  for (const SceneMesh& mesh : scene.meshes()) {
    const auto& vertices = mesh.mesh.vertices;
    for (size_t p = 0; p < mesh.mesh.triangles.size(); ++p) {
      ++submitted;
      const auto& tri = mesh.mesh.triangles[p];
      polygon = {{view.to_view(vertices[tri[0]]), Vec3d(1, 0, 0)},
                 {view.to_view(vertices[tri[1]]), Vec3d(0, 1, 0)},
                 {view.to_view(vertices[tri[2]]), Vec3d(0, 0, 1)}};
      clip_to_view(view, &polygon);
      if (polygon.size() < 3) continue;
      ScreenTriangle t;
      t.geometry = mesh.geometry;
      t.primitive = uint32_t(p);
      t.transparent = transparent && mesh.geometry < transparent->size() && (*transparent)[mesh.geometry];
      t.cutout = scene.cutout(mesh.geometry) >= 0;
      double u[8], v[8];
      for (size_t k = 0; k < polygon.size(); ++k) view.to_pixel(polygon[k].p, &u[k], &v[k]);
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {  // a fan over the clipped polygon
        const size_t idx[3] = {0, k, k + 1};
        for (int j = 0; j < 3; ++j) {
          t.u[j] = u[idx[j]];
          t.v[j] = v[idx[j]];
          t.depth[j] = polygon[idx[j]].p.z();
          t.bary[j] = polygon[idx[j]].bary;
        }
        screen.push_back(t);
      }
    }
  }

  // Bin to tiles by bounding box.
  const int tiles_x = (view.width() + tile - 1) / tile, tiles_y = (view.height() + tile - 1) / tile;
  std::vector<std::vector<uint32_t>> bins(size_t(tiles_x) * tiles_y);
  for (size_t i = 0; i < screen.size(); ++i) {
    if (i % 4096 == 0) poll_cancel();
    const ScreenTriangle& t = screen[i];
    const double umin = std::min({t.u[0], t.u[1], t.u[2]}), umax = std::max({t.u[0], t.u[1], t.u[2]});
    const double vmin = std::min({t.v[0], t.v[1], t.v[2]}), vmax = std::max({t.v[0], t.v[1], t.v[2]});
    if (umax < 0.0 || vmax < 0.0 || umin > view.width() || vmin > view.height()) continue;
    const int tx0 = std::clamp(int(std::floor(umin)) / tile, 0, tiles_x - 1);
    const int tx1 = std::clamp(int(std::floor(umax)) / tile, 0, tiles_x - 1);
    const int ty0 = std::clamp(int(std::floor(vmin)) / tile, 0, tiles_y - 1);
    const int ty1 = std::clamp(int(std::floor(vmax)) / tile, 0, tiles_y - 1);
    for (int ty = ty0; ty <= ty1; ++ty) {
      for (int tx = tx0; tx <= tx1; ++tx) bins[size_t(ty) * tiles_x + tx].push_back(uint32_t(i));
    }
  }

  VisibilityBuffer out;
  out.width = view.width();
  out.height = view.height();
  const size_t pixels = size_t(out.width) * out.height;
  // Filling a shadow map's buffers (8192^2 texels: 0.1-0.3 s each) polls Ctrl-C between them.
  poll_cancel();
  out.depth.assign(pixels, std::numeric_limits<float>::infinity());
  if (surfaces) {
    poll_cancel();
    out.geometry.assign(pixels, VisibilityBuffer::kNone);
    poll_cancel();
    out.primitive.assign(pixels, VisibilityBuffer::kNone);
    poll_cancel();
    out.b1.assign(pixels, 0.0f);
    out.b2.assign(pixels, 0.0f);
  }
  if (fragments) {
    fragments->width = out.width;
    fragments->height = out.height;
    fragments->lists.assign(pixels, {});
  }
  const auto drawn = [&scene](const ScreenTriangle& t, const Vec3d& bary) {
    return !t.cutout || scene.opacity(t.geometry, t.primitive, bary.y(), bary.z()) >= kCutoutDrawn;
  };
  std::atomic<int64_t> covered{0};
  parallel_for_each(int64_t(bins.size()), 1, control, [&](int64_t b) {
    const int x0 = int(b % tiles_x) * tile, y0 = int(b / tiles_x) * tile;
    const int x1 = std::min(x0 + tile, out.width), y1 = std::min(y0 + tile, out.height);
    int64_t count = 0;
    // Opaque surfaces first: the z-buffer.
    for (uint32_t i : bins[b]) {
      poll_cancel();  // a tile crossed by many triangles
      const ScreenTriangle& t = screen[i];
      if (t.transparent) continue;
      fill(t, view.perspective(), x0, y0, x1, y1, &count, [&](int x, int y, double depth, const Vec3d& bary) {
        const size_t k = out.index(x, y);
        if (!(depth < out.depth[k]) || !drawn(t, bary)) return;
        out.depth[k] = float(depth);
        if (!surfaces) return;
        out.geometry[k] = t.geometry;
        out.primitive[k] = t.primitive;
        out.b1[k] = float(bary.y());
        out.b2[k] = float(bary.z());
      });
    }
    // Then transparent ones, kept where they are in front of the opaque surface.
    if (fragments) {
      for (uint32_t i : bins[b]) {
        const ScreenTriangle& t = screen[i];
        if (!t.transparent) continue;
        fill(t, view.perspective(), x0, y0, x1, y1, &count, [&](int x, int y, double depth, const Vec3d& bary) {
          const size_t k = out.index(x, y);
          if (!(depth < out.depth[k]) || !drawn(t, bary)) return;
          fragments->lists[k].push_back({float(depth), t.geometry, t.primitive, float(bary.y()), float(bary.z())});
        });
      }
    }
    covered.fetch_add(count, std::memory_order_relaxed);
  });
  if (stats) {
    stats->triangles_in = submitted;
    stats->triangles_drawn = int64_t(screen.size());
    stats->fragments = covered.load();
  }
  return out;
}

}  // namespace

VisibilityBuffer rasterize(const Scene& scene, const RasterView& view, WorkControl& control, int tile,
                           RasterStats* stats, const std::vector<bool>* transparent, FragmentLists* fragments) {
  return draw(scene, view, control, tile, stats, transparent, fragments, /*surfaces=*/true);
}

VisibilityBuffer rasterize_depth(const Scene& scene, const RasterView& view, WorkControl& control) {
  return draw(scene, view, control, kRasterTile, nullptr, nullptr, nullptr, /*surfaces=*/false);
}

Hit surface_of(const Scene& scene, uint32_t geometry, uint32_t primitive, double b1, double b2, const Vec3d& toward) {
  const SceneMesh& mesh = scene.meshes().at(geometry);
  const auto& tri = mesh.mesh.triangles.at(primitive);
  const Vec3d& a = mesh.mesh.vertices[tri[0]];
  const Vec3d& b = mesh.mesh.vertices[tri[1]];
  const Vec3d& c = mesh.mesh.vertices[tri[2]];
  Hit hit;
  hit.point = (1.0 - b1 - b2) * a + b1 * b + b2 * c;
  // The counter-clockwise front, as Scene::intersect tells it (a one-sided emitter's back, seen
  // from behind, shone as its front did: a trial).
  const Vec3d front = (b - a).cross(c - a).normalized();
  hit.front_face = front.dot(toward - hit.point) >= 0.0;
  hit.normal = hit.front_face ? front : Vec3d(-front);
  hit.t = (toward - hit.point).norm();
  hit.geometry = geometry;
  hit.primitive = primitive;
  hit.extent = a.cwiseAbs().cwiseMax(b.cwiseAbs()).cwiseMax(c.cwiseAbs());
  if (const Scene::Spheres* spheres = scene.spheres(geometry)) {
    // A sphere set is rasterized as one tessellation per sphere, in order; its hits name the sphere.
    hit.primitive = uint32_t(primitive / (mesh.mesh.triangles.size() / spheres->centres.size()));
    // The tessellation lies inside the exact sphere Embree intersects (by its sagitta): a shadow
    // ray from it met the sphere from inside, and every sphere was black under the sky and point
    // lights (a trial). The point goes out to the sphere along its radius, the normal with it.
    const Vec3d& centre = spheres->centres[hit.primitive];
    const Vec3d radial = hit.point - centre;
    if (radial.norm() > 0.0) {
      const Vec3d outward = radial.normalized();
      hit.point = centre + spheres->radii[hit.primitive] * outward;
      hit.extent = centre.cwiseAbs().array() + spheres->radii[hit.primitive];
      hit.front_face = outward.dot(toward - hit.point) >= 0.0;
      hit.normal = hit.front_face ? outward : Vec3d(-outward);
      hit.t = (toward - hit.point).norm();
    }
  }
  hit.b1 = b1;
  hit.b2 = b2;
  return hit;
}

std::optional<Hit> surface_at(const Scene& scene, const VisibilityBuffer& buffer, int x, int y, const Vec3d& toward) {
  if (x < 0 || y < 0 || x >= buffer.width || y >= buffer.height || !buffer.covered(x, y)) return std::nullopt;
  const size_t i = buffer.index(x, y);
  return surface_of(scene, buffer.geometry[i], buffer.primitive[i], buffer.b1[i], buffer.b2[i], toward);
}

}  // namespace refracta
