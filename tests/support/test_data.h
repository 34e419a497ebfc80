// tests/support/test_data.h — where tests find data and write scratch output.
#pragma once

#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

namespace prt::test {

// Path of a file under ../shared/data (beside the checkout).
inline std::filesystem::path shared_data(const std::string& relative) {
  return std::filesystem::path(PRT_SHARED_DATA_DIR) / relative;
}

// Path of a file under the project's own data/.
inline std::filesystem::path project_data(const std::string& relative) {
  return std::filesystem::path(PRT_SOURCE_DIR) / "data" / relative;
}

// A scratch path for test output (inside the build tree).
inline std::filesystem::path output_path(const std::string& name) {
  return std::filesystem::path(PRT_TEST_OUTPUT_DIR) / name;
}

}  // namespace prt::test

// Skips the rest of the test case, with a message, when a shared data file is absent.
// (Catch2 v2 has no SKIP; the case is reported as passed with a warning.)
#define PRT_REQUIRE_SHARED_DATA(path)                                                 \
  do {                                                                                \
    if (!std::filesystem::exists(path)) {                                             \
      WARN("skipping: " << (path).string() << " is missing (../shared is not beside " \
                                              "the checkout)");                       \
      return;                                                                         \
    }                                                                                 \
  } while (0)
