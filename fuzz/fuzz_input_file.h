// fuzz/fuzz_input_file.h — writes a fuzz input to a per-process scratch file, for loaders that
// only take a path (the scene loaders dispatch on the extension; OpenImageIO picks its reader
// from the extension and the magic bytes). The file lives in /dev/shm when it exists (RAM), else
// in $TMPDIR or /tmp, and is removed at exit.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace prt::fuzz {

// Overwrites the scratch file with the given extension (e.g. ".obj") by `bytes` and returns its
// path. Aborts when the file cannot be written (an environment problem, not a finding).
inline std::string write_scratch_file(const std::string& extension, const uint8_t* bytes,
                                      std::size_t size) {
  static const std::string directory = [] {
    if (std::filesystem::is_directory("/dev/shm")) return std::string("/dev/shm");
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp != nullptr ? tmp : "/tmp");
  }();
  const std::string path =
      directory + "/prt-fuzz-" + std::to_string(static_cast<long>(getpid())) + extension;
  static std::string last_path;
  if (!last_path.empty() && last_path != path) std::remove(last_path.c_str());
  last_path = path;
  static const bool registered = [] {
    std::atexit([] {
      if (!last_path.empty()) std::remove(last_path.c_str());
    });
    return true;
  }();
  (void)registered;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(bytes, 1, size, f) != size) std::abort();
  if (std::fclose(f) != 0) std::abort();
  return path;
}

}  // namespace prt::fuzz
