// Emitter-response files (prt/emitters/emitter_responses.h): byte round trip, the layout of
// docs/FORMAT.md checked at fixed offsets, every corrupt or truncated variant refused with one
// line, recombination against hand-computed sums, and bad colours or names refused.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/emitters/emitter_responses.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/geometry_check.h"

namespace fs = std::filesystem;

namespace {

// Two triangles (a unit quad), two emitters with distinct responses.
prt::EmitterResponses small_responses() {
  prt::EmitterResponses d;
  d.emitters = {{"lamp", {5.f, 5.f, 5.f}}, {"window-panel", {0.f, 1.f, 2.5f}}};
  d.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  d.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  d.triangles = {0, 1, 2, 0, 2, 3};
  for (int e = 0; e < 2; ++e)
    for (int v = 0; v < 4; ++v)
      for (int c = 0; c < 3; ++c) d.responses.push_back(0.01f * float(1 + e * 37 + v * 5 + c));
  return d;
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

// Recomputes the checksum after an edit, so the reader's later checks are reached.
void reseal(std::vector<unsigned char>& b) {
  std::memset(b.data() + 48, 0, 4);
  const uint32_t crc = prt::crc32c(b.data(), b.size());
  std::memcpy(b.data() + 48, &crc, 4);
}

std::string refusal(const std::vector<unsigned char>& b) {
  const prt::Result<prt::EmitterResponses> r =
      prt::decode_emitter_responses(b.data(), b.size(), "f.prte");
  REQUIRE_FALSE(r.ok());
  const std::string m = r.status().message();
  CHECK(m.rfind("f.prte: ", 0) == 0);
  CHECK(m.find('\n') == std::string::npos);
  return m;
}

}  // namespace

TEST_CASE("emitter responses: round trip through bytes and a file, layout as documented",
          "[prt][emitter-responses]") {
  const prt::EmitterResponses d = small_responses();
  const auto bytes = prt::encode_emitter_responses(d, "mem");
  REQUIRE(bytes.ok());
  const std::vector<unsigned char>& b = *bytes;
  // docs/FORMAT.md: 64-byte header, 16-byte records, names padded to 4, then the arrays.
  const std::size_t names = 4 + 12, expected = 64 + 2 * 16 + 16 + 12 * 4 * 2 + 12 * 2 + 12 * 4 * 2;
  CHECK(b.size() == expected);
  CHECK(std::memcmp(b.data(), "PRTE", 4) == 0);
  CHECK(u32_at(b, 4) == 1u);
  CHECK(u32_at(b, 8) == 64u);
  CHECK(u32_at(b, 12) == 2u);
  CHECK(u64_at(b, 16) == 4u);
  CHECK(u64_at(b, 24) == 2u);
  CHECK(u64_at(b, 32) == prt::geometry_fingerprint(d.positions.data(), 4));
  CHECK(u64_at(b, 40) == b.size());
  CHECK(u32_at(b, 52) == names);
  CHECK(u32_at(b, 64) == 4u);  // "lamp"
  CHECK(std::memcmp(b.data() + 64 + 32, "lampwindow-panel", names) == 0);
  float first_response;
  std::memcpy(&first_response, b.data() + expected - 12 * 8, 4);
  CHECK(first_response == d.responses[0]);

  const fs::path path = fs::path(PRT_TEST_OUTPUT_DIR) / "emitter_round_trip.prte";
  fs::remove(path);
  REQUIRE(prt::write_emitter_responses(path.string(), d).ok());
  CHECK(prt::is_emitter_responses_file(path.string()));
  const prt::Result<prt::EmitterResponses> back = prt::read_emitter_responses(path.string());
  REQUIRE(back.ok());
  CHECK(back->emitters.size() == 2);
  CHECK(back->emitters[1].name == "window-panel");
  CHECK(back->emitters[1].emission == d.emitters[1].emission);
  CHECK(back->positions == d.positions);
  CHECK(back->normals == d.normals);
  CHECK(back->triangles == d.triangles);
  CHECK(back->responses == d.responses);
  CHECK(back->fingerprint == prt::geometry_fingerprint(d.positions.data(), 4));
}

TEST_CASE("emitter responses: truncated, corrupt and inconsistent files are refused",
          "[prt][emitter-responses]") {
  const std::vector<unsigned char> good = *prt::encode_emitter_responses(small_responses(), "m");
  for (std::size_t size : {std::size_t{0}, std::size_t{10}, std::size_t{63}, std::size_t{64},
                           good.size() / 2, good.size() - 1}) {
    INFO(size);
    const std::vector<unsigned char> cut(good.begin(), good.begin() + std::ptrdiff_t(size));
    CHECK(refusal(cut).find("truncated") != std::string::npos);
  }
  std::vector<unsigned char> longer = good;
  longer.push_back(0);
  CHECK(refusal(longer).find("unexpected bytes") != std::string::npos);
  // Every single flipped byte outside the checksum field is caught (by the checksum at least).
  for (std::size_t at = 0; at < good.size(); ++at) {
    if (at >= 48 && at < 52) continue;
    std::vector<unsigned char> bad = good;
    bad[at] ^= 0x10;
    INFO(at);
    refusal(bad);
  }
  std::vector<unsigned char> magic = good;
  magic[3] = 'X';
  CHECK(refusal(magic).find("bad magic") != std::string::npos);
  // Resealed edits reach the value checks: a negative, a NaN and an infinite response, a NaN
  // emission, a triangle index out of range, a wrong count.
  const std::size_t responses_at = good.size() - 12 * 8, emission_at = 64 + 16 + 4;
  const std::size_t triangles_at = responses_at - 24;
  for (float value :
       {-1.f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<unsigned char> bad = good;
    std::memcpy(bad.data() + responses_at + 4 * 13, &value, 4);
    reseal(bad);
    CHECK(refusal(bad).find("negative, NaN or infinite") != std::string::npos);
    bad = good;
    std::memcpy(bad.data() + emission_at, &value, 4);
    reseal(bad);
    CHECK(refusal(bad).find("emission") != std::string::npos);
  }
  std::vector<unsigned char> index = good;
  const uint32_t four = 4;
  std::memcpy(index.data() + triangles_at + 8, &four, 4);
  reseal(index);
  CHECK(refusal(index).find("out of range") != std::string::npos);
  std::vector<unsigned char> count = good;
  count[12] = 3;  // three emitters claimed
  reseal(count);
  CHECK(refusal(count).find("does not match") != std::string::npos);
  std::vector<unsigned char> moved = good;  // a position changed: the fingerprint no longer fits
  const float shifted = 0.5f;
  std::memcpy(moved.data() + 64 + 32 + 16, &shifted, 4);
  reseal(moved);
  CHECK(refusal(moved).find("fingerprint") != std::string::npos);

  const fs::path missing = fs::path(PRT_TEST_OUTPUT_DIR) / "no_such_file.prte";
  const prt::Result<prt::EmitterResponses> none = prt::read_emitter_responses(missing.string());
  REQUIRE_FALSE(none.ok());
  CHECK(none.status().message().find(missing.string()) == 0);
}

TEST_CASE("emitter responses: the writer refuses what a reader would refuse",
          "[prt][emitter-responses]") {
  prt::EmitterResponses d = small_responses();
  d.emitters[1].name = "lamp";
  CHECK_FALSE(prt::validate_emitter_responses(d, "x").ok());
  d = small_responses();
  d.responses.pop_back();
  CHECK_FALSE(prt::validate_emitter_responses(d, "x").ok());
  d = small_responses();
  d.emitters.clear();
  d.responses.clear();
  CHECK_FALSE(prt::validate_emitter_responses(d, "x").ok());
  d = small_responses();
  d.responses[5] = -0.5f;
  const fs::path path = fs::path(PRT_TEST_OUTPUT_DIR) / "emitter_refused.prte";
  fs::remove(path);
  CHECK_FALSE(prt::write_emitter_responses(path.string(), d).ok());
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE(
    "recombination sums colour times response per emitter and named colours replace stored "
    "emission",
    "[prt][emitter-responses]") {
  const prt::EmitterResponses d = small_responses();
  const auto stored = prt::emitter_colors(d, {});
  REQUIRE(stored.ok());
  CHECK(*stored == std::vector<float>{5, 5, 5, 0, 1, 2.5f});
  const auto recoloured =
      prt::emitter_colors(d, {{"window-panel", {2, 0, 1}}, {"lamp", {3, 3, 3}}});
  REQUIRE(recoloured.ok());
  std::vector<float> out(12, 7.f);
  REQUIRE(prt::recombine_emitters(d, *recoloured, out.data()).ok());
  const float colors[2][3] = {{3, 3, 3}, {2, 0, 1}};
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) {
      double expected = 0;
      for (int e = 0; e < 2; ++e)
        expected += double(colors[e][c]) * double(d.responses[3 * (e * 4 + v) + c]);
      CHECK(out[3 * v + c] == Approx(expected).epsilon(1e-6));
    }
  // Accumulating adds to what is there (PRT exit radiance + emitters).
  std::vector<float> base(12, 1.f), sum = base;
  REQUIRE(prt::recombine_emitters(d, *recoloured, sum.data(), true).ok());
  for (int i = 0; i < 12; ++i) CHECK(sum[i] == Approx(1.0 + out[i]).epsilon(1e-6));
  // Linearity: doubling one emitter adds its contribution once more.
  const auto doubled = prt::emitter_colors(d, {{"window-panel", {4, 0, 2}}, {"lamp", {3, 3, 3}}});
  const auto alone = prt::emitter_colors(d, {{"window-panel", {2, 0, 1}}, {"lamp", {0, 0, 0}}});
  std::vector<float> two(12), one(12);
  REQUIRE(prt::recombine_emitters(d, *doubled, two.data()).ok());
  REQUIRE(prt::recombine_emitters(d, *alone, one.data()).ok());
  for (int i = 0; i < 12; ++i) CHECK(two[i] == Approx(out[i] + one[i]).epsilon(1e-6));
}

TEST_CASE("recombination refuses unknown names and negative, NaN or infinite colours",
          "[prt][emitter-responses]") {
  const prt::EmitterResponses d = small_responses();
  const auto unknown = prt::emitter_colors(d, {{"sun", {1, 1, 1}}});
  REQUIRE_FALSE(unknown.ok());
  CHECK(unknown.status().message().find("sun") != std::string::npos);
  CHECK(unknown.status().message().find("lamp, window-panel") != std::string::npos);
  for (float bad :
       {-1.f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    CHECK_FALSE(prt::emitter_colors(d, {{"lamp", {1, bad, 1}}}).ok());
    std::vector<float> colors = {1, 1, 1, 1, 1, bad}, out(12);
    CHECK_FALSE(prt::recombine_emitters(d, colors, out.data()).ok());
  }
  std::vector<float> short_colors = {1, 1, 1}, out(12);
  CHECK_FALSE(prt::recombine_emitters(d, short_colors, out.data()).ok());
}
