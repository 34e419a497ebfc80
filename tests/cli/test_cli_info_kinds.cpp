// tests/cli/test_cli_info_kinds.cpp — `prt info` of the files it reads besides coefficient files:
// a form-factor cache (radiosity/form_factor_cache.h: patches, method, settings, revision, size;
// version 1 still read) and its --help, which names every kind.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "prt/formats/crc32c.h"

namespace fs = std::filesystem;
using namespace prt::test::cli;

namespace {

// A version-1 cache as the first format wrote it: 64-byte header, method 0, N = 2.
void write_version1(const fs::path& path) {
  std::vector<unsigned char> bytes(64 + 16, 0);
  const char magic[8] = {'P', 'R', 'T', 'F', 'F', 'M', '1', '\n'};
  std::memcpy(bytes.data(), magic, 8);
  const uint32_t version = 1, header = 64;
  const uint64_t key = 0x1234, n = 2, size = bytes.size();
  std::memcpy(&bytes[8], &version, 4);
  std::memcpy(&bytes[12], &header, 4);
  std::memcpy(&bytes[16], &key, 8);
  std::memcpy(&bytes[24], &n, 8);
  std::memcpy(&bytes[32], &size, 8);
  const float f[4] = {0.f, 0.5f, 0.25f, 0.f};
  std::memcpy(&bytes[64], f, sizeof f);
  const uint32_t crc = prt::crc32c(bytes.data(), bytes.size());
  std::memcpy(&bytes[48], &crc, 4);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

TEST_CASE("cli info: a form-factor cache states its patches, method, settings and size") {
  const fs::path dir = scratch("info_form_factors");
  const fs::path box = write_lit_box(dir);
  struct Case {
    std::string options, method;
  };
  for (const Case& c : {Case{"--form-factors rays --rays 64 --seed 5 --ray-sampling independent",
                             "rays, 64 per patch, seed 5, emitter rays 0, sampling independent"},
                        Case{"--form-factors hemicube --hemicube 16", "hemicube, resolution 16"},
                        Case{"--form-factors analytic --quadrature 1", "analytic, quadrature 1"}}) {
    const fs::path cache = dir / "box.ffm";
    fs::remove(cache);
    const RunResult solved =
        run(prt_cli() + " radiosity " + box.string() + " -o " + (dir / "box.png").string() +
            " --max-edge 0.5 --size 16x16 --quiet --form-factor-cache " + cache.string() + " " +
            c.options);
    INFO(c.options << "\n" << solved.err);
    REQUIRE(solved.exit_code == 0);
    const RunResult text = run(prt_cli() + " info " + cache.string());
    INFO(text.out << text.err);
    REQUIRE(text.exit_code == 0);
    CHECK(text.out.find("form-factor cache") != std::string::npos);
    CHECK(text.out.find("version 3") != std::string::npos);
    CHECK(text.out.find("method        " + c.method) != std::string::npos);
    CHECK(text.out.find("revision      2 (current)") != std::string::npos);
    const RunResult json = run(prt_cli() + " info --json " + cache.string());
    REQUIRE(json.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(json.out);
    // The size is the header's 104 bytes and N² floats: the patch count it states is the file's.
    const uint64_t n = j["patches"].get<uint64_t>();
    CHECK(n > 6);
    CHECK(j["bytes"].get<uint64_t>() == 104 + 4 * n * n);
    CHECK(fs::file_size(cache) == 104 + 4 * n * n);
    CHECK(j["revision"] == 2);
    CHECK(j["current_revision"] == 2);
    CHECK(j["method"].get<std::string>().rfind(c.method, 0) == 0);
    // The cache it describes is still the one radiosity reuses.
    const RunResult again =
        run(prt_cli() + " radiosity " + box.string() + " -o " + (dir / "box.png").string() +
            " --max-edge 0.5 --size 16x16 --form-factor-cache " + cache.string() + " " + c.options);
    REQUIRE(again.exit_code == 0);
  }
  // --csv has no rows to give for a cache: refused by name, as a usage error.
  const RunResult csv = run(prt_cli() + " info --csv " + (dir / "box.ffm").string());
  CHECK(csv.exit_code == 2);
  CHECK(csv.err.find("form-factor cache") != std::string::npos);

  // A version-1 cache (no settings) is still read, and says what it lacks.
  const fs::path old = dir / "old.ffm";
  write_version1(old);
  const RunResult v1 = run(prt_cli() + " info " + old.string());
  INFO(v1.err);
  REQUIRE(v1.exit_code == 0);
  CHECK(v1.out.find("version 1") != std::string::npos);
  CHECK(v1.out.find("patches       2 ") != std::string::npos);
  CHECK(v1.out.find("not recorded") != std::string::npos);
  CHECK(v1.out.find("revision      1 (earlier than this prt's 2") != std::string::npos);
  // A corrupt one is refused with one line naming the file.
  std::string bytes = slurp(old);
  bytes[70] ^= 0x10;
  std::ofstream(dir / "bad.ffm", std::ios::binary) << bytes;
  const RunResult bad = run(prt_cli() + " info " + (dir / "bad.ffm").string());
  CHECK(bad.exit_code == 1);
  CHECK(bad.err.find("bad.ffm: corrupt form-factor cache (checksum mismatch)") !=
        std::string::npos);
}

TEST_CASE("cli info: --help names every kind of file info reads") {
  const RunResult help = run(prt_cli() + " info --help");
  REQUIRE(help.exit_code == 0);
  for (const char* kind : {".prt", "Haar", ".prtg", ".prtq", ".prte", "form-factor cache",
                           "link cache", ".glb", ".gltf", ".obj"})
    CHECK(help.out.find(kind) != std::string::npos);
}
