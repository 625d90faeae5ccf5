// OBJ files into a RenderScene (obj_materials.h): the MTL policy and the texture search.
#include "refracta/render/obj_materials.h"

#include "refracta/scene/obj_loader.h"
#include "refracta/scene/texture_search.h"
#include "refracta/shading/area_light.h"
#include "refracta/shading/dielectric.h"
#include "refracta/shading/phong.h"
#include "refracta/shading/principled.h"

#include <cmath>
#include <optional>
#include <set>

namespace refracta {

MaterialPtr material_from_mtl(const MtlMaterial& mtl, int texture) {
  const bool glass = mtl.illum == 4 || mtl.illum == 6 || mtl.illum == 7;
  if (glass && mtl.alpha < 1.0 && mtl.ni > 1.0) return std::make_shared<Dielectric>(Ior(mtl.ni));
  if (mtl.pr >= 0.0 || mtl.pm >= 0.0) {  // the PBR extension: Pr, Pm
    PrincipledParameters p;
    if (mtl.pr >= 0.0) p.roughness = mtl.pr;
    if (mtl.pm >= 0.0) p.metallic = mtl.pm;
    return std::make_shared<Principled>(TexturedReflectance(mtl.kd, "Kd", texture), p);
  }
  return std::make_shared<BlinnPhong>(TexturedReflectance(mtl.kd, "Kd", texture), mtl.ks, mtl.ns, mtl.alpha);
}

const char* missing_textures_name(MissingTextures m) { return m == MissingTextures::kWarn ? "warn" : "error"; }

void ObjOptions::validate() const {
  Problems problems("add_obj");
  problems.check(is_finite(offset), "offset must be finite (got (", offset.x(), ", ", offset.y(), ", ", offset.z(), "))");
  problems.check(scale > 0.0 && std::isfinite(scale), "scale must be > 0 (got ", scale, ")");
  problems.throw_if_any();
}

namespace {

// The file of each part's map_Kd (`name` &MtlMaterial::texture_name) or map_d (cutout_name), ""
// for none, searched by find_texture. A texture found nowhere throws TextureNotFound, or with
// kWarn warns (once per name, saying what the part does without it: `instead`) and gives "".
std::vector<std::string> texture_paths(const std::vector<MaterialMesh>& parts, const ObjOptions& options,
                                       std::string MtlMaterial::*name, const char* instead) {
  std::vector<std::string> out;
  std::set<std::string> warned;
  for (const MaterialMesh& part : parts) {
    const MtlMaterial& mtl = part.material;
    const std::string& written = mtl.*name;
    std::vector<std::string> searched;
    const auto found = written.empty() ? std::optional<std::string>("")
                                       : find_texture(written, mtl.folder, options.texture_dirs, &searched);
    if (found) {
      out.push_back(*found);
      continue;
    }
    std::string folders;
    for (const auto& folder : searched) folders += concat(folders.empty() ? "" : ", ", "'", folder, "'");
    const std::string message = concat("texture '", written, "' of material '", mtl.name, "' not found in ", folders);
    if (options.missing_textures == MissingTextures::kError) throw TextureNotFound(message);
    if (warned.insert(written).second) options.warn(concat(message, "; ", instead));
    out.emplace_back();
  }
  return out;
}

}  // namespace

std::vector<unsigned> add_obj(RenderScene& scene, const std::string& path, const ObjOptions& options) {
  options.validate();
  return add_loaded_obj(scene, load_obj(path), path, options);
}

std::vector<unsigned> add_loaded_obj(RenderScene& scene, std::vector<MaterialMesh> parts, const std::string& path,
                                      const ObjOptions& options) {
  options.validate();
  if (options.missing_textures == MissingTextures::kWarn && !options.warn) {
    throw_invalid("add_obj: missing_textures 'warn' needs a warn callback");
  }
  const std::vector<std::string> textures =
      texture_paths(parts, options, &MtlMaterial::texture_name, "its material uses Kd");
  const std::vector<std::string> cutouts =
      texture_paths(parts, options, &MtlMaterial::cutout_name, "its surface stays opaque");
  std::set<std::string> distinct(textures.begin(), textures.end()), registered, noted;
  distinct.insert(cutouts.begin(), cutouts.end());
  distinct.erase("");
  // The callbacks (warnings, progress) may raise: they all run, and every texture loads, before
  // the first mesh is added, so that their failure leaves the scene's geometry as it was (the
  // materials and textures registered stay, unused).
  std::vector<int> materials(parts.size()), cutout_ids(parts.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    const MaterialMesh& part = parts[p];
    const bool first_time = noted.insert(part.material.name).second;
    if (!part.material.clamped.empty() && options.warn && first_time) {
      options.warn(concat("add_obj: '", path, "': material '", part.material.name, "' has ", part.material.clamped,
                          " out of range; moved to Kd, Ks, d, Pr, Pm in [0, 1] with Kd + Ks <= 1 (both scaled), "
                          "Ns, Ke >= 0, Ni <= 0 to 1"));
    }
    if (!part.material.ignored.empty() && options.warn && first_time) {
      options.warn(concat("add_obj: '", path, "': material '", part.material.name, "' gives ", part.material.ignored,
                          ", which refracta does not render: ignored"));
    }
    const auto registered_id = [&](const std::string& file, bool mask) {
      if (file.empty()) return -1;
      const int id = scene.geometry.add_texture(file, mask);
      if (registered.insert(file).second && options.progress) options.progress(registered.size(), distinct.size());
      return id;
    };
    materials[p] = scene.add_material(material_from_mtl(part.material, registered_id(textures[p], false)));
    cutout_ids[p] = registered_id(cutouts[p], true);
  }
  std::vector<unsigned> ids;
  for (size_t p = 0; p < parts.size(); ++p) {
    MaterialMesh& part = parts[p];
    for (auto& v : part.mesh.vertices) v = v * options.scale + options.offset;
    const unsigned id = scene.geometry.add_mesh(part.mesh, materials[p]);
    if (cutout_ids[p] >= 0) scene.geometry.set_cutout(id, cutout_ids[p]);
    if (part.material.ke.maxCoeff() > 0.0) {
      scene.add_light(std::make_shared<AreaLight>(part.mesh, Color::illuminant(part.material.ke), false), int(id));
    }
    ids.push_back(id);
  }
  return ids;
}

}  // namespace refracta
