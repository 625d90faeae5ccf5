// Wavefront OBJ + MTL meshes (tinyobjloader; the only file that includes it).
#pragma once

#include "refracta/scene/embree_scene.h"
#include "refracta/scene/mtl_material.h"

#include <string>
#include <vector>

namespace refracta {

// One mesh per material of the file with its MTL record; a material with a diffuse map (map_Kd)
// and texture coordinates on every face gets uvs and material.texture, the map's path (relative
// to the MTL's folder resolved); vertex normals (vn) on every face give the mesh its normals.
// Throws IoError for a missing or malformed file.
struct MaterialMesh {
  Mesh mesh;
  MtlMaterial material;
};
std::vector<MaterialMesh> load_obj(const std::string& path);

}  // namespace refracta
