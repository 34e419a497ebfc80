// `prt radiosity` as a user runs it: bad emission, albedo and --max-edge refused with one line
// on stderr and nothing written (exit 2 for the command line, 1 for the scene file's own
// problems, README "Exit status"); a small lit room written and lit.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "prt/formats/crc32c.h"

namespace fs = std::filesystem;

namespace {

using prt::test::cli::line_count;
using prt::test::cli::RunResult;
using prt::test::cli::slurp;

fs::path scratch(const std::string& name) {
  return prt::test::cli::scratch("radiosity_cli/" + name);
}

// Runs `prt radiosity ARGS` as a user does (tests/cli/cli_test_support.h).
RunResult run(const std::string& args) {
  return prt::test::cli::run(prt::test::cli::prt_cli() + " radiosity " + args);
}

// A room without a front wall, 1 unit wide, a lamp under the ceiling (material `lamp`, Ke from
// `lamp_ke`), white walls of albedo `white_kd`; `closed` adds the front wall.
fs::path write_room(const fs::path& dir, const std::string& lamp_ke, const std::string& white_kd,
                    bool closed) {
  std::ofstream(dir / "room.mtl") << "newmtl white\nKd " << white_kd
                                  << "\nnewmtl lamp\nKd 0.5 0.5 0.5\n"
                                  << (lamp_ke.empty() ? "" : "Ke " + lamp_ke + "\n");
  std::ofstream obj(dir / "room.obj");
  obj << "mtllib room.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
         "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"
         "o walls\nusemtl white\n"
         "f 1 4 3 2\n"                           // floor, facing +y
         "f 5 6 7 8\n"                           // ceiling, facing -y
         "f 1 5 8 4\n"                           // x = 0, facing +x
         "f 2 3 7 6\n"                           // x = 1, facing -x
         "f 4 8 7 3\n";                          // z = 1, facing -z
  if (closed) obj << "f 1 2 6 5\n";              // z = 0, facing +z
  obj << "o lamp\nusemtl lamp\nf 9 10 11 12\n";  // facing -y
  return dir / "room.obj";
}

void check_refused(const fs::path& dir, const std::string& args, const std::string& expected,
                   int exit_code = 2) {
  const RunResult r = run(args);
  INFO(args << "\nstderr: " << r.err);
  CHECK(r.exit_code == exit_code);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(expected) != std::string::npos);
  for (const char* name : {"out.png", "out.glb", "out.csv"}) CHECK_FALSE(fs::exists(dir / name));
}

// A form-factor cache's bytes (version 3, docs/FORMAT.md) with its algorithm revision set to
// `revision`, every factor times `scale`, and the checksum resealed.
std::string with_revision(std::string bytes, uint32_t revision, float scale) {
  std::memcpy(&bytes[96], &revision, 4);
  for (std::size_t at = 104; at + 4 <= bytes.size(); at += 4) {
    float f;
    std::memcpy(&f, &bytes[at], 4);
    f *= scale;
    std::memcpy(&bytes[at], &f, 4);
  }
  std::memset(&bytes[48], 0, 4);
  const uint32_t crc = prt::crc32c(bytes.data(), bytes.size());
  std::memcpy(&bytes[48], &crc, 4);
  return bytes;
}

// `prt info FILE`'s standard output.
std::string info_of(const std::string& file) {
  const RunResult r = prt::test::cli::run(prt::test::cli::prt_cli() + " info " + file);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  return r.out;
}

}  // namespace

