// Tests of the Haar kind of the coefficient file (prt/formats/haar_transfer_file.h,
// docs/FORMAT.md): round trips for every quantisation, and corrupt or mismatched files refused with
// one-line "NAME: problem" messages.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/formats/coefficient_file.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/transfer_file.h"
#include "support/test_data.h"

namespace {

namespace fs = std::filesystem;

constexpr int kCube = 8;  // 384 wavelet indices: small, yet every level is present

// A random sparse Haar transfer of `vertices` vertices (about 1 term in 6 kept), with
// geometry and metadata, built through HaarTransferBuilder as the baker does.
prt::HaarTransferFile make_file(int vertices, int channels, prt::HaarQuantization q,
                                unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-2.f, 2.f);
  std::bernoulli_distribution keep(1.0 / 6.0);
  prt::HaarTransferBuilder builder(kCube, channels, q);
  for (int v = 0; v < vertices; ++v) {
    prt::SparseVertexTransfer s;
    for (uint32_t i = 0; i < 6u * kCube * kCube; ++i) {
      if (!keep(rng)) continue;
      s.index.push_back(i);
      for (int c = 0; c < channels; ++c) s.values.push_back(value(rng));
    }
    REQUIRE(builder.add_vertex(s).ok());
  }
  prt::Result<prt::HaarTransfer> t = builder.finish();
  REQUIRE(t.ok());
  prt::HaarTransferFile file;
  file.transfer = std::move(t.value());
  prt::TransferData& info = file.info;
  info.kind = prt::TransferKind::Haar;
  info.order = kCube;
  info.channels = static_cast<uint32_t>(channels);
  info.vertex_count = static_cast<uint64_t>(vertices);
  for (int v = 0; v < vertices; ++v) {
    info.positions.insert(info.positions.end(), {value(rng), value(rng), value(rng)});
    info.normals.insert(info.normals.end(), {0.f, 1.f, 0.f});
  }
  info.primitives.push_back({0, static_cast<uint64_t>(vertices), "mesh/0"});
  info.metadata_json = R"({"basis":"haar"})";
  return file;
}

// Recomputes the header checksum after a deliberate edit (so the payload checks are reached).
void fix_checksum(std::vector<unsigned char>& b) {
  const unsigned char zeros[4] = {0, 0, 0, 0};
  uint32_t crc = prt::crc32c(b.data(), 64);
  crc = prt::crc32c(zeros, 4, crc);
  crc = prt::crc32c(b.data() + 68, b.size() - 68, crc);
  std::memcpy(b.data() + 64, &crc, 4);
}

uint64_t coefficient_section_offset(const std::vector<unsigned char>& b) {
  uint64_t at = 0;
  std::memcpy(&at, b.data() + 72 + 16 * 3, 8);  // section 3: coefficients
  return at;
}

void require_equal(const prt::HaarTransferFile& a, const prt::HaarTransferFile& b) {
  CHECK(b.info.kind == prt::TransferKind::Haar);
  CHECK(b.info.order == a.info.order);
  CHECK(b.info.channels == a.info.channels);
  CHECK(b.info.vertex_count == a.info.vertex_count);
  CHECK(b.info.positions == a.info.positions);
  CHECK(b.info.normals == a.info.normals);
  CHECK(b.info.metadata_json == a.info.metadata_json);
  REQUIRE(b.info.primitives.size() == 1);
  CHECK(b.info.primitives[0].name == "mesh/0");
  const prt::HaarTransfer &x = a.transfer, &y = b.transfer;
  CHECK(y.size == x.size);
  CHECK(y.channels == x.channels);
  CHECK(y.vertex_count == x.vertex_count);
  CHECK(y.quantization == x.quantization);
  CHECK(y.offsets == x.offsets);
  CHECK(y.vertices == x.vertices);
  CHECK(y.values_f32 == x.values_f32);  // bit-exact: the format stores the arrays verbatim
  CHECK(y.values_i16 == x.values_i16);
  CHECK(y.values_i8 == x.values_i8);
  CHECK(y.vertex_step == x.vertex_step);
}

}  // namespace

