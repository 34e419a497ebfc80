// scene/output_path.h — the checks a command makes on a file it will write beside a scene it
// reads, before any work: its type by extension, that its directory exists, and that it is not
// the scene file itself (by file identity: a symlink or "./" does not get around it).
#pragma once

#include <string>
#include <vector>

namespace prt::scene {

// Nothing for an empty `path`. Throws std::runtime_error with one line naming PATH:
// "PATH: unsupported output type '.ext'" when `extensions` (lower case, with the dot) is not
// empty and does not hold PATH's extension (compared in lower case), "PATH: directory D does not
// exist", or "PATH: an output may not overwrite the input scene" when PATH is `scene_path`.
void check_output_path(const std::string& path, const std::string& scene_path,
                       const std::vector<std::string>& extensions);

}  // namespace prt::scene