TEST_CASE("prt radiosity refuses bad emission, albedo and --max-edge, nothing is written",
          "[radiosity][cli]") {
  const fs::path dir = scratch("refused");
  const std::string outputs = " -o " + (dir / "out.png").string() + " --vertex-colors " +
                              (dir / "out.glb").string() + " --csv " + (dir / "out.csv").string();
  std::string room = write_room(dir, "5 5 5", "0.7 0.7 0.7", false).string();
  check_refused(dir, room + outputs + " --emission lamp=-1,2,3", "--emission lamp=-1,2,3");
  check_refused(dir, room + outputs + " --emission lamp=nan", "non-negative");
  check_refused(dir, room + outputs + " --emission lamp=1,inf,1", "finite");
  check_refused(dir, room + outputs + " --emission glass=1", "glass");
  check_refused(dir, room + outputs + " --max-edge 0", "--max-edge");
  check_refused(dir, room + outputs + " --albedo white=1.2", "albedo");
  check_refused(dir, room + outputs + " --form-factors hemicube --hemicube 3", "--hemicube");
  check_refused(dir, room + outputs + " --form-factors radiance", "--form-factors");
  check_refused(dir, room + outputs + " --form-factors rays --ray-sampling halton",
                "--ray-sampling");
  check_refused(dir, room + outputs + " --form-factors rays --emitter-rows both", "--emitter-rows");
  check_refused(dir,
                room + outputs +
                    " --form-factors rays --emitter-rows reciprocal "
                    "--emitter-rays 4096",
                "--emitter-rays");
  check_refused(dir, room + outputs + " --max-edge 0.0001", "--max-edge");  // > 2e7 triangles
  check_refused(dir, room + outputs + " --max-edge 0.005 --solver gauss-seidel",
                "or --solver hierarchical");  // > 16384 patches: dense only (auto: hierarchical)
  room = write_room(dir, "-5 5 5", "0.7 0.7 0.7", false).string();
  check_refused(dir, room + outputs, "emission", 1);  // the file's own values: exit 1
  room = write_room(dir, "", "0.7 0.7 0.7", false).string();
  check_refused(dir, room + outputs, "nothing emits light", 1);
  room = write_room(dir, "5 5 5", "1 1 1", true).string();
  check_refused(dir, room + outputs, "closed scene", 1);
  // The same closed room with albedo below 1 is accepted.
  const RunResult ok = run(room + outputs + " --albedo white=0.9 --size 64x48 --spp 1");
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(fs::exists(dir / "out.png"));
}

TEST_CASE("prt radiosity lights a room from its lamp: CSV radiance and energy summary",
          "[radiosity][cli]") {
  const fs::path dir = scratch("room");
  const std::string room = write_room(dir, "5 5 5", "0.7 0.5 0.3", false).string();
  const RunResult r =
      run(room + " --max-edge 0.2 --tolerance 1e-8 --csv " + (dir / "out.csv").string() + " -o " +
          (dir / "out.exr").string() + " --size 64x48 --spp 1");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("balance error") != std::string::npos);
  // Every wall vertex receives light (all see the lamp or a lit wall); colours follow albedo.
  std::ifstream csv(dir / "out.csv");
  std::string line;
  std::getline(csv, line);
  std::size_t rows = 0, lit = 0, warm = 0;
  while (std::getline(csv, line)) {
    double i, x, y, z, red, green, blue;
    char c;
    std::istringstream s(line);
    s >> i >> c >> x >> c >> y >> c >> z >> c >> red >> c >> green >> c >> blue;
    ++rows;
    lit += red > 0;
    warm += red > green && green > blue;
  }
  CHECK(rows > 40);
  CHECK(lit == rows);
  CHECK(warm > rows * 9 / 10);  // walls of albedo (0.7, 0.5, 0.3) under a white lamp
}

