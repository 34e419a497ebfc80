// bake/src/scene_label.h (private) — the name a bake error message starts with.
//
// Messages are one line "PATH: problem"; a scene built in memory (no source file) is named
// "scene".
#pragma once

#include <string>

#include "bake/scene.h"

namespace prt::bake::detail {

// The scene's source path, or "scene" when it has none.
inline std::string scene_label(const Scene& scene) {
  return scene.source_path.empty() ? std::string("scene") : scene.source_path;
}

}  // namespace prt::bake::detail
