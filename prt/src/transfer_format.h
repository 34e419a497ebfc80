// transfer_format.h (internal) — the byte layout of coefficient files (docs/FORMAT.md) and
// the parser shared by read_transfer_data() and Relighter::from_file_bytes().
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

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
  uint32_t storage_code = 0;  // the raw header storage field (Haar: quantisation bits 32/16/8)
};

// --- Haar kind (docs/FORMAT.md, "Haar-wavelet transfer") ---
// For kind 3 the header's `order` field holds the cube size N (a power of two in 8..128), the
// `storage` field the quantisation (32 f32, 16 i16, 8 i8), and the coefficient section holds
// the sparse CSR payload decoded by prt/haar/transfer_file.h; parse_transfer_file checks only
// the container (the payload is checked by its decoder).
inline constexpr uint32_t kHaarStorageF32 = 32, kHaarStorageI16 = 16, kHaarStorageI8 = 8;

// Checks the fields every kind shares: channels, vertex count, array sizes of positions,
// normals, AO and bent normals, primitive ranges, finiteness and the fingerprint.
Status validate_common_transfer_fields(const TransferData& data, const std::string& name);

// Lays out a file: header (with `order_field`, `storage_field`), primitive table, positions,
// normals, a coefficient section of `coefficient_bytes` filled by `write_coefficients` (given
// its first byte, zeroed), AO, bent normals, metadata; computes the checksum. `data` must be
// valid (its `coefficients` are not used).
Result<std::vector<unsigned char>> encode_transfer_container(
    const TransferData& data, uint32_t order_field, uint32_t storage_field,
    uint64_t coefficient_bytes, const std::function<void(unsigned char*)>& write_coefficients,
    const std::string& name);

// Reads a whole file into `bytes`.
Status read_file_bytes(const std::string& path, std::vector<unsigned char>* bytes);

// Validates everything (see read_transfer_data) and fills `out`; out->coefficients points
// into `bytes`. A Haar-kind file is refused (naming prt::read_haar_transfer_file) unless
// `allow_haar`.
Status parse_transfer_file(const void* bytes, std::size_t size, const std::string& name,
                           ParsedTransferFile* out, bool allow_haar = false);

}  // namespace prt::detail
