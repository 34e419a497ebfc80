// Corrupt and hostile coefficient files: every one must give a one-line "NAME: problem" error,
// never a crash, an over-read (the suite runs under ASan) or a giant allocation.
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/diffuse/relighter.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/transfer_file.h"
#include "transfer_fixtures.h"

using prt::Precision;

namespace {

const char* const kName = "corrupt.prt";

std::vector<unsigned char> small_file(Precision storage = Precision::F32) {
  const prt::TransferData d = prt::test::make_transfer_data(5, 2, 3, storage, 4);
  auto bytes = prt::encode_transfer_file(d, kName);
  REQUIRE(bytes.ok());
  return *bytes;
}

void put_u32(std::vector<unsigned char>& b, std::size_t at, uint32_t v) {
  std::memcpy(b.data() + at, &v, 4);
}
void put_u64(std::vector<unsigned char>& b, std::size_t at, uint64_t v) {
  std::memcpy(b.data() + at, &v, 8);
}
uint64_t get_u64(const std::vector<unsigned char>& b, std::size_t at) {
  uint64_t v;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}

// Makes the checksum valid again after a deliberate edit (CRC-32C with the field zeroed).
void fix_checksum(std::vector<unsigned char>& b) {
  put_u32(b, 64, 0);
  put_u32(b, 64, prt::crc32c(b.data(), b.size()));
}

// Reads `b` through both entry points (an exact-size heap copy, so ASan sees any over-read)
// and returns the error message, failing the test if either accepted the bytes.
std::string expect_error(const std::vector<unsigned char>& b) {
  std::vector<unsigned char> exact(b);
  const void* data = exact.empty() ? nullptr : exact.data();
  const auto r = prt::read_transfer_data(data, exact.size(), kName);
  REQUIRE_FALSE(r.ok());
  const std::string message = r.status().message();
  REQUIRE(message.rfind(std::string(kName) + ": ", 0) == 0);
  REQUIRE(message.find('\n') == std::string::npos);
  const auto relighter = prt::Relighter::from_file_bytes(data, exact.size(), kName);
  REQUIRE_FALSE(relighter.ok());
  REQUIRE(relighter.status().message() == message);
  return message;
}

bool contains(const std::string& text, const char* words) {
  return text.find(words) != std::string::npos;
}

}  // namespace

TEST_CASE("the unmodified small file reads", "[corrupt]") {
  const auto b = small_file();
  CHECK(prt::read_transfer_data(b.data(), b.size(), kName).ok());
  CHECK(prt::Relighter::from_file_bytes(b.data(), b.size(), kName).ok());
}

TEST_CASE("a file truncated at any offset is refused", "[corrupt]") {
  for (Precision storage : {Precision::F32, Precision::F16}) {
    const auto b = small_file(storage);
    for (std::size_t n = 0; n < b.size(); ++n) {
      INFO("truncated to " << n << " of " << b.size() << " bytes");
      const std::string message =
          expect_error(std::vector<unsigned char>(b.begin(), b.begin() + n));
      REQUIRE(contains(message, "truncated"));
    }
  }
}

TEST_CASE("trailing bytes are refused", "[corrupt]") {
  auto b = small_file();
  b.push_back(0);
  CHECK(contains(expect_error(b), "unexpected bytes"));
}

TEST_CASE("wrong magic and wrong version are refused", "[corrupt]") {
  auto b = small_file();
  b[0] = 'X';
  CHECK(contains(expect_error(b), "magic"));
  b = small_file();
  put_u32(b, 4, 2);
  fix_checksum(b);
  CHECK(contains(expect_error(b), "version 2"));
}

TEST_CASE("flipping any byte gives a checksum (or earlier) error", "[corrupt]") {
  const auto original = small_file();
  for (std::size_t i = 0; i < original.size(); ++i) {
    for (unsigned mask : {0x01u, 0x80u, 0xffu}) {
      auto b = original;
      b[i] = static_cast<unsigned char>(b[i] ^ mask);
      INFO("byte " << i << " xor " << int(mask));
      expect_error(b);
    }
  }
}

