// tests/bake/test_part_merge.cpp — the farm merges (bake/transfer_part.h, bake/glossy_part.h)
// called directly on sets of parts that do not fit: each is refused with a one-line BakeError
// that names the scene, and writes nothing. The cases are fuzz_part_merge's findings (fuzz/):
// the glossy merge took any set of parts (a shard missing, one given twice, a row range whose
// wrapped row count matched its matrices' size, which read far past the Morton order), and the
// SH merge copied gather hits naming no triangle of the scene into the solve's gather matrix.
// The valid sets still merge to the single bake, byte for byte.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/glossy_part.h"
#include "bake/transfer_part.h"
#include "bake/transfer_part_file.h"
#include "prt/formats/transfer_file.h"
#include "scene/procedural_mesh.h"

using namespace prt::bake;
namespace fs = std::filesystem;

namespace {

constexpr uint32_t kShards = 3;

// A 3 × 3 ground quad and a box standing on it: 40 vertices, 30 triangles, rays hit both.
prt::scene::Scene small_scene() {
  prt::scene::Scene s = prt::scene::make_quad({-1.f, 0.f, 1.f}, {2.f, 0.f, 0.f}, {0.f, 0.f, -2.f},
                                              3, 3, glm::vec3(0.7f), "ground");
  prt::scene::append_scene(s, prt::scene::make_box({-0.3f, 0.f, -0.3f}, {0.3f, 0.6f, 0.3f}, 1,
                                                   false, glm::vec3(0.8f, 0.5f, 0.3f), "box"));
  s.source_path = "merge_scene.obj";
  return s;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `merge()` throws a BakeError of one line that starts with the scene's name.
template <class Merge>
void check_refused(Merge merge) {
  try {
    merge();
    FAIL("merged parts that do not fit");
  } catch (const BakeError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.rfind("merge_scene.obj: ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}

}  // namespace

TEST_CASE("glossy merge: parts that do not tile the rows in shard order are refused",
          "[bake][farm][glossy]") {
  const prt::scene::Scene scene = small_scene();
  GlossyBakeOptions o;
  o.order = 2;
  o.samples = 16;
  o.bounces = 1;
  o.seed = 7;
  o.threads = 1;
  const GlossyInputs inputs = glossy_inputs(scene);
  std::vector<GlossyPart> parts;
  for (uint32_t i = 0; i < kShards; ++i) parts.push_back(bake_glossy_part(scene, o, {i, kShards}));
  const fs::path dir = fs::temp_directory_path() / "prt_test_part_merge";
  fs::create_directories(dir);
  const std::string merged = (dir / "merged.prtg").string();
  const std::string single = (dir / "single.prtg").string();
  fs::remove(merged);
  // Refused in one line, and the output not written.
  const auto refused = [&](const std::vector<const GlossyPart*>& given,
                           const GlossyBakeOptions& options) {
    check_refused([&] { (void)merge_glossy_parts_to_file(scene, inputs, options, given, merged); });
    CHECK(!fs::exists(merged));
  };

  SECTION("the valid set merges to the single bake's file") {
    (void)merge_glossy_parts_to_file(scene, inputs, o, {&parts[0], &parts[1], &parts[2]}, merged);
    (void)bake_glossy_transfer_to_file(scene, o, single);
    CHECK(read_bytes(merged) == read_bytes(single));
  }
  SECTION("a shard missing (was: merged, its vertices' matrices left zero)") {
    refused({&parts[0], &parts[2]}, o);
  }
  SECTION("a shard given twice (was: merged; with other hit counts, copies past the hits)") {
    refused({&parts[0], &parts[1], &parts[1], &parts[2]}, o);
  }
  SECTION("a hit with NaN barycentrics (was: merged; quantise_hit's lround(NaN) overflowed)") {
    GlossyPart hostile = parts[1];
    REQUIRE(!hostile.hits.empty());
    hostile.hits.back().v = std::numeric_limits<float>::quiet_NaN();
    refused({&parts[0], &hostile, &parts[2]}, o);
  }
  SECTION("options of SH order 1000 (was: allocated V 1000^4 floats before checking them)") {
    GlossyBakeOptions huge = o;
    huge.order = 1000;
    refused({&parts[0], &parts[1], &parts[2]}, huge);
  }
  SECTION("shards out of order") {
    refused({&parts[1], &parts[0], &parts[2]}, o);
  }
  SECTION(
      "rows [2^63, end) of a shadowed part: 16 (end - 2^63) wraps to the size of its "
      "matrices (was: read past the Morton order)") {
    GlossyBakeOptions shadowed = o;
    shadowed.bounces = 0;  // no hit counts, whose length would not match the wrapped rows
    std::vector<GlossyPart> s;
    for (uint32_t i = 0; i < kShards; ++i)
      s.push_back(bake_glossy_part(scene, shadowed, {i, kShards}));
    REQUIRE(s[0].rows.first == 0);
    s[0].rows.first = uint64_t{1} << 63;
    refused({&s[0], &s[1], &s[2]}, shadowed);
  }
  fs::remove_all(dir);
}

TEST_CASE("SH merge: a gather hit that names no triangle of the scene is refused", "[bake][farm]") {
  const prt::scene::Scene scene = small_scene();
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 2;
  o.samples = 16;
  o.bounces = 2;
  o.seed = 7;
  o.threads = 1;
  std::vector<TransferPart> parts;
  for (uint32_t i = 0; i < kShards; ++i)
    parts.push_back(bake_transfer_part(scene, o, {i, kShards}));
  const std::vector<const TransferPart*> given = {&parts[0], &parts[1], &parts[2]};
  // The valid set merges to the single bake (the check below refuses no hit of a real bake).
  CHECK(merge_transfer_parts(scene, o, given).data.coefficients ==
        bake_transfer(scene, o).data.coefficients);
  TransferPart& p = parts[1];
  REQUIRE(!p.gather_blocks.empty());
  REQUIRE(!p.gather_blocks.back().hits.empty());
  p.gather_blocks.back().hits.back().triangle = static_cast<uint32_t>(scene.triangles.size());
  check_refused([&] { (void)merge_transfer_parts(scene, o, given); });
}

TEST_CASE("part checks: a shard count of 2^32 - 1 is a missing shard, not 2^32 slots",
          "[bake][farm][part-file]") {
  // One part that says it is shard 0 of 4294967295 (read_part_file accepts any index below the
  // count): check_parts_fit sized a table of one pointer per shard (32 GB) before finding shard
  // 1 missing (fuzz_part_merge: out of memory).
  std::vector<TransferPartFile> parts(1);
  parts[0].name = "hostile.prtpart";
  parts[0].part.shard = {0, 0xFFFFFFFFu};
  parts[0].part.vertices = 40;
  parts[0].part.rows = shard_rows(40, parts[0].part.shard);
  try {
    (void)check_parts_fit(parts);
    FAIL("a split of 2^32 - 1 shards with one part fit");
  } catch (const BakeError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.rfind("shard 1/4294967295 is missing", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}
