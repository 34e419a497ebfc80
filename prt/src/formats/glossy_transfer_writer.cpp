// glossy_transfer_writer.cpp — the streaming glossy transfer file writer; see
// prt/formats/glossy_transfer_writer.h.
#include "prt/formats/glossy_transfer_writer.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>

#include "formats/binary_layout.h"
#include "formats/glossy_file_plan.h"
#include "prt/core/atomic_file.h"
#include "prt/core/half.h"
#include "prt/formats/crc32c.h"

namespace prt {
namespace {

// Writes `size` bytes at `offset`; false on failure.
bool write_at(std::FILE* f, uint64_t offset, const void* data, std::size_t size) {
  if (size == 0) return true;
  if (std::fseek(f, static_cast<long>(offset), SEEK_SET) != 0) return false;
  return std::fwrite(data, 1, size, f) == size;
}

}  // namespace

Result<std::unique_ptr<GlossyTransferFileWriter>> GlossyTransferFileWriter::create(
    const std::string& path, GlossyTransferData skeleton) {
  if (!skeleton.matrices.empty())
    return detail::fail(path, "a streamed file's data must not hold matrices");
  skeleton.metadata_json.clear();
  Result<detail::GlossyFilePlan> plan = detail::plan_glossy_file(skeleton, path);
  if (!plan.ok()) return plan.status();
  try {
    std::unique_ptr<GlossyTransferFileWriter> w(new GlossyTransferFileWriter());
    w->path_ = path;
    w->temporary_ = temporary_path_for(path);
    w->matrix_offset_ = plan->matrix_offset;
    w->bytes_per_vertex_ = uint64_t{skeleton.channels} * skeleton.matrix_floats() *
                           (skeleton.storage == Precision::F16 ? 2 : 4);
    w->skeleton_ = std::move(skeleton);
    w->file_ = std::fopen(w->temporary_.c_str(), "wb");
    if (w->file_ == nullptr)
      return detail::fail(path, "cannot create " + w->temporary_ + ": " + std::strerror(errno));
    // The prefix now (its header is rewritten at finish), so the file grows in order.
    if (!write_at(w->file_, 0, plan->prefix.data(), plan->prefix.size()))
      return w->fail_and_close("cannot write " + w->temporary_ + ": " + std::strerror(errno));
    return w;
  } catch (const std::bad_alloc&) {
    return detail::fail(path, "out of memory");
  }
}

GlossyTransferFileWriter::~GlossyTransferFileWriter() {
  if (file_ != nullptr) std::fclose(file_);
  if (!finished_ && !temporary_.empty()) std::remove(temporary_.c_str());
}

Status GlossyTransferFileWriter::fail_and_close(const std::string& problem) {
  failed_ = true;
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  std::remove(temporary_.c_str());
  return detail::fail(path_, problem);
}

Status GlossyTransferFileWriter::write(uint64_t first, uint64_t count, const float* m) {
  const GlossyTransferData& d = skeleton_;
  if (first > d.vertex_count || count > d.vertex_count - first)
    return detail::fail(path_, "matrices of vertices " + std::to_string(first) + " + " +
                                   std::to_string(count) + " lie beyond the " +
                                   std::to_string(d.vertex_count) + " vertices");
  const std::size_t floats = static_cast<std::size_t>(count * d.channels * d.matrix_floats());
  if (Status s = detail::check_glossy_matrix_entries(m, floats, first, d.channels, d.order,
                                                     d.storage, path_);
      !s.ok())
    return s;
  Block block{first, count, count * bytes_per_vertex_, 0};
  std::vector<uint16_t> halves;
  const void* bytes = m;
  try {
    if (d.storage == Precision::F16) {
      halves.resize(floats);
      convert_floats_to_halves(m, floats, halves.data());
      bytes = halves.data();
    }
  } catch (const std::bad_alloc&) {
    return fail_and_close("out of memory");
  }
  block.crc = crc32c(bytes, static_cast<std::size_t>(block.bytes));
  if (failed_ || file_ == nullptr) return detail::fail(path_, "the file was abandoned");
  if (!write_at(file_, matrix_offset_ + first * bytes_per_vertex_, bytes,
                static_cast<std::size_t>(block.bytes)))
    return fail_and_close("cannot write " + temporary_ + ": " + std::strerror(errno));
  try {
    blocks_.push_back(block);
  } catch (const std::bad_alloc&) {
    return fail_and_close("out of memory");
  }
  return Status::Ok();
}

Status GlossyTransferFileWriter::finish(const std::string& metadata_json) {
  if (failed_ || file_ == nullptr) return detail::fail(path_, "the file was abandoned");
  try {
    std::sort(blocks_.begin(), blocks_.end(),
              [](const Block& a, const Block& b) { return a.first < b.first; });
    uint64_t next = 0;
    for (const Block& b : blocks_) {
      if (b.first != next) break;
      next += b.count;
    }
    if (next != skeleton_.vertex_count)
      return fail_and_close("the matrices of vertex " + std::to_string(next) +
                            " were not written (or were written twice)");
    skeleton_.metadata_json = metadata_json;
    Result<detail::GlossyFilePlan> plan = detail::plan_glossy_file(skeleton_, path_);
    if (!plan.ok()) {
      failed_ = true;
      std::fclose(file_);
      file_ = nullptr;
      std::remove(temporary_.c_str());
      return plan.status();
    }
    // CRC over prefix (checksum field zero), the blocks in file order, then the tail.
    uint32_t crc = crc32c(plan->prefix.data(), plan->prefix.size());
    for (const Block& b : blocks_) crc = crc32c_combine(crc, b.crc, b.bytes);
    crc = crc32c(plan->tail.data(), plan->tail.size(), crc);
    detail::store_u32(plan->prefix.data() + detail::glossy_checksum_offset(), crc);
    const uint64_t tail_at = plan->matrix_offset + plan->matrix_bytes;
    bool ok = write_at(file_, 0, plan->prefix.data(), plan->prefix.size()) &&
              write_at(file_, tail_at, plan->tail.data(), plan->tail.size());
    int saved = errno;
    ok = std::fflush(file_) == 0 && ok;
    if (ok) saved = errno;
    ok = std::fclose(file_) == 0 && ok;
    file_ = nullptr;
    if (!ok) return fail_and_close("cannot write " + temporary_ + ": " + std::strerror(saved));
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
      return fail_and_close("cannot rename " + temporary_ + ": " + std::strerror(errno));
    finished_ = true;
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    return fail_and_close("out of memory");
  }
}

}  // namespace prt
