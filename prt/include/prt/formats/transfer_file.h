// prt/formats/transfer_file.h — reading and writing coefficient (.prt) files.
//
// The byte layout is specified in docs/FORMAT.md: little-endian, magic "PRTC", version 1,
// a 192-byte header, 16-byte-aligned sections, CRC-32C (prt/formats/crc32c.h) over the whole file
// with the checksum field zeroed. Coefficients are stored in the relighting kernel's blocked
// layout (blocks of kVertexBlock = 16 vertices; inside a block channel-major, then
// coefficient-major, then the 16 vertices: index ((block·C + c)·K + k)·16 + lane, zero-padded
// in the last block) as IEEE binary32 or binary16 (prt/core/half.h). In memory (TransferData) they
// are always float and vertex-major; binary16 data is expanded on reading.
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
#include "prt/formats/transfer_data.h"

namespace prt {

inline constexpr uint32_t kTransferFileVersion = 1;
inline constexpr uint32_t kMaxTransferOrder = 64;                // orders 1 .. 64 (4096 coeffs)
inline constexpr uint64_t kMaxTransferVertices = 0xffffffffull;  // 2^32 − 1
inline constexpr std::size_t kVertexBlock = 16;                  // vertices per coefficient block

// Checks that `data` is self-consistent and storable: order in [1, kMaxTransferOrder],
// channels 1 or 3, a known kind and storage, vertex_count <= kMaxTransferVertices, array sizes
// matching vertex_count (ao and bent_normals may be empty), primitive ranges inside the
// vertex range, every number finite, and fingerprint either 0 (unset) or equal to
// geometry_fingerprint(positions). With storage == F16 also that every coefficient fits in
// binary16 (|value| rounds to <= 65504); the error names the vertex, channel, index and value.
Status validate_transfer_data(const TransferData& data, const std::string& name_for_errors);

// Encodes `data` into the bytes of a coefficient file (validating it first). The stored
// fingerprint is always geometry_fingerprint(data.positions).
Result<std::vector<unsigned char>> encode_transfer_file(const TransferData& data,
                                                        const std::string& name_for_errors);

// Writes atomically: PATH.tmp-<pid> is written, flushed and renamed over PATH; on any error
// the temporary is removed and PATH is left as it was.
Status write_transfer_file(const std::string& path, const TransferData& data);

// Reads and fully validates a file (bounds, sizes, checksum, finiteness, fingerprint).
Result<TransferData> read_transfer_file(const std::string& path);
Result<TransferData> read_transfer_data(const void* bytes, std::size_t size,
                                        const std::string& name_for_errors);

// Index of coefficient (v, c, k) in the blocked on-disk/kernel layout.
inline std::size_t blocked_coefficient_index(std::size_t v, std::size_t c, std::size_t k,
                                             std::size_t channels, std::size_t k_count) {
  const std::size_t block = v / kVertexBlock, lane = v % kVertexBlock;
  return ((block * channels + c) * k_count + k) * kVertexBlock + lane;
}

}  // namespace prt
