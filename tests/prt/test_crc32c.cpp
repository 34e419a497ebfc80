// Tests of prt/formats/crc32c.h against the published check value and between implementations.
#include <cstring>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/formats/crc32c.h"

namespace {

// Bit-at-a-time CRC-32C straight from the definition (reflected polynomial 0x82F63B78):
// a third, independent implementation.
uint32_t crc32c_bitwise(const unsigned char* p, std::size_t n) {
  uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int b = 0; b < 8; ++b) c = (c & 1u) ? (c >> 1) ^ 0x82f63b78u : c >> 1;
  }
  return ~c;
}

}  // namespace

TEST_CASE("crc32c gives the published check value", "[crc32c]") {
  const char* text = "123456789";
  CHECK(prt::crc32c(text, 9) == 0xE3069283u);
  CHECK(prt::crc32c_portable(text, 9) == 0xE3069283u);
  CHECK(prt::crc32c(text, 0) == 0u);
  // RFC 3720 B.4: 32 bytes of zeros -> 0x8A9136AA.
  const unsigned char zeros[32] = {};
  CHECK(prt::crc32c(zeros, 32) == 0x8A9136AAu);
}

TEST_CASE("crc32c implementations agree at every length and alignment", "[crc32c]") {
  std::mt19937 rng(11);
  std::vector<unsigned char> data(4096 + 16);
  for (auto& b : data) b = static_cast<unsigned char>(rng());
  for (std::size_t offset = 0; offset < 8; ++offset) {
    for (std::size_t n : {0u, 1u, 7u, 8u, 9u, 15u, 16u, 63u, 64u, 65u, 1000u, 4096u}) {
      const unsigned char* p = data.data() + offset;
      const uint32_t reference = crc32c_bitwise(p, n);
      REQUIRE(prt::crc32c(p, n) == reference);
      REQUIRE(prt::crc32c_portable(p, n) == reference);
      // Continuation: crc(a ++ b) == crc(b, crc(a)).
      const std::size_t split = n / 3;
      REQUIRE(prt::crc32c(p + split, n - split, prt::crc32c(p, split)) == reference);
      REQUIRE(prt::crc32c_portable(p + split, n - split, prt::crc32c_portable(p, split)) ==
              reference);
    }
  }
}

TEST_CASE("crc32c_combine joins the CRCs of two pieces into the CRC of the whole", "[crc32c]") {
  std::mt19937 rng(7);
  std::vector<unsigned char> bytes(5000);
  for (auto& b : bytes) b = static_cast<unsigned char>(rng());
  for (std::size_t split : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(64),
                            std::size_t(2999), std::size_t(5000)}) {
    const uint32_t a = prt::crc32c(bytes.data(), split);
    const uint32_t b = prt::crc32c(bytes.data() + split, bytes.size() - split);
    CHECK(prt::crc32c_combine(a, b, bytes.size() - split) ==
          crc32c_bitwise(bytes.data(), bytes.size()));
  }
}
