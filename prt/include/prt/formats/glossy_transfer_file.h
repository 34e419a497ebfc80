// prt/formats/glossy_transfer_file.h — reading and writing glossy transfer files
// (prt::GlossyTransferData, prt/glossy/transfer.h: one n²×n² transfer matrix per vertex, global
// lighting SH to local incident radiance SH).
//
// The byte layout is specified in docs/FORMAT.md ("Glossy transfer files"): little-endian,
// magic "PRTG", version 1, a 192-byte header, 16-byte-aligned sections (primitive table,
// positions, normals, tangents, materials, material of each vertex, matrices, metadata),
// CRC-32C (prt/formats/crc32c.h) over the whole file with the checksum field zeroed, and the
// geometry fingerprint of the coefficient files (prt/formats/geometry_check.h). Matrices are stored
// vertex-major, channel, row i (local), column j (global) — the in-memory order — as IEEE binary32
// or binary16 (prt/core/half.h); binary16 is expanded to float on reading. Materials are stored as
// their model and every parameter (binary64); a MERL material by its path (the file it names
// is not read here).
//
// Nothing here throws: errors come back as a Status whose message is one line,
// "NAME: problem", NAME being the path (or the name given for a memory buffer).
// Compiles as C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/transfer.h"

namespace prt {

inline constexpr uint32_t kGlossyFileVersion = 1;
inline constexpr uint32_t kMaxGlossyOrder = 10;  // orders 1 .. 10 (100 × 100 matrices)
inline constexpr uint32_t kMaxGlossyMaterials = 1u << 20;

// True when `bytes` start with the glossy magic "PRTG" (size ≥ 4); for tools that dispatch on
// the kind of a file.
bool is_glossy_transfer_file(const void* bytes, std::size_t size);

// Checks that `data` is self-consistent and storable: order in [1, kMaxGlossyOrder], channels
// 1 or 3, a known storage, vertex_count <= 2³² − 1, array sizes matching vertex_count, primitive
// ranges inside the vertex range, unit normals and tangents (|·| within 1e-3 of 1, tangent ⊥
// normal within 1e-3, w = ±1), at least one material when there are vertices and every
// material_of_vertex below materials.size(), materials with known enumerators and finite
// parameters, every number finite, and fingerprint either 0 (unset) or equal to
// geometry_fingerprint(positions). With storage == F16 also that every matrix entry fits in
// binary16; the error names the vertex, channel, row, column and value.
Status validate_glossy_transfer_data(const GlossyTransferData& data,
                                     const std::string& name_for_errors);

// Encodes `data` into the bytes of a glossy transfer file (validating it first). The stored
// fingerprint is always geometry_fingerprint(data.positions).
Result<std::vector<unsigned char>> encode_glossy_transfer_file(const GlossyTransferData& data,
                                                               const std::string& name_for_errors);

// Writes atomically (prt/core/atomic_file.h): on any error PATH is left as it was.
Status write_glossy_transfer_file(const std::string& path, const GlossyTransferData& data);

// Reads and fully validates a file (bounds, sizes, checksum, finiteness, indices, fingerprint).
// A coefficient file ("PRTC") is refused with a message that says so.
Result<GlossyTransferData> read_glossy_transfer_file(const std::string& path);
Result<GlossyTransferData> read_glossy_transfer_data(const void* bytes, std::size_t size,
                                                     const std::string& name_for_errors);

// A file read without its matrices, for tools that read them in blocks (out of core): `data`
// holds everything else (data.matrices is empty); the matrices start at byte matrix_offset
// (matrix_bytes of them, in the stored precision).
struct GlossyFileLayout {
  GlossyTransferData data;
  uint64_t matrix_offset = 0;
  uint64_t matrix_bytes = 0;
};

// Reads PATH and validates all of it as read_glossy_transfer_file does (checksum, finiteness,
// every field), streaming through the matrices a few MiB at a time: it never holds them.
Result<GlossyFileLayout> read_glossy_transfer_layout(const std::string& path);

// The matrices of vertices [first_vertex, first_vertex + count) as floats (binary16 expanded),
// count · channels · order⁴ of them into `out`, read from PATH at the layout's offsets.
Status read_glossy_matrices(const std::string& path, const GlossyFileLayout& layout,
                            uint64_t first_vertex, uint64_t count, float* out);

// Index of M_v,c,i,j in GlossyTransferData::matrices (and in the file's matrix section).
inline std::size_t glossy_matrix_index(std::size_t v, std::size_t c, std::size_t i, std::size_t j,
                                       std::size_t channels, std::size_t k_count) {
  return ((v * channels + c) * k_count + i) * k_count + j;
}

}  // namespace prt
