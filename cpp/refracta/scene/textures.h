// Image textures through OpenImageIO's TextureSystem: MIP-mapped, anisotropic filtering driven by
// the footprint of a pixel on the surface. A texture file is prepared once by OIIO's
// make_texture (linearised from sRGB when stored in 8 or 16 bits, MIP-mapped, tiled) into a
// cache file (texture_cache_folder(), written atomically); lookups then go through the shared
// TextureSystem. The only OIIO texture user.
#pragma once

#include "refracta/core/math.h"

#include <memory>
#include <string>
#include <vector>

namespace refracta {

// Texture coordinates (s, t) in OIIO's convention: s right, t down, [0, 1] over the image,
// repeating outside. d*dx, d*dy: the change of (s, t) across one pixel's footprint.
struct TextureLookup {
  double s = 0.0, t = 0.0;
  double dsdx = 0.0, dtdx = 0.0, dsdy = 0.0, dtdy = 0.0;
};

// The folder of prepared textures: $REFRACTA_TEXTURE_CACHE when set (made if missing; IoError
// when it cannot be made or written), else refracta-textures in the temporary folder ($TMPDIR),
// else /tmp/refracta-textures (TMPDIR naming a missing or read-only folder). Files there are
// named by the source's absolute path, size and time; deleting them is always safe.
std::string texture_cache_folder();

// IoError unless `path` names a regular file: "no such texture file" or "not a regular file" (a
// folder, or a FIFO that would block the read).
void check_texture_file(const std::string& path);

class Textures {
 public:
  Textures();
  ~Textures();
  Textures(const Textures&) = delete;
  Textures& operator=(const Textures&) = delete;

  // Registers an image file (any format OIIO reads) as a colour texture, or as a `mask` (an
  // opacity, MTL's map_d); returns its id. The same path for the same use twice gives the same id.
  // Throws IoError naming the file when it is missing or unreadable.
  int add(const std::string& path, bool mask = false);
  // Filtered linear RGB (a grey image's value replicated; an image's alpha plays no part).
  Vec3d lookup(int id, const TextureLookup& at) const;
  // Whether the image has an alpha channel (grey-alpha or RGBA, as OIIO reads its header).
  bool has_alpha(int id) const;
  // Opacity in [0, 1] at (s, t), bilinear on the finest level, as stored: a mask's alpha, or its
  // first channel without one (data: a grey mask's 128 of 255 reads 0.502, as Blender reads
  // masks); a colour texture's alpha, or 1 without one.
  double opacity(int id, double s, double t) const;
  const std::string& path(int id) const { return paths_.at(id); }
  bool is_mask(int id) const { return masks_.at(id); }
  size_t size() const { return paths_.size(); }  // textures registered (ids 0 .. size - 1)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::string> paths_;
  std::vector<bool> masks_;
};

}  // namespace refracta