TEST_CASE("Haar file: round trip is exact for f32, 16-bit and 8-bit, grey and RGB") {
  const prt::HaarQuantization kinds[] = {
      prt::HaarQuantization::Float32, prt::HaarQuantization::Bits16, prt::HaarQuantization::Bits8};
  unsigned seed = 1;
  for (prt::HaarQuantization q : kinds) {
    for (int channels : {1, 3}) {
      // 37 vertices: not a multiple of anything the layout aligns to.
      const prt::HaarTransferFile file = make_file(37, channels, q, seed++);
      REQUIRE(file.transfer.entry_count() > 0);
      const std::string path =
          prt::test::output_path("haar_roundtrip_" + std::to_string(static_cast<int>(q)) + "_" +
                                 std::to_string(channels) + ".prt")
              .string();
      REQUIRE(prt::write_haar_transfer_file(path, file).ok());
      CHECK(prt::is_haar_transfer_file(path));
      prt::Result<prt::HaarTransferFile> back = prt::read_haar_transfer_file(path);
      REQUIRE(back.ok());
      require_equal(file, *back);
    }
  }
}

TEST_CASE("Haar file: SH readers refuse it and the Haar reader refuses SH files") {
  const prt::HaarTransferFile file = make_file(5, 1, prt::HaarQuantization::Bits16, 7);
  prt::Result<std::vector<unsigned char>> bytes = prt::encode_haar_transfer_file(file, "h.prt");
  REQUIRE(bytes.ok());
  prt::Result<prt::TransferData> as_sh =
      prt::read_transfer_data(bytes->data(), bytes->size(), "h.prt");
  REQUIRE_FALSE(as_sh.ok());
  CHECK_THAT(as_sh.status().message(), Catch::StartsWith("h.prt: holds Haar-wavelet transfer"));

  prt::TransferData sh;
  sh.order = 2;
  sh.vertex_count = 1;
  sh.positions = {0, 0, 0};
  sh.normals = {0, 1, 0};
  sh.coefficients = {1, 0, 0, 0};
  prt::Result<std::vector<unsigned char>> sh_bytes = prt::encode_transfer_file(sh, "s.prt");
  REQUIRE(sh_bytes.ok());
  prt::Result<prt::HaarTransferFile> as_haar =
      prt::read_haar_transfer_data(sh_bytes->data(), sh_bytes->size(), "s.prt");
  REQUIRE_FALSE(as_haar.ok());
  CHECK_THAT(as_haar.status().message(), Catch::StartsWith("s.prt: holds SH transfer"));

  // The SH writer will not store a Haar-kind TransferData as SH coefficients.
  sh.kind = prt::TransferKind::Haar;
  CHECK_FALSE(prt::encode_transfer_file(sh, "s.prt").ok());
}

TEST_CASE("Haar file: truncation, bit flips and hostile payloads are refused") {
  const prt::HaarTransferFile file = make_file(9, 3, prt::HaarQuantization::Bits8, 11);
  prt::Result<std::vector<unsigned char>> encoded = prt::encode_haar_transfer_file(file, "c.prt");
  REQUIRE(encoded.ok());
  const std::vector<unsigned char> good = *encoded;
  auto read = [](const std::vector<unsigned char>& b) {
    return prt::read_haar_transfer_data(b.data(), b.size(), "c.prt");
  };
  REQUIRE(read(good).ok());

  SECTION("truncated") {
    std::vector<unsigned char> b(good.begin(), good.end() - 16);
    CHECK_THAT(read(b).status().message(), Catch::Contains("truncated"));
  }
  SECTION("a flipped byte in the payload fails the checksum") {
    std::vector<unsigned char> b = good;
    b[coefficient_section_offset(b) + 40] ^= 0x10;
    CHECK_THAT(read(b).status().message(), Catch::Contains("checksum mismatch"));
  }
  SECTION("cube size that is not a power of two") {
    std::vector<unsigned char> b = good;
    const uint32_t bad = 12;
    std::memcpy(b.data() + 16, &bad, 4);
    fix_checksum(b);
    CHECK_THAT(read(b).status().message(), Catch::Contains("not a power of two"));
  }
  SECTION("unknown quantisation") {
    std::vector<unsigned char> b = good;
    const uint32_t bad = 4;
    std::memcpy(b.data() + 24, &bad, 4);
    fix_checksum(b);
    CHECK_THAT(read(b).status().message(), Catch::Contains("unknown storage"));
  }
  SECTION("an entry count larger than the section") {
    std::vector<unsigned char> b = good;
    const uint64_t huge = uint64_t{1} << 60;
    std::memcpy(b.data() + coefficient_section_offset(b), &huge, 8);
    fix_checksum(b);
    CHECK_THAT(read(b).status().message(), Catch::Contains("does not fit"));
  }
  SECTION("a vertex index beyond the vertex count") {
    std::vector<unsigned char> b = good;
    // The first vertex entry lies right after the offsets table (16-byte aligned).
    const uint64_t offsets_end = 16 + 8 * (6 * kCube * kCube + 1);
    const uint64_t at = coefficient_section_offset(b) + (offsets_end + 15) / 16 * 16;
    const uint32_t bad = 1000;
    std::memcpy(b.data() + at, &bad, 4);
    fix_checksum(b);
    CHECK_THAT(read(b).status().message(), Catch::Contains("out of range or not ascending"));
  }
  SECTION("offsets that decrease") {
    std::vector<unsigned char> b = good;
    const uint64_t at = coefficient_section_offset(b) + 16 + 8 * 5;  // offsets[5]
    const uint64_t bad = uint64_t{1} << 40;
    std::memcpy(b.data() + at, &bad, 8);
    fix_checksum(b);
    CHECK_THAT(read(b).status().message(), Catch::Contains("c.prt: Haar offsets"));
  }
  SECTION("an 8-bit value of -128 (outside the symmetric range)") {
    std::vector<unsigned char> c = good;
    const uint64_t section = coefficient_section_offset(c);
    uint64_t section_size = 0;
    std::memcpy(&section_size, c.data() + 72 + 16 * 3 + 8, 8);
    c[section + section_size - 1] = 0x80;  // the last i8 value
    fix_checksum(c);
    CHECK_THAT(read(c).status().message(), Catch::Contains("outside ±127"));
  }
}