TEST_CASE("prt radiosity --form-factor-cache: saved, reused, refused for another scene",
          "[radiosity][cli][cache]") {
  const fs::path dir = scratch("cache");
  const std::string room = write_room(dir, "5 5 5", "0.7 0.7 0.7", false).string();
  const std::string cache = (dir / "room.ffm").string();
  const std::string common = room + " --form-factors rays --rays 200 --tolerance 1e-8 --csv ";
  // First run: computed and saved.
  RunResult r =
      run(common + (dir / "a.csv").string() + " --max-edge 0.25" + " --form-factor-cache " + cache);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("form factors saved to " + cache) != std::string::npos);
  REQUIRE(fs::exists(cache));
  const std::string saved = slurp(cache);
  // Same geometry, new emission: loaded, not recomputed; the result equals a run without cache.
  r = run(common + (dir / "b.csv").string() + " --max-edge 0.25 --emission lamp=9,3,1" +
          " --form-factor-cache " + cache);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("form factors loaded from " + cache) != std::string::npos);
  r = run(common + (dir / "c.csv").string() + " --max-edge 0.25 --emission lamp=9,3,1");
  REQUIRE(r.exit_code == 0);
  CHECK(slurp(dir / "b.csv") == slurp(dir / "c.csv"));
  CHECK(slurp(dir / "b.csv") != slurp(dir / "a.csv"));
  // The lamp moved down: only the affected rows recomputed; equal to a run without cache.
  r = run(common + (dir / "d.csv").string() + " --max-edge 0.25 --move lamp=0,-0.2,0.1" +
          " --form-factor-cache " + cache);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("moved ") != std::string::npos);
  r = run(common + (dir / "e.csv").string() + " --max-edge 0.25 --move lamp=0,-0.2,0.1");
  REQUIRE(r.exit_code == 0);
  CHECK(slurp(dir / "d.csv") == slurp(dir / "e.csv"));
  CHECK(slurp(dir / "d.csv") != slurp(dir / "a.csv"));
  // Another subdivision (another scene) and other options: refused, nothing written, the cache
  // untouched.
  for (const std::string& other :
       {std::string(" --max-edge 0.2"), std::string(" --max-edge 0.25 --seed 5"),
        std::string(" --max-edge 0.25 --ray-sampling independent"),
        std::string(" --max-edge 0.25 --emitter-rows rays")}) {
    r = run(common + (dir / "out.csv").string() + other + " --form-factor-cache " + cache + " -o " +
            (dir / "out.png").string());
    INFO(other << "\n" << r.err);
    CHECK(r.exit_code == 1);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find(cache + ": made for another scene or other form-factor options") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out.csv"));
    CHECK_FALSE(fs::exists(dir / "out.png"));
    CHECK(slurp(cache) == saved);
  }
  // A truncated cache: one line naming it.
  std::ofstream(dir / "short.ffm", std::ios::binary) << saved.substr(0, saved.size() / 2);
  r = run(common + (dir / "out.csv").string() + " --max-edge 0.25 --form-factor-cache " +
          (dir / "short.ffm").string());
  CHECK(r.exit_code == 1);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("short.ffm: truncated") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out.csv"));
  // An unknown object to move.
  r = run(common + (dir / "out.csv").string() + " --move chair=1,0,0");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--move chair") != std::string::npos);
}

// A cache of an earlier revision of the form-factor algorithms (here its revision field set back
// to 1 and its factors halved, so that loading them would show) is recomputed and saved over,
// with one warning line on stderr that --quiet does not silence: the CSV is a run without
// cache's and the file the one a fresh run saves. A later revision is refused with one line,
// nothing written. `prt info` names the revision of each.
TEST_CASE("prt radiosity --form-factor-cache: a cache of earlier algorithms is recomputed",
          "[radiosity][cli][cache]") {
  const fs::path dir = scratch("stale_cache");
  const std::string room = write_room(dir, "5 5 5", "0.7 0.7 0.7", false).string();
  const std::string cache = (dir / "room.ffm").string();
  const std::string common = room +
                             " --max-edge 0.25 --form-factors rays --rays 200 --emitter-rows "
                             "reciprocal --tolerance 1e-8 --quiet --csv ";
  RunResult r = run(common + (dir / "a.csv").string() + " --form-factor-cache " + cache);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string saved = slurp(cache);
  CHECK(info_of(cache).find("revision      2 (current)") != std::string::npos);
  REQUIRE(run(common + (dir / "none.csv").string()).exit_code == 0);
  CHECK(slurp(dir / "a.csv") == slurp(dir / "none.csv"));

  std::ofstream(cache, std::ios::binary) << with_revision(saved, 1, 0.5f);
  CHECK(info_of(cache).find("revision      1 (earlier than this prt's 2") != std::string::npos);
  r = run(common + (dir / "b.csv").string() + " --form-factor-cache " + cache);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("prt radiosity: warning: " + cache +
                   ": form factors of algorithm revision 1, earlier than this prt's 2: "
                   "recomputed and saved over it") != std::string::npos);
  CHECK(slurp(dir / "b.csv") == slurp(dir / "none.csv"));
  CHECK(slurp(cache) == saved);

  // The same stale cache where it cannot be replaced (a read-only folder; a name so long that
  // the temporary's name passes NAME_MAX, which stops root too): the run goes on, exit 0, the
  // CSV a run without cache's, one warning naming the file and why; the file is left as it was.
  const fs::path shared = dir / "shared";
  fs::create_directories(shared);
  const std::string stuck = (shared / (std::string(246, 'c') + ".ffm")).string();
  const std::string stale = with_revision(saved, 1, 0.5f);
  std::ofstream(stuck, std::ios::binary) << stale;
  fs::permissions(shared, fs::perms(0555));
  r = run(common + (dir / "c.csv").string() + " --form-factor-cache " + stuck);
  fs::permissions(shared, fs::perms(0755));
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("prt radiosity: warning: " + stuck +
                   ": form factors of algorithm revision 1, earlier than this prt's 2: "
                   "recomputed; the cache could not be updated (" +
                   stuck + ": cannot create ") != std::string::npos);
  CHECK(slurp(dir / "c.csv") == slurp(dir / "none.csv"));
  CHECK(slurp(stuck) == stale);

  const std::string later = with_revision(saved, 3, 1.f);
  std::ofstream(cache, std::ios::binary) << later;
  CHECK(info_of(cache).find("revision      3 (later than this prt's 2: refused)") !=
        std::string::npos);
  check_refused(dir, common + (dir / "out.csv").string() + " --form-factor-cache " + cache,
                cache + ": form factors of algorithm revision 3, this prt computes revision 2", 1);
  CHECK(slurp(cache) == later);
}

