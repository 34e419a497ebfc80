// fuzz/fuzz_scene_gltf.cpp — libFuzzer target: the glTF 2.0 scene loader (tinygltf + prt's
// traversal of nodes, accessors, transforms and materials), for both containers: inputs that
// start with the GLB magic "glTF" go to a .glb file, everything else to a .gltf (JSON) file.
//
// A hostile file must either load into a consistent Scene or throw SceneError with a one-line
// message; nothing else (no crash, over-read, UB, other exception type, NaN normal).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_input_file.h"
#include "scene/scene_loader.h"
#include "scene_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = prt::fuzz::write_scratch_file(binary ? ".glb" : ".gltf", data, size);
  try {
    const prt::scene::Scene scene = prt::scene::load_scene(path);
    prt::fuzz::check_scene_invariants(scene);
  } catch (const prt::scene::SceneError& e) {
    prt::fuzz::check_one_line_message(e.what());
  }
  return 0;
}
