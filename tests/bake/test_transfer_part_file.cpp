// tests/bake/test_transfer_part_file.cpp — decode_transfer_part (bake/transfer_part_file.h) on
// parts whose header counts are hostile: every array a part holds is counted from its rows,
// vertices or triangles times a per-row size, and those products must not wrap to the size of a
// small section (a part that decodes with 2⁶² rows and no values; a division by zero in Haar
// parts; a std::length_error escaping instead of a BakeError). Each is refused with one line
// that names the part. The parts are built in memory (prt::PartFile with owned sections): the
// container's own checks (read_part_file) are the CLI farm tests' and the fuzzer's; here only
// that a read part does not keep its pages resident (prt::release_part_pages), and that the
// glossy and Haar merges release each part's pages once they have copied its rows.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/bake_settings.h"
#include "bake/transfer_part_file.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/part_file.h"
#include "scene/procedural_mesh.h"

using namespace prt::bake;

namespace {

const std::string kName = "hostile.prtpart";

prt::PartSection section(uint32_t tag, const std::string& bytes) {
  prt::PartSection s;
  s.tag = tag;
  s.bytes.assign(bytes.begin(), bytes.end());
  return s;
}

std::string settings_section(const std::string& settings) {
  nlohmann::json j;
  j["generator"] = "test";
  j["prt_version"] = "test";
  j["seed"] = 1;
  j["settings"] = nlohmann::json::parse(settings);
  j["scene_inputs"] = "0000000000000000";
  return j.dump();
}

// Zero counters (section 12): three u64.
std::string counters() {
  return std::string(24, '\0');
}

prt::PartFile part(prt::PartKind kind, uint32_t index, uint32_t count, uint64_t total,
                   uint64_t rows, const std::string& settings) {
  prt::PartFile f;
  f.layout = part_layout_id();
  f.kind = kind;
  f.index = index;
  f.count = count;
  f.total_rows = total;
  f.first_row = 0;
  f.row_count = rows;
  f.sections.push_back(section(1, settings_section(settings)));
  f.sections.push_back(section(12, counters()));
  return f;
}

BakeOptions sh_options() {
  BakeOptions o;
  o.order = 2;  // K = 4 coefficients a row
  o.samples = 16;
  return o;
}

// decode_transfer_part(f) throws a BakeError of one line that names the part and says `what`.
void check_refused(const prt::PartFile& f, const std::string& what) {
  try {
    (void)decode_transfer_part(f, kName);
    FAIL("decoded a part with wrapping counts");
  } catch (const BakeError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.rfind(kName + ": ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find(what) != std::string::npos);
  }
}

std::string scene_json(uint64_t triangles) {
  nlohmann::json j;
  j["source_path"] = "quad.obj";
  j["skipped_degenerate_triangles"] = 0;
  j["triangles"] = triangles;
  j["primitives"] = nlohmann::json::array();
  return j.dump();
}

}  // namespace

TEST_CASE("part decode: row counts that wrap a section's size are refused",
          "[bake][farm][part-file]") {
  SECTION("SH: 2^62 rows of 4 coefficients (4 * 2^62 wraps to 0: no direct section needed)") {
    check_refused(part(prt::PartKind::ShTransfer, 1, 2, uint64_t{1} << 62, uint64_t{1} << 62,
                       sh_bake_settings(sh_options())),
                  "direct transfer section");
  }
  SECTION("Haar: 2^57 rows of an 8 x 8 cube (384 * 2^57 wraps to 0: was a division by zero)") {
    HaarBakeOptions o;
    o.cube_size = 8;
    o.transport = prt::TransferKind::Interreflected;
    prt::PartFile f = part(prt::PartKind::HaarTransfer, 1, 2, uint64_t{1} << 57, uint64_t{1} << 57,
                           haar_bake_settings(o));
    f.sections.push_back(section(16, std::string(16, '\0')));  // the wavelets
    check_refused(f, "wavelets section");
  }
  SECTION("glossy: 2^60 rows of order-2 matrices (16 * 2^60 wraps to 0)") {
    GlossyBakeOptions o;
    o.order = 2;
    o.samples = 16;
    check_refused(part(prt::PartKind::GlossyTransfer, 1, 2, uint64_t{1} << 60, uint64_t{1} << 60,
                       glossy_bake_settings(o)),
                  "direct matrices section");
  }
  SECTION("form factors: 2^32 rows of 2^32 patches (the product wraps to 0)") {
    check_refused(part(prt::PartKind::FormFactorRows, 0, 1, uint64_t{1} << 32, uint64_t{1} << 32,
                       R"({"basis":"form factors"})"),
                  "form factors section");
  }
}

TEST_CASE("part decode: shard 0's scene with counts that wrap is refused, an empty one decoded",
          "[bake][farm][part-file]") {
  const std::string settings = sh_bake_settings(sh_options());
  const std::string two_floats(8, '\0');
  SECTION("0x5555555555555556 vertices (3 V wraps to 2: was a std::length_error)") {
    prt::PartFile f = part(prt::PartKind::ShTransfer, 0, 1, 0x5555555555555556ull, 0, settings);
    f.sections.push_back(section(2, scene_json(0)));
    for (uint32_t tag : {3u, 4u, 5u}) f.sections.push_back(section(tag, two_floats));
    check_refused(f, "positions section");
  }
  SECTION("0x5555555555555556 triangles (3 T wraps to 2: was a std::length_error)") {
    prt::PartFile f = part(prt::PartKind::ShTransfer, 0, 1, 1, 0, settings);
    const float xyz[3] = {0.f, 0.f, 1.f};
    const std::string vertex(reinterpret_cast<const char*>(xyz), sizeof xyz);
    f.sections.push_back(section(2, scene_json(0x5555555555555556ull)));
    for (uint32_t tag : {3u, 4u, 5u}) f.sections.push_back(section(tag, vertex));
    f.sections.push_back(section(6, two_floats));
    check_refused(f, "triangles section");
  }
  SECTION("no vertices: decoded (the fingerprint of no positions, formed without indexing)") {
    prt::PartFile f = part(prt::PartKind::ShTransfer, 0, 1, 0, 0, settings);
    f.fingerprint = prt::geometry_fingerprint(nullptr, 0);
    f.sections.push_back(section(2, scene_json(0)));
    const TransferPartFile d = decode_transfer_part(f, kName);
    REQUIRE(d.scene);
    CHECK(d.scene->positions.empty());
    CHECK(d.part.rows.size() == 0);
  }
}

namespace {

// This process's resident file-backed memory in kB (Linux: RssFile of /proc/self/status), or
// -1 where it is not reported.
long status_kb(const std::string& wanted) {
  std::ifstream status("/proc/self/status");
  std::string key;
  long kb = -1;
  while (status >> key) {
    if (key == wanted) {
      status >> kb;
      return kb;
    }
    status.ignore(1 << 20, '\n');
  }
  return -1;
}

long resident_file_kb() {
  return status_kb("RssFile:");
}

// All of this process's resident memory in kB (VmRSS: anonymous and file-backed), or -1.
long resident_kb() {
  return status_kb("VmRSS:");
}

}  // namespace

// A merge reads every part first and copies their rows afterwards, one part at a time: a part's
// mapping must not stay resident from its read (MAP_POPULATE, for the checksum) to the end, or
// the merge holds every part on top of the single bake's arrays. 32 MB of section; the slack of
// 8 MB is for other file pages the process may touch meanwhile (code, libraries).
TEST_CASE("part file: a read part's pages are released after the checksum, and on request",
          "[part-file]") {
  if (resident_file_kb() < 0) {
    WARN("RssFile is not reported here: skipped");
    return;
  }
  const std::filesystem::path dir = std::filesystem::path(PRT_TEST_OUTPUT_DIR) / "part_pages";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "big.prtpart").string();
  std::vector<uint64_t> values(uint64_t(4) << 20);  // 32 MB
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = i * 0x9E3779B97F4A7C15ull;
  const uint64_t bytes = values.size() * sizeof(uint64_t);
  {
    prt::PartFile f;
    f.total_rows = f.row_count = 1;
    prt::PartSection s;
    s.tag = 7;
    s.view = values.data();
    s.view_size = bytes;
    f.sections.push_back(std::move(s));
    REQUIRE(prt::write_part_file(path, f).ok());
  }
  const long before = resident_file_kb();
  prt::PartFile read;
  REQUIRE(prt::read_part_file(path, &read).ok());
  CHECK(resident_file_kb() - before < 8 * 1024);
  const prt::PartSection* s = read.find(7);
  REQUIRE(s != nullptr);
  REQUIRE(s->size() == bytes);
  // The bytes come back from the file, unchanged; reading them makes them resident again (so
  // the checks on the resident size can fail).
  CHECK(std::memcmp(s->data(), values.data(), bytes) == 0);
  CHECK(resident_file_kb() - before > 24 * 1024);
  prt::release_part_pages(s->data(), s->size());
  CHECK(resident_file_kb() - before < 8 * 1024);
  CHECK(std::memcmp(s->data(), values.data(), bytes) == 0);
  prt::release_part_pages(nullptr, 0);  // nothing to release: no effect
}

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A flat grid of (segments + 1)² vertices, grey (one Haar channel; glossy inputs from its UVs).
prt::scene::Scene grid(int segments) {
  return prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, segments, segments,
                               {0.5f, 0.5f, 0.5f});
}

