// transfer_format.h (internal) — the byte layout of coefficient files (docs/FORMAT.md) and
// the parser shared by read_transfer_data() and Relighter::from_file_bytes().
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "prt/status.h"
#include "prt/transfer_data.h"

namespace prt::detail {

inline constexpr std::size_t kHeaderSize = 192;
inline constexpr std::size_t kSectionAlignment = 16;
inline constexpr std::size_t kPrimitiveRecordSize = 32;
inline constexpr uint32_t kChecksumOffset = 64;

// Header field offsets.
inline constexpr std::size_t kOffMagic = 0, kOffVersion = 4, kOffHeaderSize = 8, kOffKind = 12,
                             kOffOrder = 16, kOffChannels = 20, kOffStorage = 24, kOffFlags = 28,
                             kOffVertexCount = 32, kOffPrimitiveCount = 40, kOffFingerprint = 48,
                             kOffFileSize = 56, kOffChecksum = 64, kOffReserved0 = 68,
                             kOffSections = 72, kOffReserved1 = 184;

inline constexpr uint32_t kFlagAlbedoFolded = 1u, kFlagHasAo = 2u, kFlagHasBentNormals = 4u;
inline constexpr uint32_t kKnownFlags = kFlagAlbedoFolded | kFlagHasAo | kFlagHasBentNormals;

enum Section : int {
  kPrimitives = 0,
  kPositions,
  kNormals,
  kCoefficients,
  kAo,
  kBentNormals,
  kMetadata,
  kSectionCount
};

// Bytes of the blocked coefficient section; false on overflow.
bool blocked_coefficient_bytes(uint64_t vertex_count, uint64_t channels, uint64_t k_count,
                               uint64_t bytes_per_value, uint64_t* out);

struct ParsedTransferFile {
  TransferData data;                            // everything except `coefficients`
  const unsigned char* coefficients = nullptr;  // blocked, data.storage precision, in `bytes`
  std::size_t coefficient_bytes = 0;
};

// Validates everything (see read_transfer_data) and fills `out`; out->coefficients points
// into `bytes`.
Status parse_transfer_file(const void* bytes, std::size_t size, const std::string& name,
                           ParsedTransferFile* out);

}  // namespace prt::detail
