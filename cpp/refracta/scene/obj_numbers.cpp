// The strict number pass over OBJ and MTL files (obj_numbers.h).
#include "refracta/scene/obj_numbers.h"

#include "refracta/core/error.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <vector>

namespace refracta {

namespace {

// Records whose arguments are all numbers. MTL colours may instead be "spectral file" or
// "xyz x y z"; those forms are recognised and skipped or checked from the second token on.
const std::set<std::string> kObjNumeric = {"v", "vt", "vn", "vp"};
const std::set<std::string> kMtlNumeric = {"Ka", "Kd", "Ks", "Ke", "Tf", "Ns", "Ni", "d", "Tr", "illum", "sharpness",
                                           "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};

void require_regular(const std::string& path, const char* kind) {
  if (!std::filesystem::is_regular_file(path)) {
    throw IoError(concat("cannot read ", kind, " '", path, "': not a regular file"));
  }
}

// The vertex references of a face, line or point record ("f 1/2/3 -1//2 ..."): whole numbers,
// non-zero, within a C++ int (tinyobjloader's atoi wrapped 4294967299 to vertex 3, silently).
void check_indices(const std::string& path, int number, const std::string& key, std::istringstream& tokens) {
  for (std::string token; tokens >> token;) {
    std::istringstream parts(token);
    for (std::string part; std::getline(parts, part, '/');) {
      if (part.empty()) continue;  // "1//2": no texture coordinate
      errno = 0;
      char* end = nullptr;
      const long long value = std::strtoll(part.c_str(), &end, 10);
      if (end != part.c_str() + part.size() || errno == ERANGE || value == 0 || std::llabs(value) > 2147483647LL) {
        throw IoError(concat("OBJ '", path, "' line ", number, ": '", key, "' has '", token,
                             "', whose indices must be non-zero whole numbers below 2**31"));
      }
    }
  }
}

const std::set<std::string> kMtlColours = {"Ka", "Kd", "Ks", "Ke", "Tf"};
const std::string kByteOrderMark = "\xEF\xBB\xBF";

// Checks one file's numeric records; appends its mtllib names to `libraries` (OBJ files) and its
// one-value colours to `greys` (MTL files).
void check_file(const std::string& path, const char* kind, const std::set<std::string>& numeric,
                std::vector<std::string>* libraries, MtlGreys* greys) {
  require_regular(path, kind);
  std::ifstream in(path);
  if (!in) throw IoError(concat("cannot read ", kind, " '", path, "'"));
  std::string line, material;
  for (int number = 1; std::getline(in, line); ++number) {
    if (number == 1 && line.rfind(kByteOrderMark, 0) == 0) line.erase(0, kByteOrderMark.size());
    const size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    std::istringstream tokens(line);
    std::string key;
    if (!(tokens >> key)) continue;
    if (libraries && key == "mtllib") {
      for (std::string name; tokens >> name;) libraries->push_back(name);
      continue;
    }
    if (libraries && (key == "f" || key == "l" || key == "p")) {
      check_indices(path, number, key, tokens);
      continue;
    }
    if (greys && key == "newmtl") {
      std::getline(tokens >> std::ws, material);
      material.erase(material.find_last_not_of(" \t\r") + 1);
      continue;
    }
    if (!numeric.count(key)) continue;
    std::string token;
    bool first = true, plain = true;  // plain: r [g b], not "spectral" nor "xyz"
    int count = 0;
    while (tokens >> token) {
      if (first && (token == "spectral")) {  // "Kd spectral file.rfl [factor]"
        plain = false;
        break;
      }
      if (token == "-halo") continue;              // "d -halo 0.5"
      if (first && token == "xyz") {               // "Kd xyz x y z"
        first = false, plain = false;
        continue;
      }
      first = false;
      errno = 0;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size() || !std::isfinite(value) || errno == ERANGE) {
        throw IoError(concat(kind, " '", path, "' line ", number, ": '", key, "' has '", token,
                             "', which is not a finite number"));
      }
      ++count;
    }
    // A position or normal without its three coordinates: tinyobjloader reads the missing ones as 0.
    if (libraries && (key == "v" || key == "vn") && count < 3) {
      throw IoError(concat(kind, " '", path, "' line ", number, ": '", key, "' has ", count,
                           " coordinates; it needs x y z"));
    }
    if (greys && plain && kMtlColours.count(key)) {
      if (count == 2) {  // tinyobjloader read b as 0
        throw IoError(concat(kind, " '", path, "' line ", number, ": '", key,
                             "' has 2 values; a colour is r g b, or one grey value"));
      }
      if (count == 1) (*greys)[material].insert(key);
    }
  }
}

}  // namespace

MtlGreys check_obj_numbers(const std::string& obj_path, const std::string& mtl_folder,
                           std::vector<std::string>* library_paths) {
  std::vector<std::string> libraries;
  check_file(obj_path, "OBJ", kObjNumeric, &libraries, nullptr);
  MtlGreys greys;
  for (const std::string& name : libraries) {
    const std::filesystem::path mtl = std::filesystem::path(mtl_folder) / name;
    if (!std::filesystem::exists(mtl)) {  // tinyobjloader's own words: "Material file [ x.mtl ] not found in a path : ..."
      throw MissingFile(concat("OBJ '", obj_path, "': its material library '", name, "' (mtllib) is not in '",
                           mtl_folder.empty() ? std::string(".") : mtl_folder, "'"));
    }
    check_file(mtl.string(), "MTL", kMtlNumeric, nullptr, &greys);
    if (library_paths) library_paths->push_back(mtl.string());
  }
  return greys;
}

std::string text_without_bom(const std::string& path, const char* kind) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(concat("cannot read ", kind, " '", path, "'"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.rfind(kByteOrderMark, 0) == 0) text.erase(0, kByteOrderMark.size());
  return text;
}

}  // namespace refracta
