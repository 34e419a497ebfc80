// Tests of prt/formats/glossy_transfer_file.h: round trips f32/f16, the documented header, refusal
// of truncated, corrupted and inconsistent files, atomic writes.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/core/half.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/formats/glossy_transfer_writer.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using prt::GlossyTransferData;
using prt::Precision;

namespace {

GlossyTransferData make_glossy(uint64_t vertex_count, uint32_t order, uint32_t channels,
                               Precision storage, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  GlossyTransferData d;
  d.order = order;
  d.channels = channels;
  d.storage = storage;
  d.interreflected = seed % 2 == 1;
  d.vertex_count = vertex_count;
  const std::size_t v = static_cast<std::size_t>(vertex_count);
  for (std::size_t i = 0; i < v; ++i) {
    for (int c = 0; c < 3; ++c) d.positions.push_back(5.0f * unit(rng));
    d.normals.insert(d.normals.end(), {0.0f, 0.0f, 1.0f});
    d.tangents.insert(d.tangents.end(), {1.0f, 0.0f, 0.0f, i % 2 ? -1.0f : 1.0f});
    d.material_of_vertex.push_back(static_cast<uint32_t>(i % 3));
  }
  prt::brdf::Material lambert;
  prt::brdf::Material ward;
  ward.model = prt::brdf::MaterialModel::kWard;
  ward.diffuse = {0.1, 0.2, 0.3};
  ward.specular = prt::brdf::grey(0.25);
  ward.alpha_x = 0.1;
  ward.alpha_y = 0.3;
  prt::brdf::Material merl;
  merl.model = prt::brdf::MaterialModel::kMerl;
  merl.merl_path = "brdfs/gold-metallic-paint.binary";
  d.materials = {lambert, ward, merl};
  d.matrices.resize(v * channels * d.matrix_floats());
  for (float& x : d.matrices) x = unit(rng);
  d.primitives = {{0, v / 2, "floor"}, {v / 2, v - v / 2, "teapot \xc3\xa9"}};
  d.metadata_json = R"({"samples": 256})";
  return d;
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& path, const std::vector<unsigned char>& b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// Recomputes the checksum (bytes 72..75) so a test can reach the checks after it.
void fix_checksum(std::vector<unsigned char>& b) {
  std::memset(b.data() + 72, 0, 4);
  const uint32_t crc = prt::crc32c(b.data(), b.size());
  std::memcpy(b.data() + 72, &crc, 4);
}

bool same_material(const prt::brdf::Material& a, const prt::brdf::Material& b) {
  return a.model == b.model && a.diffuse.r == b.diffuse.r && a.diffuse.g == b.diffuse.g &&
         a.diffuse.b == b.diffuse.b && a.specular.r == b.specular.r && a.exponent == b.exponent &&
         a.alpha_x == b.alpha_x && a.alpha_y == b.alpha_y && a.ward_form == b.ward_form &&
         a.distribution == b.distribution && a.fresnel == b.fresnel && a.eta == b.eta &&
         a.merl_path == b.merl_path;
}

}  // namespace

TEST_CASE("glossy file: round trip f32 is exact, f16 within half rounding", "[glossy_file]") {
  for (const Precision storage : {Precision::F32, Precision::F16}) {
    for (const uint32_t order : {1u, 3u, 5u}) {
      const GlossyTransferData d = make_glossy(37, order, order == 3 ? 3 : 1, storage);
      const fs::path path = prt::test::output_path("glossy_round_trip.prtg");
      REQUIRE(prt::write_glossy_transfer_file(path.string(), d).ok());
      const auto back = prt::read_glossy_transfer_file(path.string());
      INFO(back.status().message());
      REQUIRE(back.ok());
      const GlossyTransferData& r = back.value();
      CHECK(r.order == d.order);
      CHECK(r.channels == d.channels);
      CHECK(r.storage == storage);
      CHECK(r.interreflected == d.interreflected);
      CHECK(r.positions == d.positions);
      CHECK(r.normals == d.normals);
      CHECK(r.tangents == d.tangents);
      CHECK(r.material_of_vertex == d.material_of_vertex);
      CHECK(r.metadata_json == d.metadata_json);
      REQUIRE(r.primitives.size() == 2);
      CHECK(r.primitives[1].name == d.primitives[1].name);
      CHECK(r.primitives[1].first_vertex == d.primitives[1].first_vertex);
      REQUIRE(r.materials.size() == 3);
      for (std::size_t m = 0; m < 3; ++m) CHECK(same_material(r.materials[m], d.materials[m]));
      REQUIRE(r.matrices.size() == d.matrices.size());
      for (std::size_t i = 0; i < d.matrices.size(); ++i) {
        // f16: round to nearest, relative error ≤ 2^-11 for normals, absolute ≤ 2^-25 below.
        const float want = storage == Precision::F32
                               ? d.matrices[i]
                               : prt::half_to_float(prt::float_to_half(d.matrices[i]));
        if (r.matrices[i] != want) FAIL("matrix entry " << i << " differs");
        if (storage == Precision::F16) {
          REQUIRE(std::fabs(r.matrices[i] - d.matrices[i]) <=
                  std::fabs(d.matrices[i]) * 0x1p-11f + 0x1p-25f);
        }
      }
    }
  }
}

TEST_CASE("glossy file: header fields at the documented offsets", "[glossy_file]") {
  const GlossyTransferData d = make_glossy(20, 4, 3, Precision::F16, 8);
  auto bytes = prt::encode_glossy_transfer_file(d, "mem");
  REQUIRE(bytes.ok());
  const auto& b = bytes.value();
  auto u32 = [&](std::size_t at) {
    uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  auto u64 = [&](std::size_t at) {
    uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
  };
  CHECK(std::memcmp(b.data(), "PRTG", 4) == 0);
  CHECK(u32(4) == 1);
  CHECK(u32(8) == 208);
  CHECK(u32(12) == 4);
  CHECK(u32(16) == 3);
  CHECK(u32(20) == 1);
  CHECK(u32(24) == 0);  // seed 8: not interreflected
  CHECK(u64(32) == 20);
  CHECK(u64(40) == 2);
  CHECK(u64(48) == 3);
  CHECK(u64(64) == b.size());
  // Matrices: section 6, V · C · K² · 2 bytes; the first entry in f16.
  CHECK(u64(80 + 16 * 6 + 8) == 20u * 3 * 256 * 2);
  uint16_t first;
  std::memcpy(&first, b.data() + u64(80 + 16 * 6), 2);
  CHECK(first == prt::float_to_half(d.matrices[0]));
  // Materials: section 4; record 1 is the Ward material, alpha_x at byte 72 of the record.
  const std::size_t mats = u64(80 + 16 * 4);
  CHECK(u32(mats + 128) == 2);
  double alpha_x;
  std::memcpy(&alpha_x, b.data() + mats + 128 + 72, 8);
  CHECK(alpha_x == 0.1);
  CHECK(prt::is_glossy_transfer_file(b.data(), b.size()));
}

TEST_CASE("glossy file: truncated, corrupted and inconsistent files are refused", "[glossy_file]") {
  const GlossyTransferData d = make_glossy(33, 3, 1, Precision::F32);
  const auto good = prt::encode_glossy_transfer_file(d, "mem").value();
  REQUIRE(prt::read_glossy_transfer_data(good.data(), good.size(), "mem").ok());
  auto refused = [](const std::vector<unsigned char>& b, const std::string& needle) {
    const auto r = prt::read_glossy_transfer_data(b.data(), b.size(), "bad.prtg");
    REQUIRE_FALSE(r.ok());
    const std::string m = r.status().message();
    INFO(m);
    CHECK(m.rfind("bad.prtg: ", 0) == 0);
    CHECK(m.find('\n') == std::string::npos);
    CHECK(m.find(needle) != std::string::npos);
  };
  // Every truncation is refused.
  for (std::size_t cut :
       {std::size_t{0}, std::size_t{3}, std::size_t{100}, good.size() / 2, good.size() - 1}) {
    refused(std::vector<unsigned char>(good.begin(), good.begin() + cut), "truncated");
  }
  // Any flipped byte past the header is caught by the checksum.
  for (std::size_t at : {std::size_t{300}, good.size() / 2, good.size() - 20}) {
    auto b = good;
    b[at] ^= 0x10;
    refused(b, "checksum mismatch");
  }
  {
    auto b = good;
    b.push_back(0);
    refused(b, "unexpected bytes");
  }
  {
    auto b = good;
    b[0] = 'X';
    refused(b, "bad magic");
  }
  {
    auto b = good;
    std::memcpy(b.data(), "PRTC", 4);
    refused(b, "coefficient file");
  }
  {  // A material index out of range, checksum recomputed.
    auto b = good;
    uint64_t at;
    std::memcpy(&at, b.data() + 80 + 16 * 5, 8);
    const uint32_t bad = 9;
    std::memcpy(b.data() + at, &bad, 4);
    fix_checksum(b);
    refused(b, "has material 9 of 3");
  }
  {  // A NaN matrix entry.
    auto b = good;
    uint64_t at;
    std::memcpy(&at, b.data() + 80 + 16 * 6, 8);
    const float nan = std::nanf("");
    std::memcpy(b.data() + at + 4 * 10, &nan, 4);
    fix_checksum(b);
    refused(b, "not finite");
  }
  {  // An order beyond 10.
    auto b = good;
    const uint32_t order = 11;
    std::memcpy(b.data() + 12, &order, 4);
    fix_checksum(b);
    refused(b, "SH order 11");
  }
  {  // A moved position: the fingerprint no longer matches.
    auto b = good;
    uint64_t at;
    std::memcpy(&at, b.data() + 80 + 16 * 1, 8);
    b[at] ^= 1;
    fix_checksum(b);
    refused(b, "fingerprint");
  }
}

TEST_CASE("glossy file: invalid data is refused and an existing file is kept", "[glossy_file]") {
  const fs::path path = prt::test::output_path("glossy_keep.prtg");
  const GlossyTransferData good = make_glossy(8, 2, 1, Precision::F32);
  REQUIRE(prt::write_glossy_transfer_file(path.string(), good).ok());
  const auto before = read_bytes(path);
  GlossyTransferData d = good;
  d.storage = Precision::F16;
  d.matrices[5 * 16 + 2] = 1e6f;  // vertex 5, row 0, column 2 at order 2 (K = 4, K² = 16)
  const prt::Status s = prt::write_glossy_transfer_file(path.string(), d);
  REQUIRE_FALSE(s.ok());
  CHECK(s.message().find("vertex 5, channel 0, row 0, column 2") != std::string::npos);
  CHECK(read_bytes(path) == before);
  d = good;
  d.tangents[4 * 3 + 3] = 0.5f;
  CHECK_FALSE(prt::validate_glossy_transfer_data(d, "x").ok());
  d = good;
  d.materials.clear();
  CHECK_FALSE(prt::validate_glossy_transfer_data(d, "x").ok());
  d = good;
  d.matrices.pop_back();
  CHECK_FALSE(prt::validate_glossy_transfer_data(d, "x").ok());
  // A coefficient-file reader's data is no glossy file.
  write_bytes(path, std::vector<unsigned char>{'P', 'R', 'T', 'C', 1, 0, 0, 0});
  const auto r = prt::read_glossy_transfer_file(path.string());
  REQUIRE_FALSE(r.ok());
  CHECK(r.status().message().find("PRTC") != std::string::npos);
}

// Material record offset 112 holds the glTF model's metallic (docs/FORMAT.md): it round-trips,
// and a record of another model with a non-zero metallic is refused in one line.
TEST_CASE("glossy file: a glTF material keeps its metallic", "[glossy_file]") {
  GlossyTransferData d = make_glossy(6, 2, 3, Precision::F32);
  prt::brdf::Material gltf;
  gltf.model = prt::brdf::MaterialModel::kGltf;
  gltf.diffuse = {0.2, 0.4, 0.8};
  gltf.specular = prt::brdf::grey(0.04);
  gltf.metallic = 0.3;
  gltf.alpha_x = gltf.alpha_y = 0.16;
  d.materials[1] = gltf;
  const auto bytes = prt::encode_glossy_transfer_file(d, "g");
  REQUIRE(bytes.ok());
  const auto back = prt::read_glossy_transfer_data(bytes.value().data(), bytes.value().size(), "g");
  INFO((back.ok() ? std::string() : back.status().message()));
  REQUIRE(back.ok());
  CHECK(back.value().materials[1].model == prt::brdf::MaterialModel::kGltf);
  CHECK(back.value().materials[1].metallic == 0.3);
  CHECK(back.value().materials[1].diffuse.b == 0.8);
  d.materials[1].model = prt::brdf::MaterialModel::kMicrofacet;
  const auto refused = prt::encode_glossy_transfer_file(d, "g");
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.status().message().find("metallic") != std::string::npos);
}

namespace {

// Everything of `d` but its matrices and metadata: what a streaming writer is created with.
GlossyTransferData skeleton_of(const GlossyTransferData& d) {
  GlossyTransferData s = d;
  s.matrices.clear();
  s.metadata_json.clear();
  return s;
}

bool no_temporaries(const fs::path& path) {
  for (const auto& e : fs::directory_iterator(path.parent_path()))
    if (e.path().filename().string().rfind(path.filename().string() + ".tmp-", 0) == 0)
      return false;
  return true;
}

}  // namespace

TEST_CASE("glossy file: streamed blocks in any order give the in-memory writer's bytes",
          "[glossy_file]") {
  for (const Precision storage : {Precision::F32, Precision::F16}) {
    for (const uint32_t order : {1u, 5u}) {
      const uint32_t channels = order == 5 ? 3 : 1;
      const GlossyTransferData d = make_glossy(101, order, channels, storage);
      const fs::path whole = prt::test::output_path("glossy_whole.prtg");
      const fs::path streamed = prt::test::output_path("glossy_streamed.prtg");
      REQUIRE(prt::write_glossy_transfer_file(whole.string(), d).ok());
      auto w = prt::GlossyTransferFileWriter::create(streamed.string(), skeleton_of(d));
      INFO(w.status().message());
      REQUIRE(w.ok());
      // Uneven blocks, last first: the file order is rebuilt from the offsets.
      const std::size_t per = channels * d.matrix_floats();
      const uint64_t cuts[] = {0, 1, 17, 64, 100, 101};
      for (int b = 4; b >= 0; --b) {
        const prt::Status s =
            (*w)->write(cuts[b], cuts[b + 1] - cuts[b], &d.matrices[cuts[b] * per]);
        REQUIRE(s.ok());
      }
      REQUIRE((*w)->finish(d.metadata_json).ok());
      CHECK(read_bytes(streamed) == read_bytes(whole));
      CHECK(no_temporaries(streamed));
      // The layout reader streams through the matrices and gives everything else.
      auto layout = prt::read_glossy_transfer_layout(streamed.string());
      INFO(layout.status().message());
      REQUIRE(layout.ok());
      CHECK(layout->data.matrices.empty());
      CHECK(layout->data.positions == d.positions);
      CHECK(layout->data.metadata_json == d.metadata_json);
      CHECK(layout->data.material_of_vertex == d.material_of_vertex);
      const auto full = prt::read_glossy_transfer_file(whole.string());
      REQUIRE(full.ok());
      std::vector<float> part(40 * per);
      REQUIRE(prt::read_glossy_matrices(streamed.string(), *layout, 30, 40, part.data()).ok());
      CHECK(std::equal(part.begin(), part.end(), full->matrices.begin() + 30 * per));
    }
  }
}

TEST_CASE("glossy file: a stream with a missing block or a bad entry leaves no file",
          "[glossy_file]") {
  const GlossyTransferData d = make_glossy(50, 3, 1, Precision::F16);
  const std::size_t per = d.matrix_floats();
  const fs::path path = prt::test::output_path("glossy_stream_refused.prtg");
  fs::remove(path);
  {
    auto w = prt::GlossyTransferFileWriter::create(path.string(), skeleton_of(d));
    REQUIRE(w.ok());
    REQUIRE((*w)->write(0, 20, d.matrices.data()).ok());
    REQUIRE((*w)->write(30, 20, &d.matrices[30 * per]).ok());
    const prt::Status s = (*w)->finish("");
    REQUIRE_FALSE(s.ok());
    CHECK(s.message().find("vertex 20 were not written") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(path));
  CHECK(no_temporaries(path));
  {
    std::vector<float> bad(d.matrices.begin(), d.matrices.begin() + 10 * per);
    bad[3 * per + 4] = 1e6f;  // beyond binary16
    auto w = prt::GlossyTransferFileWriter::create(path.string(), skeleton_of(d));
    REQUIRE(w.ok());
    const prt::Status s = (*w)->write(0, 10, bad.data());
    REQUIRE_FALSE(s.ok());
    CHECK(s.message().find("vertex 3, channel 0, row 0, column 4") != std::string::npos);
  }  // abandoned without finish()
  CHECK_FALSE(fs::exists(path));
  CHECK(no_temporaries(path));
}

TEST_CASE("glossy file: the streaming reader refuses a corrupted matrix byte", "[glossy_file]") {
  const GlossyTransferData d = make_glossy(40, 5, 1, Precision::F32);
  const fs::path path = prt::test::output_path("glossy_layout_corrupt.prtg");
  REQUIRE(prt::write_glossy_transfer_file(path.string(), d).ok());
  auto bytes = read_bytes(path);
  auto layout = prt::read_glossy_transfer_layout(path.string());
  REQUIRE(layout.ok());
  bytes[static_cast<std::size_t>(layout->matrix_offset + 1000)] ^= 0x10;
  write_bytes(path, bytes);
  const auto again = prt::read_glossy_transfer_layout(path.string());
  REQUIRE_FALSE(again.ok());
  CHECK(again.status().message().find("checksum mismatch") != std::string::npos);
  CHECK_FALSE(prt::read_glossy_transfer_file(path.string()).ok());
}
