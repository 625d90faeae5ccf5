// A strict pass over the numbers of an OBJ file and its MTL libraries, before tinyobjloader reads
// them: tinyobjloader turns a number it cannot parse ("v nan 0 0", "Kd abc") into 0 without a
// word, and blocks reading a FIFO. Throws IoError naming file, line and token.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace refracta {

// Per MTL material name, its colours (Ka, Kd, Ks, Ke, Tf) given as one value: a grey, "g and b
// assumed equal to r" (the MTL specification), which tinyobjloader reads as (r, 0, 0).
using MtlGreys = std::map<std::string, std::set<std::string>>;

// Checks `obj_path` (a regular file) and every MTL file its mtllib lines name (resolved against
// mtl_folder; a missing one is an IoError naming it): each number of a
// numeric record (v, vt, vn, vp; Ka, Kd, Ks, Ke, Tf, Ns, Ni, d, Tr, illum, Pr, Pm, ...) must
// parse entirely and be finite, and a colour has one value or three. Returns the one-value colours;
// *libraries (if given) gets the MTL files' paths, in the order the mtllib lines name them.
MtlGreys check_obj_numbers(const std::string& obj_path, const std::string& mtl_folder,
                           std::vector<std::string>* libraries = nullptr);

// A text file's contents without a leading UTF-8 byte-order mark, which tinyobjloader would read as
// part of the first record (a trial: "\ufeffv 0 0 0" dropped, every vertex index shifted by one).
std::string text_without_bom(const std::string& path, const char* kind);

}  // namespace refracta
