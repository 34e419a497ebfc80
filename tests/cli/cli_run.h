// tests/cli/cli_run.h — running the built `prt` (PRT_CLI_PATH) from a test and looking at what it
// left behind: exit code, stdout, stderr, files.
//
// ctest runs every test case as its own process, several at once (-j), all sharing the output
// directory: capture files are named by process id and a per-process counter, so parallel cases
// never read each other's output, and are removed once read.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "support/test_data.h"

namespace prt::test::cli {

struct RunResult {
  int exit_code = 0;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `command` through the shell, capturing stdout and stderr.
inline RunResult run(const std::string& command) {
  static int counter = 0;
  const std::filesystem::path dir = output_path("cli");
  std::filesystem::create_directories(dir);
  const std::string stem = "run" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::filesystem::path out = dir / (stem + ".out"), err = dir / (stem + ".err");
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  RunResult r;
  r.exit_code = (status == -1) ? -1 : WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

inline std::string prt_cli() {
  return PRT_CLI_PATH;
}

// A fresh, empty scratch directory for one test case.
inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = output_path("cli") / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::size_t line_count(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += (c == '\n');
  if (!text.empty() && text.back() != '\n') ++n;
  return n;
}

// Every file in `dir` (recursively).
inline std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    names.push_back(e.path().string());
  return names;
}

// The shape of a refusal: non-zero exit, a single stderr line that mentions `must_mention`.
inline void require_one_line_error(const RunResult& r, const std::string& must_mention) {
  INFO("stderr: " << r.err);
  CHECK(r.exit_code != 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(must_mention) != std::string::npos);
}

}  // namespace prt::test::cli