// Shard i of n's values of a row: distinct, deterministic, in a range the bakes' files keep.
float row_value(uint64_t row, uint64_t k) {
  return 0.001f * static_cast<float>((row * 7919 + k * 104729) % 1000);
}

// Reads and decodes the parts at `paths`, in shard order.
std::vector<TransferPartFile> read_parts(const std::vector<std::string>& paths) {
  std::vector<TransferPartFile> parts;
  for (const std::string& path : paths) {
    prt::PartFile f;
    const prt::Status read = prt::read_part_file(path, &f);
    REQUIRE(read.ok());
    parts.push_back(decode_transfer_part(f, path));
  }
  return parts;
}

}  // namespace

// The glossy merge, as the SH one: a part's direct matrices stay in its file's mapping when
// decoded (not copied, not resident), and the merge releases each part's pages once it has copied
// its rows, so that after the merge its parts are not resident; the file is the one the parts
// held in memory merge to, byte for byte. Two parts of about 17 MB of direct matrices each
// (13 456 vertices × 625 floats); the slack of 8 MB is the other test's.
TEST_CASE("glossy parts: read without keeping their pages, released by the merge",
          "[part-file][glossy]") {
  if (resident_file_kb() < 0) {
    WARN("RssFile is not reported here: skipped");
    return;
  }
  const std::filesystem::path dir = std::filesystem::path(PRT_TEST_OUTPUT_DIR) / "glossy_pages";
  std::filesystem::create_directories(dir);
  const prt::scene::Scene scene = grid(115);
  const uint64_t V = scene.vertex_count();
  GlossyBakeOptions o;
  o.order = 5;
  o.samples = 16;
  const uint64_t KK = 625;
  const GlossyInputs inputs = glossy_inputs(scene);
  const std::vector<std::string> paths = {(dir / "g0.prtpart").string(),
                                          (dir / "g1.prtpart").string()};
  const std::string reference = (dir / "reference.prtg").string();
  const std::string merged = (dir / "merged.prtg").string();
  {
    std::vector<GlossyPart> parts(2);
    std::vector<const GlossyPart*> in_memory;
    for (uint32_t i = 0; i < 2; ++i) {
      GlossyPart& p = parts[i];
      p.shard = {i, 2};
      p.vertices = V;
      p.rows = shard_rows(V, p.shard);
      p.order = o.order;
      p.direct.resize(p.rows.size() * KK);
      for (uint64_t r = 0; r < p.rows.size(); ++r)
        for (uint64_t k = 0; k < KK; ++k) p.direct[r * KK + k] = row_value(p.rows.first + r, k);
      REQUIRE(prt::write_part_file(paths[i], encode_glossy_part(p, scene, inputs, o, "test")).ok());
      in_memory.push_back(&p);
    }
    merge_glossy_parts_to_file(scene, inputs, o, in_memory, reference);
  }
  const long before = resident_file_kb(), all_before = resident_kb();
  const std::vector<TransferPartFile> read = read_parts(paths);
  CHECK(resident_file_kb() - before < 8 * 1024);
  CHECK(resident_kb() - all_before < 8 * 1024);  // nor copied into memory of their own
  std::vector<const GlossyPart*> parts;
  for (const TransferPartFile& f : read) {
    REQUIRE(f.glossy);
    CHECK(f.glossy_part.direct.empty());  // a view into the mapping, not a copy
    CHECK(f.glossy_part.direct_size() == f.glossy_part.rows.size() * KK);
    parts.push_back(&f.glossy_part);
  }
  REQUIRE(read[0].scene);
  REQUIRE(read[0].glossy_inputs);
  merge_glossy_parts_to_file(*read[0].scene, *read[0].glossy_inputs, read[0].glossy_options, parts,
                             merged);
  CHECK(resident_file_kb() - before < 8 * 1024);
  const std::string bytes = file_bytes(merged);
  REQUIRE(!bytes.empty());
  CHECK(bytes == file_bytes(reference));
  // The values come back from the file after the release.
  CHECK(parts[1]->direct_values()[KK + 3] == row_value(parts[1]->rows.first + 1, 3));
}

