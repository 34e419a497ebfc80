// bake/cpca/matrix_source.h — the matrices of a glossy transfer file as one float array the
// CPCA compressor can read (bake/cpca/compressor.h), without loading them into memory.
//
// Binary32 files are mapped from the file itself (mmap, read-only): the pages are the file's,
// read in as the compressor touches them and dropped by the kernel under memory pressure, so a
// file larger than memory compresses out of core. Binary16 files are expanded to floats, in
// memory when that fits the budget, else into an unlinked temporary file that is mapped the
// same way. FloatScratch is the same choice for an array the compressor makes (the metric's
// scaled copy). What is held in memory is charged to the MemoryBudget given; mapped file
// pages are not (they are the page cache's). POSIX; nothing here is part of the runtime.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "prt/core/memory_budget.h"
#include "prt/core/status.h"
#include "prt/formats/glossy_transfer_file.h"

namespace prt {

// n floats, in memory (charged) or, when the budget refuses them, in an unlinked temporary file
// in `directory` (empty: the system's temporary directory), mapped. Throws MemoryBudgetExceeded
// never: a refusal is what sends the array to a file. Errors (no file, no mapping) come back
// as a Status.
class FloatScratch {
 public:
  static Result<std::unique_ptr<FloatScratch>> create(std::size_t n, MemoryBudget& budget,
                                                      const std::string& what,
                                                      const std::string& directory = {});
  ~FloatScratch();
  FloatScratch(const FloatScratch&) = delete;
  FloatScratch& operator=(const FloatScratch&) = delete;
  float* data() { return data_; }
  bool in_file() const { return mapped_bytes_ != 0; }

 private:
  FloatScratch() = default;
  float* data_ = nullptr;
  std::size_t mapped_bytes_ = 0;  // non-zero: data_ is a mapping of that many bytes
  std::unique_ptr<float[]> memory_;
  MemoryBudget* budget_ = nullptr;
  uint64_t charged_ = 0;
};

// A .prtg read as layout (everything but the matrices, validated in full by streaming:
// prt/formats/glossy_transfer_file.h's read_glossy_transfer_layout) plus its matrices as floats.
class GlossyMatrixSource {
 public:
  static Result<std::unique_ptr<GlossyMatrixSource>> open(
      const std::string& path, MemoryBudget& budget, const std::string& scratch_directory = {});
  ~GlossyMatrixSource();
  GlossyMatrixSource(const GlossyMatrixSource&) = delete;
  GlossyMatrixSource& operator=(const GlossyMatrixSource&) = delete;

  const GlossyTransferData& data() const { return layout_.data; }  // matrices empty
  const float* matrices() const { return matrices_; }  // vertex_count · channels · order⁴
  bool mapped() const { return map_ != nullptr; }

 private:
  GlossyMatrixSource() = default;
  GlossyFileLayout layout_;
  void* map_ = nullptr;
  std::size_t map_bytes_ = 0;
  std::unique_ptr<FloatScratch> expanded_;  // binary16 files
  const float* matrices_ = nullptr;
};

}  // namespace prt
