// crc32c.cpp — CRC-32C, slice-by-8 and SSE4.2; see prt/formats/crc32c.h.
#include "prt/formats/crc32c.h"

#include <array>
#include <cstring>

#include "core/cpu_features.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {
namespace {

constexpr uint32_t kReflectedPolynomial = 0x82f63b78u;

using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr Tables make_tables() {
  Tables t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int bit = 0; bit < 8; ++bit) c = (c & 1u) ? (c >> 1) ^ kReflectedPolynomial : c >> 1;
    t[0][i] = c;
  }
  for (uint32_t i = 0; i < 256; ++i) {
    for (int s = 1; s < 8; ++s) t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xffu];
  }
  return t;
}

constexpr Tables kTables = make_tables();

uint32_t update_portable(const unsigned char* p, std::size_t n, uint32_t c) {
  while (n >= 8) {
    uint32_t lo, hi;
    std::memcpy(&lo, p, 4);
    std::memcpy(&hi, p + 4, 4);
    lo ^= c;  // little-endian byte order assumed (all supported targets)
    c = kTables[7][lo & 0xffu] ^ kTables[6][(lo >> 8) & 0xffu] ^ kTables[5][(lo >> 16) & 0xffu] ^
        kTables[4][lo >> 24] ^ kTables[3][hi & 0xffu] ^ kTables[2][(hi >> 8) & 0xffu] ^
        kTables[1][(hi >> 16) & 0xffu] ^ kTables[0][hi >> 24];
    p += 8;
    n -= 8;
  }
  while (n--) c = (c >> 8) ^ kTables[0][(c ^ *p++) & 0xffu];
  return c;
}

#if PRT_HAVE_X86_DISPATCH
__attribute__((target("sse4.2"))) uint32_t update_sse42(const unsigned char* p, std::size_t n,
                                                        uint32_t c) {
  uint64_t c64 = c;
  while (n >= 8) {
    uint64_t word;
    std::memcpy(&word, p, 8);
    c64 = _mm_crc32_u64(c64, word);
    p += 8;
    n -= 8;
  }
  auto c32 = static_cast<uint32_t>(c64);
  while (n--) c32 = _mm_crc32_u8(c32, *p++);
  return c32;
}
#endif

// a · b modulo the polynomial, both reflected (bit 31 is x⁰); a ≠ 0.
uint32_t multiply_mod_p(uint32_t a, uint32_t b) {
  uint32_t m = 1u << 31, p = 0;
  for (;;) {
    if (a & m) {
      p ^= b;
      if ((a & (m - 1)) == 0) break;
    }
    m >>= 1;
    b = (b & 1u) ? (b >> 1) ^ kReflectedPolynomial : b >> 1;
  }
  return p;
}

// x^(8·n) modulo the polynomial, by squaring.
uint32_t x_to_8n_mod_p(uint64_t n) {
  uint32_t result = 1u << 31;  // x⁰
  uint32_t power = 1u << 23;   // x⁸
  while (n != 0) {
    if (n & 1u) result = multiply_mod_p(power, result);
    power = multiply_mod_p(power, power);
    n >>= 1;
  }
  return result;
}

}  // namespace

uint32_t crc32c_combine(uint32_t crc_a, uint32_t crc_b, uint64_t size_b) noexcept {
  return multiply_mod_p(x_to_8n_mod_p(size_b), crc_a) ^ crc_b;
}

uint32_t crc32c_portable(const void* data, std::size_t size, uint32_t crc) noexcept {
  return ~update_portable(static_cast<const unsigned char*>(data), size, ~crc);
}

uint32_t crc32c(const void* data, std::size_t size, uint32_t crc) noexcept {
#if PRT_HAVE_X86_DISPATCH
  static const bool has_sse42 = detail::cpu_supports_sse42();
  if (has_sse42) return ~update_sse42(static_cast<const unsigned char*>(data), size, ~crc);
#endif
  return crc32c_portable(data, size, crc);
}

}  // namespace prt
