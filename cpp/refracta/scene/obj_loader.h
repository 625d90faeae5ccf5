// Wavefront OBJ + MTL meshes (tinyobjloader; the only file that includes it).
#pragma once

#include "refracta/scene/embree_scene.h"
#include "refracta/scene/material.h"

#include <string>
#include <vector>

namespace refracta {

// One mesh per material of the file, with the material's Kd, Ks, Ns; a material with a diffuse
// map (map_Kd) and texture coordinates on every face gets uvs and `texture`, the map's path
// (relative to the MTL's folder resolved). Throws IoError for a missing or malformed file.
struct MaterialMesh {
  Mesh mesh;
  Material material;
  std::string name, texture;
};
std::vector<MaterialMesh> load_obj(const std::string& path);

}  // namespace refracta
