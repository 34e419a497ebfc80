// scene/scene_label.h — the name an error message about a scene (loading, ray casting, baking)
// starts with.
//
// Messages are one line "PATH: problem"; a scene built in memory (no source file) is named
// "scene".
#pragma once

#include <string>

#include "scene/scene.h"

namespace prt::scene {

// The scene's source path, or "scene" when it has none.
inline std::string scene_label(const Scene& scene) {
  return scene.source_path.empty() ? std::string("scene") : scene.source_path;
}

}  // namespace prt::scene
