// bake/src/float_scratch_file.h (private) — an array of floats kept in an unlinked temporary
// file and read or written by ranges (pread/pwrite, safe from several threads at distinct
// ranges). The glossy bake's streamed bounces keep the direct transfer and the bounce being
// written here, so that memory holds only the bounce that is read at random. The file is
// unlinked at once: it disappears with the process whatever happens, and nothing is left beside
// the output. The pages are the page cache's (not the process's), dropped under pressure.
// The file's blocks are reserved when it is opened (fallocate, where the file system has it), so
// that a disk too small for the bake fails at once, before its ray pass, and not at a write hours
// later; where the file system cannot reserve, a full disk fails the first write that finds it.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace prt::bake::detail {

class FloatScratchFile {
 public:
  // A file for `count` floats in `directory` (the system's temporary directory when empty).
  // `what` names it in errors. Returns false with *error set when it cannot be made.
  bool open(const std::string& directory, uint64_t count, const std::string& what,
            std::string* error) {
    what_ = what;
    std::error_code ec;
    std::string dir =
        directory.empty() ? std::filesystem::temp_directory_path(ec).string() : directory;
    std::string name = dir + "/prt-glossy-scratch-XXXXXX";
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    fd_ = mkstemp(buffer.data());
    if (fd_ < 0) {
      *error = what + ": cannot create a scratch file in " + dir + ": " + std::strerror(errno);
      return false;
    }
    unlink(buffer.data());
    const off_t bytes = static_cast<off_t>(count * sizeof(float));
    if (ftruncate(fd_, bytes) != 0 || !reserve(bytes)) {
      *error = what + ": cannot size a scratch file in " + dir + ": " + std::strerror(errno);
      return false;
    }
    return true;
  }
  ~FloatScratchFile() {
    if (fd_ >= 0) close(fd_);
  }
  FloatScratchFile() = default;
  FloatScratchFile(const FloatScratchFile&) = delete;
  FloatScratchFile& operator=(const FloatScratchFile&) = delete;

  // Floats [first, first + count) from / to `data`; false with *error set on failure.
  bool write(uint64_t first, uint64_t count, const float* data, std::string* error) const {
    return transfer(first, count, const_cast<float*>(data), true, error);
  }
  bool read(uint64_t first, uint64_t count, float* data, std::string* error) const {
    return transfer(first, count, data, false, error);
  }

 private:
  // Reserves the blocks of [0, bytes); true when done or when the file system cannot reserve.
  bool reserve(off_t bytes) const {
#if defined(__linux__)
    if (bytes == 0) return true;
    int r;
    do {
      r = fallocate(fd_, 0, 0, bytes);
    } while (r != 0 && errno == EINTR);
    return r == 0 || errno == EOPNOTSUPP || errno == ENOSYS;
#else
    (void)bytes;
    return true;
#endif
  }

  bool transfer(uint64_t first, uint64_t count, float* data, bool writing,
                std::string* error) const {
    char* p = reinterpret_cast<char*>(data);
    uint64_t left = count * sizeof(float), at = first * sizeof(float);
    while (left > 0) {
      const ssize_t n = writing ? pwrite(fd_, p, left, static_cast<off_t>(at))
                                : pread(fd_, p, left, static_cast<off_t>(at));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        *error =
            what_ +
            (writing ? ": cannot write the scratch file: " : ": cannot read the scratch file: ") +
            (n < 0 ? std::strerror(errno) : "unexpected end");
        return false;
      }
      p += n;
      at += uint64_t(n);
      left -= uint64_t(n);
    }
    return true;
  }

  int fd_ = -1;
  std::string what_;
};

}  // namespace prt::bake::detail
