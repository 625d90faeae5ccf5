// find_texture: the MTL's folder, then the caller's texture folders.
#include "refracta/scene/texture_search.h"

#include <filesystem>

namespace refracta {

namespace fs = std::filesystem;

std::optional<std::string> find_texture(const std::string& name, const std::string& folder,
                                        const std::vector<std::string>& dirs, std::vector<std::string>* searched) {
  // MTL files written on Windows separate folders with '\'.
  std::string portable = name;
  for (char& c : portable) c = c == '\\' ? '/' : c;
  const fs::path relative(portable);
  auto regular = [](const fs::path& p) {
    std::error_code error;
    return fs::is_regular_file(p, error);
  };
  std::vector<std::string> folders{folder.empty() ? std::string(".") : folder};
  folders.insert(folders.end(), dirs.begin(), dirs.end());
  for (const std::string& dir : folders) {
    if (searched) searched->push_back(dir);
    for (const fs::path& candidate : {fs::path(dir) / relative, fs::path(dir) / relative.filename()}) {
      if (regular(candidate)) return candidate.string();
    }
  }
  return std::nullopt;
}

}  // namespace refracta
