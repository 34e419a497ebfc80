// The engine runtime (prt/ and sh/) needs nothing but the standard library: every #include in
// their headers and sources names a standard header, a CPU-intrinsics or POSIX/Windows system
// header, or a header of prt/ or sh/ themselves. A third-party header (Embree, OpenImageIO,
// tinygltf, TBB, glm), a header of a higher layer (scene/, bake/, ...) or <thread> fails here
// before an engine finds out.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <catch2/catch.hpp>

namespace fs = std::filesystem;

namespace {

// The C++17 standard headers the runtime may use, and the system headers of its CPU dispatch
// and atomic file write, the memory budget's reading of peak memory (sys/resource.h) and the
// part file reader's read-only mapping (POSIX; a plain read on Windows). <thread>,
// <mutex>, <future> and <condition_variable> are left out on purpose: the runtime starts no
// threads.
const std::set<std::string>& allowed_system_headers() {
  static const std::set<std::string> headers = {
      "algorithm",   "array",         "cassert",        "cerrno",     "cfloat",
      "climits",     "cmath",         "cstddef",        "cstdint",    "cstdio",
      "cstdlib",     "cstring",       "filesystem",     "fstream",    "functional",
      "iterator",    "limits",        "memory",         "new",        "numeric",
      "optional",    "set",           "sstream",        "stdexcept",  "string",
      "string_view", "type_traits",   "utility",        "variant",    "vector",
      "map",         "unordered_map", "tuple",          "bit",        "atomic",
      "immintrin.h", "cpuid.h",       "unistd.h",       "process.h",  "io.h",
      "windows.h",   "cctype",        "sys/resource.h", "sys/mman.h", "sys/stat.h",
      "fcntl.h"};
  return headers;
}

// Whether `name` (as written in #include "name") is a header of prt/ or sh/.
bool is_runtime_header(const fs::path& root, const fs::path& including_file,
                       const std::string& name) {
  for (const fs::path& dir : {root / "prt/include", root / "sh/include", root / "prt/src",
                              root / "sh/src", including_file.parent_path()}) {
    if (fs::exists(dir / name)) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("the runtime (prt/, sh/) includes only the standard library and its own headers") {
  const fs::path root = PRT_SOURCE_DIR;
  const std::regex include_line(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  int files = 0, includes = 0;
  for (const char* folder : {"prt", "sh"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, include_line)) continue;
        ++includes;
        INFO(entry.path().string() << ": " << line);
        if (m[1] == "<") {
          CHECK(allowed_system_headers().count(m[2]) == 1);
        } else {
          CHECK(is_runtime_header(root, entry.path(), m[2]));
        }
      }
    }
  }
  CHECK(files > 80);      // the scan saw the runtime (about 110 files)
  CHECK(includes > 400);  // and its includes
}