TEST_CASE("inconsistent sizes with a valid checksum are refused", "[corrupt]") {
  const auto original = small_file();
  struct Edit {
    const char* what;
    std::size_t at;
    uint64_t value;
    bool is64;
    const char* words;
  };
  const uint64_t coeff_offset = get_u64(original, 72 + 16 * 3);
  const Edit edits[] = {
      {"vertex count one more", 32, 6, true, "section holds"},
      {"vertex count one less", 32, 4, true, "section holds"},
      {"huge vertex count", 32, 1ull << 40, true, "vertex count"},
      {"largest vertex count", 32, 0xffffffffull, true, "section holds"},
      {"vertex count 2^64-1", 32, ~0ull, true, "vertex count"},
      {"huge primitive count", 40, 1ull << 60, true, "primitive count"},
      {"order 0", 16, 0, false, "order"},
      {"order 65", 16, 65, false, "order"},
      {"order 3 (sizes no longer match)", 16, 3, false, "section holds"},
      {"two channels", 20, 2, false, "channel"},
      {"one channel (sizes no longer match)", 20, 1, false, "section holds"},
      {"storage 2", 24, 2, false, "storage"},
      {"storage f16 (sizes no longer match)", 24, 1, false, "section holds"},
      {"unknown kind", 12, 7, false, "kind"},
      {"unknown flag", 28, 0x100, false, "flags"},
      {"ao flag cleared", 28, 1 | 4, false, "ao section"},
      {"header size", 8, 200, false, "header size"},
      {"reserved field", 68, 1, false, "reserved"},
      {"fingerprint", 48, 12345, true, "fingerprint"},
      {"coefficient offset past the end", 72 + 16 * 3, 1ull << 40, true, "outside"},
      {"coefficient offset wraps around", 72 + 16 * 3, ~0ull - 15, true, "outside"},
      {"misaligned offset", 72 + 16 * 3, coeff_offset + 4, true, "misaligned"},
      {"offset into the header", 72 + 16 * 3, 16, true, "outside"},
      {"overlapping sections", 72 + 16 * 3, get_u64(original, 72 + 16 * 2), true, "overlaps"},
      {"coefficient size huge", 72 + 16 * 3 + 8, ~0ull, true, "section holds"},
      {"primitive table size past the end", 72 + 8, 1ull << 50, true, "outside"},
      {"metadata size past the end", 72 + 16 * 6 + 8, 1ull << 62, true, "outside"},
      {"empty section with an offset", 72 + 16 * 6 + 8, 0, true, "has an offset"},
  };
  for (const Edit& e : edits) {
    auto b = original;
    if (e.is64) {
      put_u64(b, e.at, e.value);
    } else {
      put_u32(b, e.at, static_cast<uint32_t>(e.value));
    }
    fix_checksum(b);
    INFO(e.what);
    const std::string message = expect_error(b);
    INFO(message);
    CHECK(contains(message, e.words));
  }
}

TEST_CASE("bad primitive records and non-finite values with a valid checksum are refused",
          "[corrupt]") {
  const auto original = small_file();
  const uint64_t prim = get_u64(original, 72);
  auto b = original;
  put_u64(b, prim + 32 + 16, 1ull << 40);  // name offset of primitive 1
  fix_checksum(b);
  CHECK(contains(expect_error(b), "name of primitive 1"));
  b = original;
  put_u64(b, prim + 32 + 24, ~0ull);  // name size of primitive 1
  fix_checksum(b);
  CHECK(contains(expect_error(b), "name of primitive 1"));
  b = original;
  put_u64(b, prim + 16, 0);  // a name inside the record table
  fix_checksum(b);
  CHECK(contains(expect_error(b), "name of primitive 0"));
  b = original;
  put_u64(b, prim + 8, 6);  // primitive 0 covers 6 of 5 vertices
  fix_checksum(b);
  CHECK(contains(expect_error(b), "primitive 0"));
  b = original;
  put_u64(b, prim, ~0ull);  // first vertex overflow
  fix_checksum(b);
  CHECK(contains(expect_error(b), "primitive 0"));

  const float nan = std::nanf("");
  for (int s : {1, 2, 3, 4, 5}) {
    b = original;
    std::memcpy(b.data() + get_u64(b, 72 + 16 * s) + 4, &nan, 4);
    fix_checksum(b);
    INFO("section " << s);
    const std::string message = expect_error(b);
    CHECK((contains(message, "not finite") || contains(message, "NaN")));
  }
  auto h = small_file(Precision::F16);
  const uint16_t half_inf = 0x7c00;
  std::memcpy(h.data() + get_u64(h, 72 + 16 * 3) + 6, &half_inf, 2);
  fix_checksum(h);
  CHECK(contains(expect_error(h), "float16"));
}
