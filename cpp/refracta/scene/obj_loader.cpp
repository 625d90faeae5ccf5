// Wavefront OBJ + MTL through tinyobjloader.
#include "refracta/scene/obj_loader.h"

#include "refracta/core/error.h"
#include "refracta/scene/image_io.h"
#include "refracta/scene/obj_numbers.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace refracta {

std::vector<MaterialMesh> load_obj(const std::string& path) {
  check_path_text(path);
  if (!std::filesystem::exists(path)) throw MissingFile(concat("no such OBJ file: '", path, "'"));
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  // Regular files, no unparsable numbers; the colours given as one grey value.
  std::vector<std::string> libraries;
  const MtlGreys greys = check_obj_numbers(path, config.mtl_search_path, &libraries);
  // The texts without byte-order marks; every library's materials in one text, so that one mtllib
  // line may name several (tinyobjloader read only the first: "material [ 'm2' ] not found").
  std::string materials_text;
  for (const std::string& library : libraries) materials_text += text_without_bom(library, "MTL") + "\n";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text_without_bom(path, "OBJ"), materials_text, config)) {
    throw IoError(concat("cannot read OBJ '", path, "': ", reader.Error()));
  }
  if (!reader.Warning().empty() && reader.Warning().find("not found") != std::string::npos) {
    throw IoError(concat("OBJ '", path, "': ", reader.Warning()));  // usemtl of a material no library has
  }
  const auto& attrib = reader.GetAttrib();
  std::vector<tinyobj::material_t> materials = reader.GetMaterials();
  for (tinyobj::material_t& m : materials) {
    const auto grey = greys.find(m.name);
    if (grey == greys.end()) continue;
    for (const auto& [key, colour] : {std::pair<const char*, tinyobj::real_t*>{"Ka", m.ambient}, {"Kd", m.diffuse},
                                      {"Ks", m.specular}, {"Ke", m.emission}, {"Tf", m.transmittance}}) {
      if (grey->second.count(key)) colour[1] = colour[2] = colour[0];
    }
  }
  const size_t vertex_count = attrib.vertices.size() / 3;
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  const size_t normal_count = attrib.normals.size() / 3;
  // Triangles per material, as (vertex, texcoord, normal) indices; -1 where the file has none.
  using Corner = std::array<int, 3>;
  std::map<int, std::vector<std::array<Corner, 3>>> by_material;
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3) throw IoError(concat("OBJ '", path, "': a face is not a triangle"));
      const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      std::array<Corner, 3> triangle;
      for (int k = 0; k < 3; ++k) {
        const int v = indices[3 * f + k].vertex_index, t = indices[3 * f + k].texcoord_index;
        const int n = indices[3 * f + k].normal_index;
        if (v < 0 || size_t(v) >= vertex_count) throw IoError(concat("OBJ '", path, "': vertex index out of range"));
        if (t >= 0 && size_t(t) >= texcoord_count) throw IoError(concat("OBJ '", path, "': texcoord index out of range"));
        if (n >= 0 && size_t(n) >= normal_count) throw IoError(concat("OBJ '", path, "': normal index out of range"));
        triangle[k] = {v, t, n};
      }
      by_material[material].push_back(triangle);
    }
  }
  std::vector<MaterialMesh> out;
  for (auto& [id, triangles] : by_material) {
    MaterialMesh part;
    bool textured = id >= 0 && size_t(id) < materials.size() && !materials[id].diffuse_texname.empty();
    bool has_uvs = true, has_normals = true;
    for (const auto& triangle : triangles) {
      for (const auto& corner : triangle) has_uvs = has_uvs && corner[1] >= 0, has_normals = has_normals && corner[2] >= 0;
    }
    textured = textured && has_uvs;
    // Keep only the corners this part uses, renumbered: one vertex per (position, texcoord, normal).
    std::map<Corner, int> remap;
    for (const auto& triangle : triangles) {
      std::array<int, 3> indices;
      for (int k = 0; k < 3; ++k) {
        const Corner key{triangle[k][0], has_uvs ? triangle[k][1] : -1, has_normals ? triangle[k][2] : -1};
        auto [it, inserted] = remap.try_emplace(key, int(remap.size()));
        if (inserted) {
          const int v = key[0];
          part.mesh.vertices.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
          if (has_uvs) part.mesh.uvs.emplace_back(attrib.texcoords[2 * key[1]], attrib.texcoords[2 * key[1] + 1]);
          if (has_normals) {
            const Vec3d n(attrib.normals[3 * key[2]], attrib.normals[3 * key[2] + 1], attrib.normals[3 * key[2] + 2]);
            if (!is_finite(n) || !(n.norm() > 0.0)) throw IoError(concat("OBJ '", path, "': a vertex normal is zero or not finite"));
            part.mesh.normals.push_back(n.normalized());
          }
        }
        indices[k] = it->second;
      }
      part.mesh.triangles.push_back(indices);
    }
    if (id >= 0 && size_t(id) < materials.size()) {
      const auto& m = materials[id];
      MtlMaterial& out_m = part.material;
      out_m.name = m.name;
      out_m.folder = config.mtl_search_path;
      if (textured) {
        out_m.texture = (std::filesystem::path(config.mtl_search_path) / m.diffuse_texname).string();
        out_m.texture_name = m.diffuse_texname;
      }
      if (has_uvs) out_m.cutout_name = m.alpha_texname;
      // Albedos and opacity into [0, 1], the exponent to >= 0, as renderers read MTL files; the
      // values moved are noted (add_obj warns: a Kd of 5 is a mistake the image would hide).
      const Vec3d kd(m.diffuse[0], m.diffuse[1], m.diffuse[2]), ks(m.specular[0], m.specular[1], m.specular[2]);
      out_m.kd = kd.cwiseMax(0.0).cwiseMin(1.0);
      out_m.ks = ks.cwiseMax(0.0).cwiseMin(1.0);
      out_m.ns = std::max(0.0, double(m.shininess));
      out_m.alpha = std::clamp(double(m.dissolve), 0.0, 1.0);
      // Kd + Ks > 1 reflects more light than arrives: both scaled down to a sum of 1 (per the
      // largest channel's sum), as energy-conserving renderers read Phong materials.
      // (Exporters write about 6 digits: 0.333333 x 3 is a sum of 1 within kWrittenDigits.)
      constexpr double kWrittenDigits = 1e-6;
      const double sum = (out_m.kd + out_m.ks).maxCoeff();
      if (sum > 1.0 + kWrittenDigits) out_m.kd /= sum, out_m.ks /= sum;
      std::vector<std::string> moved;
      if (out_m.kd != kd) moved.push_back(concat("Kd (", kd.x(), ", ", kd.y(), ", ", kd.z(), ")"));
      if (out_m.ks != ks) moved.push_back(concat("Ks (", ks.x(), ", ", ks.y(), ", ", ks.z(), ")"));
      if (out_m.ns != double(m.shininess)) moved.push_back(concat("Ns ", m.shininess));
      if (out_m.alpha != double(m.dissolve)) moved.push_back(concat("d ", m.dissolve));
      out_m.ni = m.ior;
      if (!(m.ior > 0.0)) {  // an index of refraction is > 0: the refracting material takes 1 (none)
        moved.push_back(concat("Ni ", m.ior));
        out_m.ni = 1.0;
      }
      out_m.illum = m.illum;
      // Emission >= 0, and the PBR extension's Pr and Pm into [0, 1] (tinyobjloader reads them; 0 is
      // its "absent" value too), noted like the rest (a Ke of -5 was dropped, a Pr of 5 refused
      // without the file's name).
      const Vec3d ke(m.emission[0], m.emission[1], m.emission[2]);
      out_m.ke = ke.cwiseMax(0.0);
      if (out_m.ke != ke) moved.push_back(concat("Ke (", ke.x(), ", ", ke.y(), ", ", ke.z(), ")"));
      out_m.pr = m.roughness > 0.0 ? std::min(1.0, double(m.roughness)) : -1.0;
      out_m.pm = m.metallic > 0.0 ? std::min(1.0, double(m.metallic)) : -1.0;
      if (m.roughness > 1.0) moved.push_back(concat("Pr ", m.roughness));
      if (m.metallic > 1.0) moved.push_back(concat("Pm ", m.metallic));
      for (const std::string& item : moved) out_m.clamped += (out_m.clamped.empty() ? "" : ", ") + item;
      // Dropped without a word, a cut-out leaf rendered as an opaque card (a trial).
      std::vector<std::string> ignored;
      if (!m.diffuse_texname.empty() && !has_uvs) ignored.push_back("map_Kd on faces without texture coordinates (vt)");
      const auto& option = m.diffuse_texopt;
      const bool transformed = option.scale[0] != 1.0 || option.scale[1] != 1.0 || option.origin_offset[0] != 0.0 ||
                               option.origin_offset[1] != 0.0;
      if (!m.diffuse_texname.empty() && transformed) {
        ignored.push_back("map_Kd's -s and -o options");
      }
      if (!m.alpha_texname.empty() && !has_uvs) ignored.push_back("map_d on faces without texture coordinates (vt)");
      if (!m.specular_texname.empty()) ignored.push_back("map_Ks");
      if (!m.bump_texname.empty() || !m.normal_texname.empty() || !m.displacement_texname.empty()) {
        ignored.push_back("bump, normal or displacement maps");
      }
      for (const std::string& item : ignored) out_m.ignored += (out_m.ignored.empty() ? "" : ", ") + item;
    }
    if (!part.mesh.triangles.empty()) out.push_back(std::move(part));
  }
  if (out.empty()) throw IoError(concat("OBJ '", path, "' has no triangles"));
  return out;
}

}  // namespace refracta