TEST_CASE("Haar file: the writer validates and leaves nothing behind on error") {
  prt::HaarTransferFile file = make_file(4, 1, prt::HaarQuantization::Float32, 3);
  file.info.order = 16;  // disagrees with the transfer's cube size
  const std::string path = prt::test::output_path("haar_invalid.prt").string();
  std::remove(path.c_str());
  const prt::Status s = prt::write_haar_transfer_file(path, file);
  REQUIRE_FALSE(s.ok());
  CHECK_THAT(s.message(), Catch::StartsWith(path + ": info"));
  CHECK_FALSE(std::filesystem::exists(path));
  file.info.order = kCube;
  file.transfer.values_f32[0] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THAT(prt::write_haar_transfer_file(path, file).message(), Catch::Contains("Inf or NaN"));
  CHECK_FALSE(std::filesystem::exists(path));
}

TEST_CASE("one reader opens every kind: read_coefficient_file gives SH and Haar files whole") {
  const fs::path dir = prt::test::output_path("coefficient_file");
  fs::create_directories(dir);
  const prt::HaarTransferFile haar = make_file(7, 3, prt::HaarQuantization::Bits8, 11);
  const std::string haar_path = (dir / "h.prt").string();
  REQUIRE(prt::write_haar_transfer_file(haar_path, haar).ok());
  prt::Result<prt::CoefficientFile> h = prt::read_coefficient_file(haar_path);
  REQUIRE(h.ok());
  REQUIRE(h->haar.has_value());
  CHECK(h->data.kind == prt::TransferKind::Haar);
  CHECK(h->data.order == static_cast<uint32_t>(kCube));
  CHECK(h->data.positions == haar.info.positions);
  CHECK(h->data.metadata_json == haar.info.metadata_json);
  CHECK(h->haar->offsets == haar.transfer.offsets);
  CHECK(h->haar->vertices == haar.transfer.vertices);
  CHECK(h->haar->values_i8 == haar.transfer.values_i8);
  CHECK(h->haar->vertex_step == haar.transfer.vertex_step);

  prt::TransferData sh;
  sh.order = 2;
  sh.vertex_count = 1;
  sh.positions = {0, 0, 0};
  sh.normals = {0, 1, 0};
  sh.coefficients = {1, 0.5f, 0, -0.25f};
  const std::string sh_path = (dir / "s.prt").string();
  REQUIRE(prt::write_transfer_file(sh_path, sh).ok());
  prt::Result<prt::CoefficientFile> s = prt::read_coefficient_file(sh_path);
  REQUIRE(s.ok());
  CHECK_FALSE(s->haar.has_value());
  CHECK(s->data.coefficients == sh.coefficients);

  // Errors are those of the kind's own reader: one line naming the file.
  prt::Result<prt::CoefficientFile> missing = prt::read_coefficient_file((dir / "no.prt").string());
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.status().message() ==
        prt::read_transfer_file((dir / "no.prt").string()).status().message());
}
