// matrix_source.cpp — a .prtg's matrices mapped or expanded for the compressor; see
// bake/cpca/matrix_source.h.
#include "bake/cpca/matrix_source.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <new>
#include <vector>

#include "prt/core/half.h"

namespace prt {
namespace {

std::string errno_text() {
  return std::strerror(errno);
}

// A new file in `directory`, unlinked at once (it lives while it is open or mapped).
int unlinked_temporary(const std::string& directory, std::string* error) {
  std::error_code ec;
  const std::string dir =
      directory.empty() ? std::filesystem::temp_directory_path(ec).string() : directory;
  std::string name = dir + "/prt-cpca-scratch-XXXXXX";
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = mkstemp(buffer.data());
  if (fd < 0) {
    *error = "cannot create a scratch file in " + dir + ": " + errno_text();
    return -1;
  }
  unlink(buffer.data());
  return fd;
}

}  // namespace

Result<std::unique_ptr<FloatScratch>> FloatScratch::create(std::size_t n, MemoryBudget& budget,
                                                           const std::string& what,
                                                           const std::string& directory) {
  std::unique_ptr<FloatScratch> s(new FloatScratch());
  const uint64_t bytes = uint64_t(n) * sizeof(float);
  try {
    budget.charge(bytes, what);
    s->budget_ = &budget;
    s->charged_ = bytes;
    s->memory_.reset(new float[std::max<std::size_t>(n, 1)]);
    s->data_ = s->memory_.get();
    return s;
  } catch (const MemoryBudgetExceeded&) {
  } catch (const std::bad_alloc&) {
  }
  if (s->charged_ != 0) budget.release(s->charged_);
  s->charged_ = 0;
  std::string error;
  const int fd = unlinked_temporary(directory, &error);
  if (fd < 0) return Status::Error(what + ": " + error);
  const std::size_t size = std::max<std::size_t>(bytes, 1);
  if (ftruncate(fd, static_cast<off_t>(size)) != 0) {
    error = errno_text();
    close(fd);
    return Status::Error(what + ": cannot size a scratch file of " + std::to_string(size) +
                         " bytes: " + error);
  }
  void* map = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  error = errno_text();
  close(fd);
  if (map == MAP_FAILED) return Status::Error(what + ": cannot map a scratch file: " + error);
  s->data_ = static_cast<float*>(map);
  s->mapped_bytes_ = size;
  return s;
}

FloatScratch::~FloatScratch() {
  if (mapped_bytes_ != 0) munmap(data_, mapped_bytes_);
  if (budget_ != nullptr && charged_ != 0) budget_->release(charged_);
}

Result<std::unique_ptr<GlossyMatrixSource>> GlossyMatrixSource::open(
    const std::string& path, MemoryBudget& budget, const std::string& scratch_directory) {
  Result<GlossyFileLayout> layout = read_glossy_transfer_layout(path);
  if (!layout.ok()) return layout.status();
  std::unique_ptr<GlossyMatrixSource> s(new GlossyMatrixSource());
  s->layout_ = std::move(layout).value();
  const GlossyTransferData& d = s->layout_.data;
  const std::size_t floats =
      static_cast<std::size_t>(d.vertex_count * d.channels * d.matrix_floats());
  if (floats == 0) return s;
  if (d.storage == Precision::F32) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) return Status::Error(path + ": cannot open: " + errno_text());
    const std::size_t bytes = static_cast<std::size_t>(s->layout_.matrix_offset) + 4 * floats;
    void* map = mmap(nullptr, bytes, PROT_READ, MAP_PRIVATE, fd, 0);
    const std::string error = errno_text();
    close(fd);
    if (map == MAP_FAILED) return Status::Error(path + ": cannot map the matrices: " + error);
    s->map_ = map;
    s->map_bytes_ = bytes;
    s->matrices_ = reinterpret_cast<const float*>(static_cast<const unsigned char*>(map) +
                                                  s->layout_.matrix_offset);
    return s;
  }
  auto scratch = FloatScratch::create(floats, budget, path + ": the expanded float16 matrices",
                                      scratch_directory);
  if (!scratch.ok()) return scratch.status();
  s->expanded_ = std::move(scratch).value();
  // Expanded a block of vertices at a time (read_glossy_matrices converts).
  const uint64_t per_vertex = d.channels * d.matrix_floats();
  const uint64_t block = std::max<uint64_t>(1, (1u << 20) / per_vertex);
  for (uint64_t v = 0; v < d.vertex_count; v += block) {
    const uint64_t n = std::min(block, d.vertex_count - v);
    if (Status st =
            read_glossy_matrices(path, s->layout_, v, n, s->expanded_->data() + v * per_vertex);
        !st.ok())
      return st;
  }
  s->matrices_ = s->expanded_->data();
  return s;
}

GlossyMatrixSource::~GlossyMatrixSource() {
  if (map_ != nullptr) munmap(map_, map_bytes_);
}

}  // namespace prt
