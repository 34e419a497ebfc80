// Tests of prt/core/atomic_file.h: the new contents appear whole or not at all, and no temporary is
// ever left behind.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "prt/core/atomic_file.h"
#include "support/test_data.h"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void put(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Files in `dir` whose name starts with NAME.tmp-.
int temporaries_of(const fs::path& path) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(path.parent_path()))
    n += entry.path().filename().string().rfind(path.filename().string() + ".tmp-", 0) == 0;
  return n;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("write_file_atomically replaces the file", "[atomic_file]") {
  const fs::path path = prt::test::output_path("atomic_bytes.txt");
  put(path, "old contents");
  const std::string text = "new";
  REQUIRE(prt::write_file_atomically(path.string(), text.data(), text.size()).ok());
  CHECK(slurp(path) == "new");
  CHECK(temporaries_of(path) == 0);
}

TEST_CASE("write_file_atomically names the file when the folder is missing", "[atomic_file]") {
  const fs::path path = prt::test::output_path("no_such_folder/atomic.txt");
  const prt::Status s = prt::write_file_atomically(path.string(), "x", 1);
  REQUIRE_FALSE(s.ok());
  CHECK(s.message().rfind(path.string() + ": cannot create " + path.string() + ".tmp-", 0) == 0);
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("replace_file_atomically: a failed write leaves the old file and no temporary",
          "[atomic_file]") {
  const fs::path path = prt::test::output_path("atomic_failed.txt");
  put(path, "old contents");
  const prt::Status s = prt::replace_file_atomically(path.string(), [&](const std::string& tmp) {
    put(tmp, "half");
    return prt::Status::Error(path.string() + ": disk full");
  });
  CHECK(s.message() == path.string() + ": disk full");
  CHECK(slurp(path) == "old contents");
  CHECK(temporaries_of(path) == 0);
}

TEST_CASE("replace_file_atomically: a throwing writer leaves the old file and no temporary",
          "[atomic_file]") {
  const fs::path path = prt::test::output_path("atomic_throw.txt");
  put(path, "old contents");
  CHECK_THROWS_AS(prt::replace_file_atomically(path.string(),
                                               [&](const std::string& tmp) -> prt::Status {
                                                 put(tmp, "half");
                                                 throw std::runtime_error("writer failed");
                                               }),
                  std::runtime_error);
  CHECK(slurp(path) == "old contents");
  CHECK(temporaries_of(path) == 0);
}

TEST_CASE("replace_file_atomically: a failed rename names the file and removes the temporary",
          "[atomic_file]") {
  const fs::path path = prt::test::output_path("atomic_target_is_a_folder");
  fs::create_directories(path / "inside");  // renaming a file over a non-empty folder fails
  const prt::Status s = prt::replace_file_atomically(path.string(), [](const std::string& tmp) {
    put(tmp, "new");
    return prt::Status::Ok();
  });
  REQUIRE_FALSE(s.ok());
  CHECK(contains(s.message(), path.string() + ": cannot rename " + path.string() + ".tmp-"));
  CHECK(fs::is_directory(path / "inside"));
  CHECK(temporaries_of(path) == 0);
}
