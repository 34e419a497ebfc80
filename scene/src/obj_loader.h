// scene/src/obj_loader.h (private) — reads a Wavefront OBJ (+ MTL) file into a raw Scene.
//
// See scene/scene_loader.h for the rules. The raw scene has positions, normals (zero vectors
// where they must be computed), per-vertex albedo, triangles (indices checked) and one
// primitive per non-empty shape. Degenerate triangles are still present; load_scene()
// finishes the job. Throws SceneError("PATH: problem").
#pragma once

#include <string>

#include "scene/scene.h"

namespace prt::scene::detail {

// With textures false, map_Kd is not read (Kd is used).
Scene read_obj_scene(const std::string& path, bool textures = true);

}  // namespace prt::scene::detail