TEST_CASE("prt radiosity --adaptive: refines in passes to the budget, bad values refused",
          "[radiosity][cli]") {
  const fs::path dir = scratch("adaptive");
  const std::string outputs = " -o " + (dir / "out.png").string() + " --vertex-colors " +
                              (dir / "out.glb").string() + " --csv " + (dir / "out.csv").string();
  const std::string room = write_room(dir, "5 5 5", "0.7 0.7 0.7", false).string();
  check_refused(dir, room + outputs + " --max-edge 0.5 --adaptive 0", "--adaptive");
  check_refused(dir, room + outputs + " --max-edge 0.5 --adaptive nan", "--adaptive");
  check_refused(dir, room + outputs + " --max-edge 0.5 --max-patches 100", "--max-patches");
  check_refused(dir, room + outputs + " --max-edge 0.5 --adaptive 0.1 --max-patches 3",
                "--max-patches");
  check_refused(dir, room + outputs + " --max-edge 0.5 --adaptive 0.1 --adaptive-levels 0",
                "--adaptive-levels");
  const RunResult r = run(room + " --max-edge 0.5 --adaptive 0.05 --max-patches 300 --csv " +
                          (dir / "out.csv").string());
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  std::size_t first = 0, patches = 0;
  REQUIRE(r.out.find("adaptive pass 2:") != std::string::npos);
  CHECK(std::sscanf(r.out.c_str(), "adaptive pass 1: %zu patches", &first) == 1);
  CHECK(std::sscanf(r.out.substr(r.out.find('\n', r.out.rfind("adaptive pass")) + 1).c_str(),
                    "%zu patches", &patches) == 1);
  CHECK(first > 0);
  CHECK(patches > first);
  CHECK(patches <= 300);
}

TEST_CASE("prt radiosity prints its choice of form factors in one line, --quiet silences it",
          "[radiosity][cli]") {
  const fs::path dir = scratch("choice");
  const std::string room = write_room(dir, "5 5 5", "0.7 0.5 0.3", false).string();
  const std::string csv = " --csv " + (dir / "out.csv").string();
  const auto choice_lines = [](const std::string& out) {
    std::size_t n = 0;
    for (std::size_t at = out.find("form factors: "); at != std::string::npos;
         at = out.find("form factors: ", at + 1))
      ++n;
    return n;
  };
  RunResult r = run(room + " --max-edge 0.2" + csv);  // 588 patches: analytic
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(choice_lines(r.out) == 1);
  CHECK(r.out.find("form factors: analytic (") != std::string::npos);
  r = run(room + " --max-edge 0.1" + csv);  // over 1500 patches: rays
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("form factors: rays, 1024 per patch (") != std::string::npos);
  r = run(room + " --max-edge 0.1 --quiet" + csv);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.empty());
  r = run(room + " --max-edge 0.2 --form-factors analytic" + csv);  // forced: no choice
  REQUIRE(r.exit_code == 0);
  CHECK(choice_lines(r.out) == 0);
}

