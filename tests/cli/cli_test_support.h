// tests/cli/cli_test_support.h — running the built `prt` (PRT_CLI_PATH) as a user does, for
// the CLI tests: exit code, stdout and stderr, scratch folders, and the shape of a refusal.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "relight/image_io.h"
#include "support/test_data.h"

namespace prt::test::cli {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code = 0;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `command` through the shell, capturing stdout and stderr into files. ctest runs every
// test case as its own process, several at once (-j), all sharing the output directory: the
// capture files are named by process id as well as by a per-process counter, so that parallel
// cases never read each other's output, and are removed once read.
inline RunResult run(const std::string& command) {
  static int counter = 0;
  const fs::path dir = prt::test::output_path("cli");
  fs::create_directories(dir);
  const std::string stem = "run" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const fs::path out = dir / (stem + ".out");
  const fs::path err = dir / (stem + ".err");
  const std::string full = command + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(full.c_str());
  RunResult r;
  r.exit_code = (status == -1) ? -1 : WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);  // a later process given the same pid starts clean
  fs::remove(err);
  return r;
}

inline std::string prt_cli() {
  return PRT_CLI_PATH;
}

// A fresh, empty scratch directory for one test case.
inline fs::path scratch(const std::string& name) {
  const fs::path dir = prt::test::output_path("cli") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline std::size_t line_count(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += (c == '\n');
  if (!text.empty() && text.back() != '\n') ++n;
  return n;
}

// Every file in `dir` (recursively), to show that a failed command wrote nothing.
inline std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(e.path().string());
  return names;
}

// The shape of a refusal: non-zero exit, a single stderr line that mentions `must_mention`.
inline void require_one_line_error(const RunResult& r, const std::string& must_mention) {
  INFO("stderr: " << r.err);
  CHECK(r.exit_code != 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(must_mention) != std::string::npos);
}

inline void write_constant_env(const fs::path& path, int width, int height, const float rgb[3]) {
  std::vector<float> pixels(static_cast<std::size_t>(3 * width * height));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = rgb[i % 3];
  prt::relight::write_image(path.string(), width, height, 3, pixels.data());
}

}  // namespace prt::test::cli
