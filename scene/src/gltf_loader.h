// scene/src/gltf_loader.h (private) — reads a glTF 2.0 file (.gltf or .glb) into a raw Scene.
//
// See scene/scene_loader.h for what is read. The raw scene has world-space positions, normals
// (zero vectors where the file has none, to be computed later), per-vertex albedo, triangles
// (indices checked against their primitive), primitives and cameras. Degenerate triangles are
// still present; load_scene() finishes the job. Throws SceneError("PATH: problem").
#pragma once

#include <string>

#include "scene/scene.h"

namespace prt::scene::detail {

// With textures false, base-colour textures are not read (their materials keep their factor).
Scene read_gltf_scene(const std::string& path, bool binary, bool textures = true);

}  // namespace prt::scene::detail
