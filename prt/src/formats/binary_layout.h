// binary_layout.h (internal) — the byte layout of coefficient files (docs/FORMAT.md) and
// the parser shared by read_transfer_data() and Relighter::from_file_bytes(); and the pieces
// every binary file of prt shares (coefficient, glossy transfer, emitter-response and CPCA
// files): the one-line error, little-endian fields, the checksum, the recorded file size, the
// section table and the primitive table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/formats/transfer_data.h"

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

// --- shared by the binary files (implemented in transfer_format.cpp) ---

// The one-line error every reader and writer gives: "name: problem".
Status fail(const std::string& name, const std::string& problem);

// Little-endian unsigned fields at any byte address.
inline uint32_t load_u32(const unsigned char* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}
inline uint64_t load_u64(const unsigned char* p) {
  return uint64_t{load_u32(p)} | uint64_t{load_u32(p + 4)} << 32;
}
inline void store_u32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
inline void store_u64(unsigned char* p, uint64_t v) {
  store_u32(p, static_cast<uint32_t>(v));
  store_u32(p + 4, static_cast<uint32_t>(v >> 32));
}

// x rounded up to a multiple of `alignment` (> 0).
inline uint64_t align_up(uint64_t x, uint64_t alignment = kSectionAlignment) {
  return (x + alignment - 1) / alignment * alignment;
}

// CRC-32C (prt/formats/crc32c.h) of `size` bytes with the 4-byte checksum field at
// `checksum_offset` taken as zero; size ≥ checksum_offset + 4.
uint32_t file_checksum(const unsigned char* bytes, std::size_t size, std::size_t checksum_offset);

// The file size a header records against the `size` bytes present: "truncated: …" when the file
// is shorter, "… unexpected bytes after …" when longer.
Status check_recorded_size(const std::string& name, uint64_t recorded, std::size_t size);

// The stored checksum (at `checksum_offset`) against file_checksum(): "checksum mismatch
// (stored 0x…, computed 0x…)".
Status check_checksum(const std::string& name, const unsigned char* bytes, std::size_t size,
                      std::size_t checksum_offset);

// A header's section table: `count` sections, each at offsets[s] with sizes[s] bytes, named
// names[s] in messages. A section with expected[s] != kAnySize must hold exactly that many bytes
// (`vertex_count` is named in that message). Every non-empty section lies inside the
// `file_size`-byte file after the `header_size`-byte header, at a multiple of
// kSectionAlignment, and no two overlap; an empty one has offset 0.
inline constexpr uint64_t kAnySize = ~uint64_t{0};
Status check_section_table(const std::string& name, int count, const uint64_t* offsets,
                           const uint64_t* sizes, const char* const* names,
                           const uint64_t* expected, uint64_t header_size, uint64_t file_size,
                           uint64_t vertex_count);

// The primitive table (docs/FORMAT.md): kPrimitiveRecordSize-byte records (first vertex, vertex
// count, name offset from the table's start, name size, all u64), then the names.
uint64_t primitive_table_bytes(const std::vector<PrimitiveRange>& primitives);
void write_primitive_table(unsigned char* table, const std::vector<PrimitiveRange>& primitives);
// Reads `count` records from a `section_size`-byte table (count · kPrimitiveRecordSize ≤
// section_size, checked by the caller): names must lie inside the table after the records; with
// `check_ranges`, each range must lie within `vertex_count` vertices. May throw std::bad_alloc.
Status read_primitive_table(const unsigned char* table, uint64_t section_size, uint64_t count,
                            uint64_t vertex_count, bool check_ranges, const std::string& name,
                            std::vector<PrimitiveRange>* out);

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
// the sparse CSR payload decoded by prt/formats/haar_transfer_file.h; parse_transfer_file checks
// only the container (the payload is checked by its decoder).
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
