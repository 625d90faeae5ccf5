// Wavefront OBJ files into a RenderScene: the MTL -> shading material policy and add_obj. The
// scene layer reads the files (scene/obj_loader.h, MtlMaterial as the file states it); this file
// decides what each record becomes, because only here are both the MTL and the materials known.
#pragma once

#include "refracta/core/error.h"
#include "refracta/render/render_scene.h"
#include "refracta/scene/mtl_material.h"
#include "refracta/scene/obj_loader.h"

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
class TextureNotFound : public MissingFile {
 public:
  using MissingFile::MissingFile;
};

enum class MissingTextures { kError, kWarn };

// How add_obj (Scene.add_obj) places an OBJ file and finds its textures.
struct ObjOptions {
  // [m] added to every vertex after scaling
  Vec3d offset = Vec3d::Zero();
  // every vertex is multiplied by this (> 0), then offset
  double scale = 1.0;
  // folders searched, in order, after the MTL's own for each map_Kd and map_d (one folder or a sequence)
  std::vector<std::string> texture_dirs;
  // 'error' (raise refracta.TextureNotFoundError) or 'warn' (a UserWarning once per texture name,
  // through the `warn` callback; the material keeps Kd)
  MissingTextures missing_textures = MissingTextures::kError;
  // The callbacks (not settings: neither validated nor pickled). kWarn needs `warn`.
  std::function<void(const std::string& message)> warn;
  // Called after each distinct texture file is registered: (done, total) distinct files.
  std::function<void(size_t done, size_t total)> progress;

  void validate() const;  // throws std::invalid_argument listing every bad setting
};

const char* missing_textures_name(MissingTextures m);  // "error", "warn"

// Add a Wavefront OBJ file with its MTL materials, scaled then offset.
//
// The settings are a refracta.ObjOptions (``options``; None: its defaults) changed by the keywords
// offset, scale, texture_dirs and missing_textures (None: left as they are).
//
// Kd, Ks, Ns, d, map_Kd become BlinnPhong; Pr/Pm (PBR extension) Principled; illum 4/6/7 with
// d < 1 and Ni > 1 Dielectric(Ni); Ke an area light. Vertex normals are kept as
// shading normals. map_d is a cut-out mask (its alpha channel, else its first; Scene::set_cutout):
// leaves and fences on cards, clear where the mask is 0. A grey mask is data, read as stored
// (its 128 of 255 is opacity 0.502); a map_d found nowhere is a missing texture.
//
// A texture the MTL names (map_Kd) is looked for in the MTL's folder, then in each of
// ``texture_dirs`` in order (relative folders from the working directory), as written and by its
// file name alone (a path from the author's machine). A texture found nowhere raises
// refracta.TextureNotFoundError (a refracta.IoError and a FileNotFoundError) naming it and the
// folders searched (``missing_textures='error'``), or, with ``missing_textures='warn'``, issues a
// UserWarning (Python's warnings) and its material uses Kd.
//
// Each texture is prepared once (MIP-mapped, linear) into the texture cache folder
// ($REFRACTA_TEXTURE_CACHE, else refracta-textures in the temporary folder); a model with hundreds of
// textures takes seconds the first time. progress: True shows a bar on stderr once preparing has
// taken over a second, a callable gets progress(done, total) textures, False shows nothing.
//
// Returns the geometry ids, one per part. A missing OBJ or MTL raises refracta.IoError.
std::vector<unsigned> add_obj(RenderScene& scene, const std::string& path, const ObjOptions& options = {});
// The same with the file already read (scene/obj_loader.h's load_obj(path)): the Python binding
// reads it with the GIL released, then adds it here; `path` names the file in messages.
std::vector<unsigned> add_loaded_obj(RenderScene& scene, std::vector<MaterialMesh> parts, const std::string& path,
                                      const ObjOptions& options);

}  // namespace refracta
