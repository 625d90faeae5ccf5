// The scene's geometry in Embree 3 (the only file that includes Embree), with a material id per
// geometry (the render layer's material table). Every ray is checked before Embree sees it: Debian's Embree is built with assertions
// on and aborts the process on a NaN or huge ray.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/surface_interaction.h"
#include "refracta/scene/terrain.h"
#include "refracta/scene/textures.h"

#include <array>
#include <atomic>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace refracta {

// A triangle mesh; uvs, when given, are one texture coordinate (u right, v up, OBJ style) per
// vertex, and normals one unit shading normal per vertex (interpolated across each triangle).
// A triangle's front is its counter-clockwise side: geometric normal (v1 - v0) x (v2 - v0).
struct Mesh {
  std::vector<Vec3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Eigen::Vector2d> uvs;
  std::vector<Vec3d> normals;
};

// A geometry of the scene as triangles, for the rasterizer (spheres tessellated).
struct SceneMesh {
  unsigned geometry;
  Mesh mesh;
};

struct Hit {
  double t;          // distance along the (unit) direction [m]
  Vec3d point;       // [m]
  Vec3d normal;      // unit geometric normal, facing the incoming ray
  unsigned geometry;
  unsigned primitive;
  double b1 = 0.0, b2 = 0.0;  // barycentric weights of the triangle's vertices 1 and 2
  bool front_face = true;     // the ray met the geometry's front (normal is then the unflipped one)
  // [m] per axis, the largest |coordinate| of the primitive met (a triangle's vertices, a sphere's
  // extent), which Embree rounds to float: what a ray leaving the point must clear (offset_point).
  Vec3d extent = Vec3d::Zero();
};

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Triangles index into vertices; returns the geometry id. `material` is an id of the render
  // layer's material table (checked there).
  unsigned add_mesh(const Mesh& mesh, int material);
  unsigned add_spheres(const std::vector<Vec3d>& centres, const std::vector<double>& radii, int material);
  // A terrain grid as Embree grid geometry (its vertex buffer shared, not copied). Its entry in
  // meshes() is empty: the rasterizer does not draw terrain. A hit's primitive is
  // 2 * (row * (cols - 1) + col) + k for triangle k of cell (row, col) (TerrainGrid::triangle),
  // b1 and b2 that triangle's barycentric weights.
  unsigned add_terrain(std::shared_ptr<const TerrainGrid> terrain, int material);

  // Registers an image texture, a colour or a `mask` (Textures::add), for this scene's materials
  // and cut-outs; a change like add_mesh.
  int add_texture(const std::string& path, bool mask = false);
  // Cuts a triangle-mesh geometry with uvs out where `texture` (an id of textures()) is clear:
  // a ray passes through a point of it with probability 1 - opacity (Textures::opacity; pbrt-v4's
  // stochastic alpha test, drawn from a hash of the ray, so the same ray gets the same answer),
  // shadow rays too; the rasterizer draws it where the opacity is at least 1/2.
  void set_cutout(unsigned geometry, int texture);
  // A geometry's cut-out texture (set_cutout), -1 for none.
  int cutout(unsigned geometry) const { return geometry < cutouts_.size() ? cutouts_[geometry] : -1; }
  // The opacity of a triangle-mesh geometry at barycentric weights (b1, b2) of its triangle
  // `primitive`: its cut-out's there, 1 without one.
  double opacity(unsigned geometry, unsigned primitive, double b1, double b2) const;

  // Builds the acceleration structure; called by the renderers (not thread-safe itself).
  void commit() const;

  // Work that reads the scene without the GIL (a render on a worker thread) holds a ReadGuard;
  // while one is held every change throws (check_unchanging), so a scene never changes under a
  // running render. Renders may share a scene with each other.
  class ReadGuard {
   public:
    explicit ReadGuard(const Scene& scene) : scene_(scene) { ++scene_.readers_; }
    ~ReadGuard() { --scene_.readers_; }
    ReadGuard(const ReadGuard&) = delete;
    ReadGuard& operator=(const ReadGuard&) = delete;

   private:
    const Scene& scene_;
  };
  // Throws std::runtime_error (Python RuntimeError) naming `change` while a ReadGuard is held.
  void check_unchanging(const char* change) const;

  // Closest hit along origin + t dir, t in (0, t_max]; dir must be unit. Throws on bad rays.
  std::optional<Hit> intersect(const Vec3d& origin, const Vec3d& dir, double t_max) const;
  bool occluded(const Vec3d& origin, const Vec3d& dir, double t_max) const;

  int material(unsigned geometry) const { return materials_.at(geometry); }
  void set_material(unsigned geometry, int material);
  // Removes a geometry: Embree detaches it and recommits before the next query; the other ids
  // stay as they were (a removed id is never reused), its mesh becomes empty and the bounds
  // shrink to what is left.
  void remove(unsigned geometry);
  bool removed(unsigned geometry) const { return geometry < removed_.size() && removed_[geometry]; }
  // Throws ValueError naming `what` unless `geometry` is a geometry of the scene, not removed.
  void check_geometry(unsigned geometry, const char* what) const;
  // Every geometry as triangles (spheres as 48 x 24 UV spheres), in geometry order.
  const std::vector<SceneMesh>& meshes() const { return meshes_; }
  // A terrain's grid (null for every other geometry).
  const TerrainGrid* terrain(unsigned geometry) const {
    return geometry < terrains_.size() ? terrains_[geometry].get() : nullptr;
  }
  // Whether a geometry is an exact sphere set (add_spheres) rather than a triangle mesh.
  bool is_spheres(unsigned geometry) const { return sphere_sets_.at(geometry) != nullptr; }
  struct Spheres {
    std::vector<Vec3d> centres;
    std::vector<double> radii;
  };
  // A sphere set's centres and radii as given to add_spheres (null for a mesh).
  const Spheres* spheres(unsigned geometry) const { return sphere_sets_.at(geometry).get(); }
  // Everything shading needs at a hit found along unit `dir`: the unflipped geometric normal and
  // front-face flag, the shading normal (vertex normals interpolated, else the geometric one),
  // uv and dp/du, and the texture footprint: the ray cone's disc of diameter `footprint` [m]
  // across `dir`, projected onto the triangle's plane and mapped to texture space by its uv
  // Jacobian (Akenine-Moller et al. 2019, "Texture Level of Detail Strategies for Real-Time Ray
  // Tracing"); footprint 0 samples the finest level at the point.
  SurfaceInteraction interaction(const Hit& hit, const Vec3d& dir, double footprint) const;
  // The same with the footprint given as two vectors [m] spanning it (a ray's differentials:
  // where the paths of neighbouring samples meet the hit's plane, less the hit), projected along
  // `dir` onto the triangle's plane as the cone's axes are.
  SurfaceInteraction interaction(const Hit& hit, const Vec3d& dir, const std::array<Vec3d, 2>& footprint) const;
  // Whether a hit's geometry has texture coordinates (a footprint matters there).
  bool has_uvs(unsigned geometry) const;
  // The scene's image textures (materials refer to them by id).
  Textures& textures() { return *textures_; }
  const Textures& textures() const { return *textures_; }
  size_t geometry_count() const { return materials_.size(); }  // ids 0 .. count - 1, removed ones included
  // Lowest y of any geometry [m] (+inf for an empty scene).
  double lowest() const { return lower_.y(); }
  // Highest y of any geometry [m] (-inf for an empty scene).
  double highest() const { return upper_.y(); }
  // Corners of the axis-aligned box around every geometry (spheres exact) [m]; lower > upper
  // (+inf, -inf) for an empty scene.
  const Vec3d& lower() const { return lower_; }
  const Vec3d& upper() const { return upper_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  mutable std::atomic<int> readers_{0};
  std::vector<int> materials_;
  std::vector<SceneMesh> meshes_;
  std::vector<std::shared_ptr<const Spheres>> sphere_sets_;  // null for meshes
  std::vector<std::shared_ptr<const TerrainGrid>> terrains_;  // by geometry id (shorter: the rest are not terrain)
  std::vector<bool> removed_;  // by geometry id (shorter: the rest not removed)
  std::vector<int> cutouts_;   // cut-out texture by geometry id, -1 for none (shorter: the rest none)
  std::shared_ptr<Textures> textures_ = std::make_shared<Textures>();
  Vec3d lower_ = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d upper_ = Vec3d::Constant(-std::numeric_limits<double>::infinity());
};

// Shapes a mirage scene needs, as triangle meshes.
Mesh ground_mesh(double height, double half_size);                 // a square at y = height
// The same with texture coordinates repeating every texture_size [m] (u along +x, v along -z).
Mesh ground_mesh(double height, double half_size, double texture_size);
Mesh box_mesh(const Vec3d& centre, const Vec3d& size);             // axis-aligned box
// An upright rectangle width x height [m] centred at `centre`, its front (counter-clockwise, uvs
// (0, 0) bottom left to (1, 1) top right) toward the horizontal part of `facing`: a photo in the scene.
Mesh billboard_mesh(const Vec3d& centre, double width, double height, const Vec3d& facing);
Mesh sphere_mesh(const Vec3d& centre, double radius, int segments, int rings);  // a UV sphere

}  // namespace refracta
