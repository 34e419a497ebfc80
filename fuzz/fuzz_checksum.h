// fuzz/fuzz_checksum.h — resealing a fuzz input's CRC-32C, so that mutated files reach the checks
// behind a reader's checksum. Every checksummed file of prt (coefficient .prt and Haar, glossy
// .prtg, CPCA .prtq, emitter responses .prte, the form-factor cache) stores the CRC-32C
// (prt/formats/crc32c.h) of the whole file, its 4-byte checksum field taken as zero, at a fixed
// offset (docs/FORMAT.md). A target runs its reader on the input as it is (the checksum check
// itself) and on a resealed copy (everything behind it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "prt/formats/crc32c.h"

namespace prt::fuzz {

// A copy of `bytes` whose checksum field at `offset` holds the CRC-32C of the copy with that
// field zeroed (little-endian). Inputs too short to hold the field are copied unchanged.
inline std::vector<unsigned char> resealed(const uint8_t* bytes, std::size_t size,
                                           std::size_t offset) {
  std::vector<unsigned char> out(bytes, bytes + size);
  if (size < offset + 4) return out;
  std::memset(out.data() + offset, 0, 4);
  const uint32_t crc = prt::crc32c(out.data(), out.size());
  for (int i = 0; i < 4; ++i) out[offset + i] = static_cast<unsigned char>(crc >> (8 * i));
  return out;
}

// The body of a checksummed reader's target: `check(bytes, size)` on the input as it is (the
// checksum check itself) and on its resealed copy (everything behind the checksum).
template <class Check>
inline void check_as_given_and_resealed(const uint8_t* bytes, std::size_t size, std::size_t offset,
                                        Check check) {
  check(bytes, size);
  const std::vector<unsigned char> sealed = resealed(bytes, size, offset);
  check(sealed.data(), sealed.size());
}

}  // namespace prt::fuzz
