// Atomic file replacement; see prt/core/atomic_file.h.
#include "prt/core/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>

#if defined(_WIN32)
#include <process.h>
#define PRT_GETPID _getpid
#else
#include <unistd.h>
#define PRT_GETPID getpid
#endif

namespace prt {
namespace {

Status fail(const std::string& path, const std::string& problem) {
  return Status::Error(path + ": " + problem);
}

// Removes the temporary when it goes out of scope, unless it has been renamed into place.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& name) : name_(name) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (!kept_) std::remove(name_.c_str());
  }
  void keep() { kept_ = true; }

 private:
  const std::string& name_;
  bool kept_ = false;
};

}  // namespace

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp-" + std::to_string(PRT_GETPID());
}

Status replace_file_atomically(const std::string& path,
                               const std::function<Status(const std::string& temporary)>& write) {
  std::string temporary;
  try {
    temporary = temporary_path_for(path);
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory");
  }
  TemporaryFile guard(temporary);
  Status written = write(temporary);
  if (!written.ok()) return written;
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int saved_errno = errno;
    return fail(path, "cannot rename " + temporary + ": " + std::strerror(saved_errno));
  }
  guard.keep();
  return Status::Ok();
}

Status write_file_atomically(const std::string& path, const void* data, std::size_t size) {
  // One captured reference keeps the callable inside std::function (no allocation).
  const struct {
    const std::string& path;
    const void* data;
    std::size_t size;
  } in{path, data, size};
  return replace_file_atomically(path, [&in](const std::string& temporary) {
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (f == nullptr)
      return fail(in.path, "cannot create " + temporary + ": " + std::strerror(errno));
    bool ok = std::fwrite(in.data, 1, in.size, f) == in.size;
    int saved_errno = errno;
    ok = (std::fflush(f) == 0) && ok;
    if (ok) saved_errno = errno;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) return fail(in.path, "cannot write " + temporary + ": " + std::strerror(saved_errno));
    return Status::Ok();
  });
}

}  // namespace prt
