// The scene's geometry in Embree 3 (the only file that includes Embree), with a material per
// geometry. Every ray is checked before Embree sees it: Debian's Embree is built with assertions
// on and aborts the process on a NaN or huge ray.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/material.h"
#include "refracta/scene/textures.h"

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace refracta {

// A triangle mesh; uvs, when given, are one texture coordinate (u right, v up, OBJ style) per vertex.
struct Mesh {
  std::vector<Vec3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Eigen::Vector2d> uvs;
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
};

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Triangles index into vertices; returns the geometry id. A material's kd_texture needs uvs.
  unsigned add_mesh(const std::vector<Vec3d>& vertices, const std::vector<std::array<int, 3>>& triangles,
                    const Material& material);
  unsigned add_mesh(const Mesh& mesh, const Material& material);
  unsigned add_spheres(const std::vector<Vec3d>& centres, const std::vector<double>& radii,
                       const Material& material);

  // Builds the acceleration structure; called by the renderers (not thread-safe itself).
  void commit() const;

  // Closest hit along origin + t dir, t in (0, t_max]; dir must be unit. Throws on bad rays.
  std::optional<Hit> intersect(const Vec3d& origin, const Vec3d& dir, double t_max) const;
  bool occluded(const Vec3d& origin, const Vec3d& dir, double t_max) const;

  const Material& material(unsigned geometry) const { return materials_.at(geometry); }
  // Every geometry as triangles (spheres as 48 x 24 UV spheres), in geometry order.
  const std::vector<SceneMesh>& meshes() const { return meshes_; }
  // Diffuse albedo at a hit: the material's kd times its texture, filtered by OpenImageIO over
  // the footprint of a ray cone (Akenine-Moller et al. 2019, "Texture Level of Detail Strategies
  // for Real-Time Ray Tracing"): a disc of diameter `footprint` [m] across the arriving direction
  // `dir`, projected onto the triangle's plane and mapped to texture space by its uv Jacobian.
  // footprint 0 samples the finest level at the point.
  Vec3d albedo(const Hit& hit, const Vec3d& dir, double footprint) const;
  // The scene's image textures (materials refer to them by id).
  Textures& textures() { return *textures_; }
  const Textures& textures() const { return *textures_; }
  const std::shared_ptr<Textures>& shared_textures() const { return textures_; }
  size_t geometry_count() const { return materials_.size(); }
  size_t triangle_count() const { return triangles_; }
  // Lowest y of any geometry [m] (+inf for an empty scene).
  double lowest() const { return lowest_; }
  // Highest y of any geometry [m] (-inf for an empty scene).
  double highest() const { return highest_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<Material> materials_;
  std::vector<SceneMesh> meshes_;
  std::shared_ptr<Textures> textures_ = std::make_shared<Textures>();
  size_t triangles_ = 0;
  double lowest_ = std::numeric_limits<double>::infinity();
  double highest_ = -std::numeric_limits<double>::infinity();
};

// Shapes a mirage scene needs, as triangle meshes.
Mesh ground_mesh(double height, double half_size);                 // a square at y = height
Mesh box_mesh(const Vec3d& centre, const Vec3d& size);             // axis-aligned box
Mesh sphere_mesh(const Vec3d& centre, double radius, int segments, int rings);  // a UV sphere

}  // namespace refracta
