// tests/cli/cli_test_support.h — running the built `prt` (PRT_CLI_PATH) as a user does, for
// the CLI tests: exit code, stdout and stderr, scratch folders and the shape of a refusal (all
// from cli_run.h), and writing a lighting image or a small lit scene for a command to read.
#pragma once

#include <filesystem>
#include <fstream>
#include <vector>

#include "cli_run.h"
#include "relight/image_io.h"

namespace prt::test::cli {

namespace fs = std::filesystem;

// A width × height RGB image of one colour, written with relight's image I/O.
inline void write_constant_env(const fs::path& path, int width, int height, const float rgb[3]) {
  std::vector<float> pixels(static_cast<std::size_t>(3 * width * height));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = rgb[i % 3];
  prt::relight::write_image(path.string(), width, height, 3, pixels.data());
}

// DIR/box.obj (+ box.mtl): an open box 1 unit wide, white walls ("walls", Kd 0.7) and a lamp
// under the ceiling ("lamp", Ke 4): a scene for bake and radiosity alike.
inline fs::path write_lit_box(const fs::path& dir) {
  std::ofstream(dir / "box.mtl") << "newmtl white\nKd 0.7 0.7 0.7\nnewmtl lamp\nKd 0.5 0.5 0.5\n"
                                    "Ke 4 4 4\n";
  std::ofstream(dir / "box.obj")
      << "mtllib box.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
         "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"
         "o walls\nusemtl white\nf 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\n"
         "o lamp\nusemtl lamp\nf 9 10 11 12\n";
  return dir / "box.obj";
}

}  // namespace prt::test::cli
