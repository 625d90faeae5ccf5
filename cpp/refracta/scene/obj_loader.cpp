// Wavefront OBJ + MTL through tinyobjloader.
#include "refracta/scene/obj_loader.h"

#include "refracta/core/error.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace refracta {

std::vector<MaterialMesh> load_obj(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(concat("no such OBJ file: '", path, "'"));
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    throw IoError(concat("cannot read OBJ '", path, "': ", reader.Error()));
  }
  if (!reader.Warning().empty() && reader.Warning().find("not found") != std::string::npos) {
    throw IoError(concat("OBJ '", path, "': ", reader.Warning()));  // a missing .mtl file
  }
  const auto& attrib = reader.GetAttrib();
  const auto& materials = reader.GetMaterials();
  const size_t vertex_count = attrib.vertices.size() / 3;
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  // Triangles per material, as (vertex, texcoord) index pairs; texcoord -1 where the file has none.
  std::map<int, std::vector<std::array<std::pair<int, int>, 3>>> by_material;
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3) throw IoError(concat("OBJ '", path, "': a face is not a triangle"));
      const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      std::array<std::pair<int, int>, 3> triangle;
      for (int k = 0; k < 3; ++k) {
        const int v = indices[3 * f + k].vertex_index, t = indices[3 * f + k].texcoord_index;
        if (v < 0 || size_t(v) >= vertex_count) throw IoError(concat("OBJ '", path, "': vertex index out of range"));
        if (t >= 0 && size_t(t) >= texcoord_count) throw IoError(concat("OBJ '", path, "': texcoord index out of range"));
        triangle[k] = {v, t};
      }
      by_material[material].push_back(triangle);
    }
  }
  std::vector<MaterialMesh> out;
  for (auto& [id, triangles] : by_material) {
    MaterialMesh part;
    bool textured = id >= 0 && size_t(id) < materials.size() && !materials[id].diffuse_texname.empty();
    for (const auto& triangle : triangles) {
      for (const auto& corner : triangle) textured = textured && corner.second >= 0;
    }
    // Keep only the corners this part uses, renumbered: one vertex per (position, texcoord).
    std::map<std::pair<int, int>, int> remap;
    for (const auto& triangle : triangles) {
      std::array<int, 3> indices;
      for (int k = 0; k < 3; ++k) {
        const std::pair<int, int> key{triangle[k].first, textured ? triangle[k].second : -1};
        auto [it, inserted] = remap.try_emplace(key, int(remap.size()));
        if (inserted) {
          const int v = key.first;
          part.mesh.vertices.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
          if (textured) {
            part.mesh.uvs.emplace_back(attrib.texcoords[2 * key.second], attrib.texcoords[2 * key.second + 1]);
          }
        }
        indices[k] = it->second;
      }
      part.mesh.triangles.push_back(indices);
    }
    if (id >= 0 && size_t(id) < materials.size()) {
      const auto& m = materials[id];
      part.name = m.name;
      if (textured) part.texture = (std::filesystem::path(config.mtl_search_path) / m.diffuse_texname).string();
      part.material.kd = Vec3d(m.diffuse[0], m.diffuse[1], m.diffuse[2]).cwiseMax(0.0).cwiseMin(1.0);
      part.material.ks = Vec3d(m.specular[0], m.specular[1], m.specular[2]).cwiseMax(0.0).cwiseMin(1.0);
      part.material.ns = std::max(0.0, double(m.shininess));
      part.material.alpha = std::clamp(double(m.dissolve), 0.0, 1.0);
    }
    if (!part.mesh.triangles.empty()) out.push_back(std::move(part));
  }
  if (out.empty()) throw IoError(concat("OBJ '", path, "' has no triangles"));
  return out;
}

}  // namespace refracta
