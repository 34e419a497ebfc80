// prt/formats/crc32c.h — CRC-32C (Castagnoli), the checksum of coefficient files.
//
// Polynomial 0x1EDC6F41 (reflected 0x82F63B78), initial value and final xor 0xFFFFFFFF,
// as in iSCSI (RFC 3720 §12.1) and the SSE4.2 CRC32 instruction. Check value:
// crc32c("123456789") = 0xE3069283. Uses the SSE4.2 instruction when the CPU has it
// (runtime dispatch), otherwise slice-by-8 tables (Kounavis & Berry 2005); both give the
// same result. Thread-safe. Compiles as C++17.
// References: [21] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <cstdint>

namespace prt {

// Continues a CRC: crc32c(b, crc32c(a)) == crc32c(a ++ b). Start with crc = 0.
uint32_t crc32c(const void* data, std::size_t size, uint32_t crc = 0) noexcept;

// The CRC of a ++ b from crc_a = crc32c(a), crc_b = crc32c(b) and b's length (zlib's
// crc32_combine: crc_a times x^(8·size_b) modulo the polynomial, xor crc_b). Lets a writer
// checksum blocks of a file in any order and join them in file order.
uint32_t crc32c_combine(uint32_t crc_a, uint32_t crc_b, uint64_t size_b) noexcept;

// The portable table-driven implementation alone (for tests and benchmarks).
uint32_t crc32c_portable(const void* data, std::size_t size, uint32_t crc = 0) noexcept;

}  // namespace prt
