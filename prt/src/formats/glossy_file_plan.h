// formats/glossy_file_plan.h — the bytes of a glossy transfer file around its matrix section,
// for the streaming writer (prt/formats/glossy_transfer_writer.h). Private to prt/formats.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/transfer.h"

namespace prt::detail {

// A file cut at its matrix section: prefix = bytes [0, matrix_offset) (the header with the
// checksum field zero, and every section before the matrices), then matrix_bytes of matrices,
// then tail (padding, the metadata, padding) up to the end of the file.
struct GlossyFilePlan {
  std::vector<unsigned char> prefix;
  uint64_t matrix_offset = 0, matrix_bytes = 0;
  std::vector<unsigned char> tail;
  uint64_t file_size() const { return prefix.size() + matrix_bytes + tail.size(); }
};

// Validates `d` but for its matrices (which it need not hold) and lays its file out.
Result<GlossyFilePlan> plan_glossy_file(const GlossyTransferData& d, const std::string& name);

// Every one of `count` matrix floats, the first at vertex `first_vertex`, finite (and within
// binary16 for F16 storage); the error names the entry as validate_glossy_transfer_data does.
Status check_glossy_matrix_entries(const float* m, std::size_t count, uint64_t first_vertex,
                                   uint32_t channels, uint32_t order, Precision storage,
                                   const std::string& name);

// The checksum field's offset in the header.
uint64_t glossy_checksum_offset();

}  // namespace prt::detail