TEST_CASE(
    "prt radiosity --solver hierarchical: links, passes and memory printed, the link cache, "
    "dense-only options refused",
    "[radiosity][cli][hierarchical]") {
  const fs::path dir = scratch("hierarchical");
  const std::string room = write_room(dir, "5 5 5", "0.7 0.5 0.3", false).string();
  const RunResult r =
      run(room + " --solver hierarchical --max-edge 0.1 --csv " + (dir / "out.csv").string() +
          " --per-emitter " + (dir / "out.prte").string());
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("hierarchical: ") != std::string::npos);
  CHECK(r.out.find(" links (") != std::string::npos);
  CHECK(r.out.find("hierarchical pass 2: ") != std::string::npos);
  CHECK(r.out.find("charged at the peak") != std::string::npos);
  CHECK(r.out.find("per-emitter responses: 1 emitter") != std::string::npos);
  CHECK(fs::exists(dir / "out.prte"));
  // The link cache: saved, then used as it is for the same light (the same CSV, byte for byte),
  // re-checked for another lamp colour; refused with --move.
  const std::string cached = room + " --solver hierarchical --max-edge 0.1 --form-factor-cache " +
                             (dir / "room.links").string() + " --csv ";
  const RunResult saved = run(cached + (dir / "saved.csv").string());
  INFO(saved.out << saved.err);
  REQUIRE(saved.exit_code == 0);
  CHECK(saved.out.find("links saved to " + (dir / "room.links").string()) != std::string::npos);
  const RunResult reused = run(cached + (dir / "reused.csv").string());
  INFO(reused.out << reused.err);
  REQUIRE(reused.exit_code == 0);
  CHECK(reused.out.find("the same emission and albedo: used as they are") != std::string::npos);
  const auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  CHECK(bytes(dir / "reused.csv") == bytes(dir / "saved.csv"));
  // `prt info` describes the link cache: its kind, patch and link counts and the three keys.
  const RunResult info = prt::test::cli::run(prt::test::cli::prt_cli() + " info " +
                                             (dir / "room.links").string() + " --json");
  INFO(info.out << info.err);
  REQUIRE(info.exit_code == 0);
  const nlohmann::json described = nlohmann::json::parse(info.out);
  CHECK(described.at("kind") == "link cache");
  CHECK(described.at("links").get<uint64_t>() > 0);
  CHECK(described.at("patches").get<uint64_t>() > 0);
  CHECK(described.at("keys").at("lighting").get<std::string>().size() == 16);
  CHECK(described.at("revision") == 1);
  CHECK(described.at("current_revision") == 1);
  // A link cache of a later revision of the link algorithms (the header's revision field, which
  // the reader checks before the checksum) is refused with one line naming it.
  {
    std::string later = bytes(dir / "room.links");
    later[112] = 2;
    const fs::path later_dir = scratch("hierarchical_later");
    std::ofstream(later_dir / "later.links", std::ios::binary) << later;
    check_refused(
        later_dir,
        room + " --solver hierarchical --max-edge 0.1 --form-factor-cache " +
            (later_dir / "later.links").string() + " --csv " + (later_dir / "out.csv").string(),
        "later.links: link cache of algorithm revision 2, this prt computes revision 1", 1);
  }
  const RunResult relit = run(cached + (dir / "relit.csv").string() + " --emission lamp=2,4,8");
  INFO(relit.out << relit.err);
  REQUIRE(relit.exit_code == 0);
  CHECK(relit.out.find("other emission or albedo: re-checked") != std::string::npos);
  const fs::path refused = scratch("hierarchical_refused");
  check_refused(refused,
                room + " --solver hierarchical --form-factor-cache " +
                    (refused / "ff.bin").string() + " --move lamp=0,0,0.1 --csv " +
                    (refused / "out.csv").string(),
                "--move: not with --form-factor-cache and the hierarchical solver");
  CHECK_FALSE(fs::exists(refused / "ff.bin"));
  check_refused(
      refused,
      room + " --solver hierarchical --form-factors rays --csv " + (refused / "out.csv").string(),
      "--form-factors: not with --solver hierarchical");
  check_refused(
      refused,
      room + " --solver jacobi --link-epsilon 1e-4 --csv " + (refused / "out.csv").string(),
      "--link-epsilon");
}
