// Tests of prt/formats/transfer_file.h: round trips, the documented byte layout, validation,
// atomicity.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/core/half.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/transfer_file.h"
#include "support/test_data.h"
#include "transfer_fixtures.h"

namespace fs = std::filesystem;
using prt::Precision;
using prt::TransferData;

namespace {

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

uint32_t u32_at(const std::vector<unsigned char>& b, std::size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
uint64_t u64_at(const std::vector<unsigned char>& b, std::size_t at) {
  uint64_t v;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}

void require_same_metadata(const TransferData& a, const TransferData& b) {
  REQUIRE(a.kind == b.kind);
  REQUIRE(a.order == b.order);
  REQUIRE(a.channels == b.channels);
  REQUIRE(a.storage == b.storage);
  REQUIRE(a.albedo_folded == b.albedo_folded);
  REQUIRE(a.vertex_count == b.vertex_count);
  REQUIRE(a.fingerprint == b.fingerprint);
  REQUIRE(a.primitives.size() == b.primitives.size());
  for (std::size_t i = 0; i < a.primitives.size(); ++i) {
    REQUIRE(a.primitives[i].first_vertex == b.primitives[i].first_vertex);
    REQUIRE(a.primitives[i].vertex_count == b.primitives[i].vertex_count);
    REQUIRE(a.primitives[i].name == b.primitives[i].name);
  }
  REQUIRE(a.positions == b.positions);
  REQUIRE(a.normals == b.normals);
  REQUIRE(a.ao == b.ao);
  REQUIRE(a.bent_normals == b.bent_normals);
  REQUIRE(a.metadata_json == b.metadata_json);
}

// No PATH.tmp-* file is left beside `path`.
bool no_temporaries_beside(const fs::path& path) {
  for (const auto& entry : fs::directory_iterator(path.parent_path())) {
    if (entry.path().filename().string().rfind(path.filename().string() + ".tmp-", 0) == 0) {
      return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("coefficient files round-trip every section", "[transfer_file]") {
  for (Precision storage : {Precision::F32, Precision::F16}) {
    for (uint32_t channels : {1u, 3u}) {
      for (uint64_t vertices : {0ull, 1ull, 16ull, 37ull}) {
        for (bool optional : {true, false}) {
          const TransferData d = prt::test::make_transfer_data(
              vertices, 3, channels, storage, static_cast<uint32_t>(vertices + channels), optional);
          const fs::path path = prt::test::output_path("round_trip.prt");
          INFO("storage " << static_cast<int>(storage) << " channels " << channels << " vertices "
                          << vertices << " optional " << optional);
          const prt::Status written = prt::write_transfer_file(path.string(), d);
          REQUIRE(written.ok());
          REQUIRE(no_temporaries_beside(path));
          const prt::Result<TransferData> back = prt::read_transfer_file(path.string());
          INFO(back.status().message());
          REQUIRE(back.ok());
          require_same_metadata(d, *back);
          REQUIRE(back->coefficients.size() == d.coefficients.size());
          for (std::size_t i = 0; i < d.coefficients.size(); ++i) {
            const float want = d.coefficients[i], got = back->coefficients[i];
            if (storage == Precision::F32) {
              REQUIRE(got == want);
            } else {
              // binary16 keeps 11 significant bits: relative error <= 2^-11 for normal halves;
              // below 2^-14 the absolute error is at most half a subnormal step, 2^-25.
              REQUIRE(std::abs(got - want) <= std::max(0x1p-11f * std::abs(want), 0x1p-25f));
            }
          }
          // The memory reader gives the same as the path reader.
          const std::vector<unsigned char> bytes = read_bytes(path);
          const prt::Result<TransferData> from_memory =
              prt::read_transfer_data(bytes.data(), bytes.size(), "memory");
          REQUIRE(from_memory.ok());
          require_same_metadata(*back, *from_memory);
          REQUIRE(from_memory->coefficients == back->coefficients);
        }
      }
    }
  }
}

TEST_CASE("the byte layout is the one docs/FORMAT.md describes", "[transfer_file]") {
  const uint32_t order = 2, channels = 3;
  const uint64_t vertices = 21;  // two blocks, the second padded
  for (Precision storage : {Precision::F32, Precision::F16}) {
    const TransferData d = prt::test::make_transfer_data(vertices, order, channels, storage, 5);
    const prt::Result<std::vector<unsigned char>> encoded = prt::encode_transfer_file(d, "mem");
    REQUIRE(encoded.ok());
    const std::vector<unsigned char>& b = *encoded;
    REQUIRE(std::memcmp(b.data(), "PRTC", 4) == 0);
    CHECK(u32_at(b, 4) == 1);    // version
    CHECK(u32_at(b, 8) == 192);  // header size
    CHECK(u32_at(b, 12) == 2);   // Interreflected
    CHECK(u32_at(b, 16) == order);
    CHECK(u32_at(b, 20) == channels);
    CHECK(u32_at(b, 24) == static_cast<uint32_t>(storage));
    CHECK(u32_at(b, 28) == ((d.albedo_folded ? 1u : 0u) | 2u | 4u));
    CHECK(u64_at(b, 32) == vertices);
    CHECK(u64_at(b, 40) == 3);  // primitives
    CHECK(u64_at(b, 48) == d.fingerprint);
    CHECK(u64_at(b, 56) == b.size());
    // Checksum: CRC-32C of the file with the field zeroed.
    std::vector<unsigned char> zeroed = b;
    std::memset(zeroed.data() + 64, 0, 4);
    CHECK(u32_at(b, 64) == prt::crc32c(zeroed.data(), zeroed.size()));
    // Sections: 16-byte aligned, in bounds, with the documented sizes.
    const uint64_t expected_sizes[] = {
        0 /*primitives: checked below*/,
        12 * vertices,
        12 * vertices,
        2 * channels * order * order * 16 * (storage == Precision::F16 ? 2 : 4),
        4 * vertices,
        12 * vertices,
        d.metadata_json.size()};
    for (int s = 0; s < 7; ++s) {
      const uint64_t off = u64_at(b, 72 + 16 * s), size = u64_at(b, 72 + 16 * s + 8);
      INFO("section " << s);
      CHECK(off % 16 == 0);
      CHECK(off + size <= b.size());
      if (s != 0) CHECK(size == expected_sizes[s]);
    }
    // Positions are plain little-endian floats.
    const uint64_t positions_at = u64_at(b, 72 + 16 * 1);
    float p[3];
    std::memcpy(p, b.data() + positions_at + 12 * 20, 12);
    CHECK(p[0] == d.positions[60]);
    CHECK(p[2] == d.positions[62]);
    // Primitive record 1: first, count, name offset, name size; the name follows the table.
    const uint64_t prim_at = u64_at(b, 72);
    CHECK(u64_at(b, prim_at + 32) == d.primitives[1].first_vertex);
    CHECK(u64_at(b, prim_at + 40) == d.primitives[1].vertex_count);
    const uint64_t name_at = u64_at(b, prim_at + 48), name_size = u64_at(b, prim_at + 56);
    CHECK(std::string(reinterpret_cast<const char*>(b.data() + prim_at + name_at), name_size) ==
          d.primitives[1].name);
    // Coefficient (v, c, k) sits at ((block·C + c)·K + k)·16 + lane; padding is zero.
    const uint64_t coeff_at = u64_at(b, 72 + 16 * 3);
    const std::size_t k_count = order * order;
    for (std::size_t v = 0; v < 32; ++v) {
      for (std::size_t c = 0; c < channels; ++c) {
        for (std::size_t k = 0; k < k_count; ++k) {
          const std::size_t index = ((v / 16 * channels + c) * k_count + k) * 16 + v % 16;
          float stored;
          if (storage == Precision::F16) {
            uint16_t h;
            std::memcpy(&h, b.data() + coeff_at + 2 * index, 2);
            stored = prt::half_to_float(h);
          } else {
            std::memcpy(&stored, b.data() + coeff_at + 4 * index, 4);
          }
          const float want = v < vertices ? d.coefficients[(v * channels + c) * k_count + k] : 0.0f;
          const float expected =
              storage == Precision::F16 ? prt::half_to_float(prt::float_to_half(want)) : want;
          REQUIRE(stored == expected);
        }
      }
    }
    // Metadata JSON is stored verbatim.
    const uint64_t meta_at = u64_at(b, 72 + 16 * 6);
    CHECK(std::string(reinterpret_cast<const char*>(b.data() + meta_at), d.metadata_json.size()) ==
          d.metadata_json);
  }
}

TEST_CASE("float16 overflow is refused on write, naming the value", "[transfer_file]") {
  TransferData d = prt::test::make_transfer_data(20, 2, 3, Precision::F16, 9);
  d.coefficients[(17 * 3 + 2) * 4 + 1] = 70000.0f;  // vertex 17, channel 2, index 1
  const fs::path path = prt::test::output_path("overflow.prt");
  fs::remove(path);
  const prt::Status s = prt::write_transfer_file(path.string(), d);
  REQUIRE_FALSE(s.ok());
  INFO(s.message());
  CHECK(s.message().rfind(path.string() + ": ", 0) == 0);
  CHECK(s.message().find("70000") != std::string::npos);
  CHECK(s.message().find("vertex 17") != std::string::npos);
  CHECK(s.message().find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(path));
  CHECK(no_temporaries_beside(path));
  // The same data is fine as F32, and 65519 (which rounds to 65504) is fine as F16.
  d.storage = Precision::F32;
  CHECK(prt::write_transfer_file(path.string(), d).ok());
  d.storage = Precision::F16;
  d.coefficients[(17 * 3 + 2) * 4 + 1] = -65519.0f;
  CHECK(prt::write_transfer_file(path.string(), d).ok());
  const auto back = prt::read_transfer_file(path.string());
  REQUIRE(back.ok());
  CHECK(back->coefficients[(17 * 3 + 2) * 4 + 1] == -65504.0f);
}

TEST_CASE("invalid transfer data is refused and leaves the old file in place", "[transfer_file]") {
  const fs::path path = prt::test::output_path("keep.prt");
  const TransferData good = prt::test::make_transfer_data(10, 2, 1, Precision::F32, 3);
  REQUIRE(prt::write_transfer_file(path.string(), good).ok());
  const std::vector<unsigned char> before = read_bytes(path);

  auto expect_refused = [&](TransferData bad, const char* words) {
    const prt::Status s = prt::write_transfer_file(path.string(), bad);
    INFO("expected an error mentioning '" << words << "', got: " << s.message());
    REQUIRE_FALSE(s.ok());
    CHECK(s.message().find(words) != std::string::npos);
    CHECK(s.message().rfind(path.string() + ": ", 0) == 0);
    CHECK(read_bytes(path) == before);
    CHECK(no_temporaries_beside(path));
  };
  TransferData bad = good;
  bad.order = 0;
  expect_refused(bad, "order");
  bad = good;
  bad.order = 65;
  expect_refused(bad, "order");
  bad = good;
  bad.channels = 2;
  expect_refused(bad, "channel");
  bad = good;
  bad.coefficients.pop_back();
  expect_refused(bad, "coefficients");
  bad = good;
  bad.positions.pop_back();
  expect_refused(bad, "positions");
  bad = good;
  bad.ao.resize(3);
  expect_refused(bad, "ao");
  bad = good;
  bad.coefficients[5] = std::nanf("");
  expect_refused(bad, "not finite");
  bad = good;
  bad.normals[4] = INFINITY;
  expect_refused(bad, "not finite");
  bad = good;
  bad.primitives.push_back({8, 3, "too long"});
  expect_refused(bad, "primitive");
  bad = good;
  bad.fingerprint ^= 1;
  expect_refused(bad, "fingerprint");
  bad = good;
  bad.kind = static_cast<prt::TransferKind>(9);
  expect_refused(bad, "kind");

  // A directory that does not exist: a one-line error naming the path, nothing created.
  const std::string missing = prt::test::output_path("no/such/dir/x.prt").string();
  const prt::Status s = prt::write_transfer_file(missing, good);
  REQUIRE_FALSE(s.ok());
  CHECK(s.message().rfind(missing + ": ", 0) == 0);
  // Reading a missing file.
  const auto r = prt::read_transfer_file(missing);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status().message().rfind(missing + ": ", 0) == 0);
  // Reading a folder: said so (it once reported "out of memory while reading 2^63 bytes").
  const std::string folder = PRT_SOURCE_DIR;  // exists in every build
  const auto f = prt::read_transfer_file(folder);
  REQUIRE_FALSE(f.ok());
  CHECK(f.status().message() == folder + ": is a directory, not a file");
}

TEST_CASE("a zero fingerprint is filled in by the writer", "[transfer_file]") {
  TransferData d = prt::test::make_transfer_data(7, 1, 1, Precision::F32, 2);
  const uint64_t expected = d.fingerprint;
  d.fingerprint = 0;
  const auto bytes = prt::encode_transfer_file(d, "mem");
  REQUIRE(bytes.ok());
  const auto back = prt::read_transfer_data(bytes->data(), bytes->size(), "mem");
  REQUIRE(back.ok());
  CHECK(back->fingerprint == expected);
}