// The Haar merge (interreflected: each row's dense D̂), as the glossy one above: decoded without
// copying, released once copied; the result is the in-memory parts' merge. Two parts of about
// 16 MB of wavelets each (21 316 vertices × 6·8² floats).
TEST_CASE("Haar parts: read without keeping their pages, released by the merge",
          "[part-file][haar]") {
  if (resident_file_kb() < 0) {
    WARN("RssFile is not reported here: skipped");
    return;
  }
  const std::filesystem::path dir = std::filesystem::path(PRT_TEST_OUTPUT_DIR) / "haar_pages";
  std::filesystem::create_directories(dir);
  const prt::scene::Scene scene = grid(145);
  const uint64_t V = scene.vertex_count();
  HaarBakeOptions o;
  o.transport = prt::TransferKind::Interreflected;
  o.cube_size = 8;
  const uint64_t W = 6 * 8 * 8;
  const std::vector<std::string> paths = {(dir / "h0.prtpart").string(),
                                          (dir / "h1.prtpart").string()};
  const std::string reference = (dir / "reference.prth").string();
  const std::string merged = (dir / "merged.prth").string();
  {
    std::vector<HaarPart> parts(2);
    std::vector<const HaarPart*> in_memory;
    for (uint32_t i = 0; i < 2; ++i) {
      HaarPart& p = parts[i];
      p.shard = {i, 2};
      p.vertices = V;
      p.rows = shard_rows(V, p.shard);
      p.wavelets.resize(p.rows.size() * W);
      for (uint64_t r = 0; r < p.rows.size(); ++r)
        for (uint64_t k = 0; k < W; ++k) p.wavelets[r * W + k] = row_value(p.rows.first + r, k);
      p.gather_lengths.assign(p.rows.size(), 0);  // no bounce light: D̂ is the answer
      REQUIRE(prt::write_part_file(paths[i], encode_haar_part(p, scene, o, "test")).ok());
      in_memory.push_back(&p);
    }
    REQUIRE(
        prt::write_haar_transfer_file(reference, merge_haar_parts(scene, o, in_memory).file).ok());
  }
  const long before = resident_file_kb(), all_before = resident_kb();
  const std::vector<TransferPartFile> read = read_parts(paths);
  CHECK(resident_file_kb() - before < 8 * 1024);
  CHECK(resident_kb() - all_before < 8 * 1024);  // nor copied into memory of their own
  std::vector<const HaarPart*> parts;
  for (const TransferPartFile& f : read) {
    REQUIRE(f.haar);
    CHECK(f.haar_part.wavelets.empty());  // a view into the mapping, not a copy
    CHECK(f.haar_part.wavelet_size() == f.haar_part.rows.size() * W);
    parts.push_back(&f.haar_part);
  }
  REQUIRE(read[0].scene);
  const HaarBakeResult result = merge_haar_parts(*read[0].scene, read[0].haar_options, parts);
  CHECK(resident_file_kb() - before < 8 * 1024);
  REQUIRE(prt::write_haar_transfer_file(merged, result.file).ok());
  CHECK(file_bytes(merged) == file_bytes(reference));
  CHECK(parts[1]->wavelet_data()[W + 3] == row_value(parts[1]->rows.first + 1, 3));
}
