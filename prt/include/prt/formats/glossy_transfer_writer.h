// prt/formats/glossy_transfer_writer.h — writing a glossy transfer file (.prtg) while its
// matrices are still being made: a bake hands over each block of vertices' matrices as it
// finishes it, and never holds them all.
//
// The file is byte for byte the one write_glossy_transfer_file writes for the same data
// (docs/FORMAT.md, "Glossy transfer files", version 1): the sections before the matrices are
// written when the writer is created, each block of matrices at its own offset when it is
// written (converted to binary16 for F16 storage), and the metadata, the header's final fields
// and the checksum at finish(). The CRC-32C of each block is computed as it is written and the
// blocks' CRCs are joined in file order at the end (crc32c_combine), so nothing is read back.
// The file is written to PATH.tmp-<process id> and renamed over PATH by finish(); a writer
// destroyed before finish() — or a finish() that fails — removes the temporary and leaves PATH
// as it was (prt/core/atomic_file.h's contract).
//
// Memory: the sections before the matrices (44 bytes a vertex plus the tables) and one CRC per
// block. Like the rest of the runtime it uses no threads and no locks: callers writing from
// several threads serialise their calls.
// Nothing here throws; errors are one-line Status messages "PATH: problem". Compiles as C++17.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/transfer.h"

namespace prt {

class GlossyTransferFileWriter {
 public:
  // Starts PATH for `skeleton`: everything of the file but its matrices (skeleton.matrices must
  // be empty) and its metadata (given to finish()). Validates it as validate_glossy_transfer_data
  // does, creates the temporary and writes the sections that precede the matrices.
  static Result<std::unique_ptr<GlossyTransferFileWriter>> create(const std::string& path,
                                                                  GlossyTransferData skeleton);

  GlossyTransferFileWriter(const GlossyTransferFileWriter&) = delete;
  GlossyTransferFileWriter& operator=(const GlossyTransferFileWriter&) = delete;
  ~GlossyTransferFileWriter();  // removes the temporary unless finish() succeeded

  // Writes the matrices of vertices [first_vertex, first_vertex + vertex_count):
  // vertex_count · channels · order⁴ floats in GlossyTransferData::matrices' order. Blocks may
  // come in any order; each vertex exactly once. Checks finiteness (and, for
  // F16, the binary16 range) like validate_glossy_transfer_data.
  Status write(uint64_t first_vertex, uint64_t vertex_count, const float* matrices);

  // Writes the metadata, the header and the checksum, closes and renames the file over PATH.
  // Fails (and removes the temporary) when some vertex's matrices were never written.
  Status finish(const std::string& metadata_json);

  const std::string& path() const { return path_; }

 private:
  GlossyTransferFileWriter() = default;
  Status fail_and_close(const std::string& problem);

  struct Block {
    uint64_t first = 0, count = 0, bytes = 0;
    uint32_t crc = 0;
  };
  std::string path_, temporary_;
  GlossyTransferData skeleton_;
  uint64_t matrix_offset_ = 0, bytes_per_vertex_ = 0;
  std::FILE* file_ = nullptr;
  std::vector<Block> blocks_;
  bool failed_ = false, finished_ = false;
};

}  // namespace prt
