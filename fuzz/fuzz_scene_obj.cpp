// fuzz/fuzz_scene_obj.cpp — libFuzzer target: the OBJ scene loader (tinyobjloader + prt's
// post-processing: normals, degenerate-triangle removal, index and finiteness checks).
//
// A hostile file must either load into a consistent Scene or throw SceneError with a one-line
// message; nothing else (no crash, over-read, UB, other exception type, NaN normal).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_input_file.h"
#include "scene/scene_loader.h"
#include "scene_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = prt::fuzz::write_scratch_file(".obj", data, size);
  try {
    const prt::scene::Scene scene = prt::scene::load_scene(path);
    prt::fuzz::check_scene_invariants(scene);
  } catch (const prt::scene::SceneError& e) {
    prt::fuzz::check_one_line_message(e.what());
  }
  return 0;
}
