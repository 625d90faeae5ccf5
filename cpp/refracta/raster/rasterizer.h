// refracta's CPU rasterizer: the scene's triangles drawn into a visibility buffer (depth,
// geometry, primitive and perspective-correct barycentrics per pixel) from a RasterView.
// Triangles are clipped in the view frame against the near plane and a guard band (so vertices
// behind the eye or far outside never reach screen space), binned to square tiles, and the tiles
// filled in parallel over oneTBB with edge functions at pixel centres (top-left fill rule) and a
// z-buffer. Shading reads the buffer afterwards (surface_at), so each pixel is shaded once.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/raster/raster_view.h"
#include "refracta/scene/embree_scene.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace refracta {

// The bytes a visibility buffer holds per pixel: depth, geometry, primitive and two barycentrics.
constexpr double kVisibilityBytesPerPixel = 20.0;

struct VisibilityBuffer {
  static constexpr uint32_t kNone = 0xffffffffu;
  int width = 0, height = 0;
  std::vector<float> depth;        // view depth [m] (+inf where nothing is drawn)
  std::vector<uint32_t> geometry;  // scene geometry id, kNone where nothing is drawn
  std::vector<uint32_t> primitive; // triangle index within the geometry's SceneMesh
  std::vector<float> b1, b2;       // barycentric weights of the triangle's vertices 1 and 2

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  bool covered(int x, int y) const { return geometry[index(x, y)] != kNone; }
};

// A fragment of a transparent surface: what the visibility buffer keeps, per fragment.
struct RasterFragment {
  float depth;
  uint32_t geometry, primitive;
  float b1, b2;
};

// Per-pixel lists of the transparent fragments in front of the opaque surface, in submission
// order (sorting is the compositor's business).
struct FragmentLists {
  int width = 0, height = 0;
  std::vector<std::vector<RasterFragment>> lists;
  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  int64_t total() const;
};

struct RasterStats {
  int64_t triangles_in = 0;     // scene triangles submitted
  int64_t triangles_drawn = 0;  // screen triangles after clipping
  int64_t fragments = 0;        // pixels that passed the edge test (before the depth test)
};

// Tile side [pixels] of the binning: 32 x 32 keeps a tile's depth and id rows in L1/L2 while
// leaving enough tiles to balance over the threads.
constexpr int kRasterTile = 32;

// Draws every mesh of the scene. Degenerate triangles are skipped; no back-face culling.
// With `transparent` (per geometry id) and `fragments`, the flagged geometries are drawn after the
// opaque ones, per tile, into fragment lists where they lie in front of the opaque surface (the
// same culling for every compositing method) instead of into the buffer.
VisibilityBuffer rasterize(const Scene& scene, const RasterView& view, WorkControl& control, int tile = kRasterTile,
                           RasterStats* stats = nullptr, const std::vector<bool>* transparent = nullptr,
                           FragmentLists* fragments = nullptr);
// The same drawing's depths alone (a shadow map's: the other buffers are left empty, not filled
// and thrown away -- 1 GB of an 8192^2 map).
VisibilityBuffer rasterize_depth(const Scene& scene, const RasterView& view, WorkControl& control);

// The surface at barycentrics (b1, b2) of a triangle, its normal facing `toward`.
Hit surface_of(const Scene& scene, uint32_t geometry, uint32_t primitive, double b1, double b2, const Vec3d& toward);

// The surface a pixel shows: its world point (from the barycentrics), the unit geometric normal
// facing `toward` (the viewer's side), the geometry and primitive; nullopt where nothing is drawn.
std::optional<Hit> surface_at(const Scene& scene, const VisibilityBuffer& buffer, int x, int y,
                              const Vec3d& toward);

}  // namespace refracta
