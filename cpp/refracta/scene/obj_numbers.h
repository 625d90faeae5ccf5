// A strict pass over the numbers of an OBJ file and its MTL libraries, before tinyobjloader reads
// them: tinyobjloader turns a number it cannot parse ("v nan 0 0", "Kd abc") into 0 without a
// word, and blocks reading a FIFO. Throws IoError naming file, line and token.
#pragma once

#include <string>

namespace refracta {

// Checks `obj_path` (a regular file) and every MTL file its mtllib lines name (resolved against
// mtl_folder, when they exist; a missing one is tinyobjloader's error to report): each number of a
// numeric record (v, vt, vn, vp; Ka, Kd, Ks, Ke, Tf, Ns, Ni, d, Tr, illum, Pr, Pm, ...) must
// parse entirely and be finite.
void check_obj_numbers(const std::string& obj_path, const std::string& mtl_folder);

}  // namespace refracta
