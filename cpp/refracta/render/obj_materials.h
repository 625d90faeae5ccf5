// Wavefront OBJ files into a RenderScene: the MTL -> shading material policy and add_obj. The
// scene layer reads the files (scene/obj_loader.h, MtlMaterial as the file states it); this file
// decides what each record becomes, because only here are both the MTL and the materials known.
#pragma once

#include "refracta/core/error.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/mtl_material.h"

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace refracta {

// The material of an MTL record (texture: a scene texture id for map_Kd, -1 for none):
// - illum 4, 6 or 7 with d < 1 and Ni > 1 (the MTL's glass): Dielectric(Ni);
// - Pr or Pm given (the PBR extension): Principled of Kd, the missing one at Principled's default;
// - anything else: Blinn-Phong of Kd (times the texture), Ks, Ns and d (raster opacity).
MaterialPtr material_from_mtl(const MtlMaterial& mtl, int texture);

// A texture an MTL names is in none of the folders searched (add_obj with MissingTextures::kError).
class TextureNotFound : public IoError {
 public:
  using IoError::IoError;
};

enum class MissingTextures { kError, kWarn };

// How add_obj (Scene.add_obj) places an OBJ file and finds its textures.
struct ObjOptions {
  Vec3d offset = Vec3d::Zero();  // [m], added after scaling
  double scale = 1.0;            // > 0
  // Folders searched, in order, after the MTL's own for each map_Kd (scene/texture_search.h).
  std::vector<std::string> texture_dirs;
  // kError: a texture found nowhere throws TextureNotFound; kWarn: `warn` is called once per
  // texture name and the material keeps its Kd.
  MissingTextures missing_textures = MissingTextures::kError;
  // The callbacks (not settings: neither validated nor pickled). kWarn needs `warn`.
  std::function<void(const std::string& message)> warn;
  // Called after each distinct texture file is registered: (done, total) distinct files.
  std::function<void(size_t done, size_t total)> progress;

  void validate() const;  // throws std::invalid_argument listing every bad setting
};

const char* missing_textures_name(MissingTextures m);  // "error", "warn"

// Adds an OBJ file's parts (scaled, then offset) with their MTL materials (material_from_mtl) and
// an area light for each part with Ke > 0; returns the geometry ids, one per part. A missing OBJ
// or MTL throws IoError.
std::vector<unsigned> add_obj(RenderScene& scene, const std::string& path, const ObjOptions& options = {});

}  // namespace refracta
