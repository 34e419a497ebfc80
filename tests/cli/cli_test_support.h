// tests/cli/cli_test_support.h — running the built `prt` (PRT_CLI_PATH) as a user does, for
// the CLI tests: exit code, stdout and stderr, scratch folders and the shape of a refusal (all
// from cli_run.h), and writing a lighting image for a command to read.
#pragma once

#include <filesystem>
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

}  // namespace prt::test::cli
