// Where the texture an MTL file names is: models downloaded from the web keep their images beside
// the MTL, in a sibling folder (the original mirage editor's Portland scene: textures/), or name
// them by a path that only existed on the author's machine.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace refracta {

// The first regular file `dir`/`name` or `dir`/<file name of `name`> (an author's absolute or
// nested path reduced to its last component) for dir = `folder` (the MTL's own), then each of
// `dirs` in order. Relative `dirs` are relative to the working directory.
// `searched` (when given) receives the folders looked in, in order.
std::optional<std::string> find_texture(const std::string& name, const std::string& folder,
                                        const std::vector<std::string>& dirs,
                                        std::vector<std::string>* searched = nullptr);

}  // namespace refracta
