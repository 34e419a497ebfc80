// `prt make-scene --scene level | field | field-glossy` as a user runs it: bad values refused with
// one line (exit 2) and nothing written, the same seed giving the same bytes, size targets met
// within the stated 5%, and a small level lit by its own lamps in `prt radiosity` (dense).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using prt::test::cli::line_count;
using prt::test::cli::RunResult;
using prt::test::cli::slurp;

RunResult make_scene(const std::string& args) {
  return prt::test::cli::run(prt::test::cli::prt_cli() + " make-scene " + args);
}

// The first number before `word` in `text` ("123 vertices"), or −1.
double number_before(const std::string& text, const std::string& word) {
  const std::size_t at = text.find(" " + word);
  if (at == std::string::npos) return -1;
  std::size_t start = text.rfind(' ', at - 1);
  start = start == std::string::npos ? 0 : start + 1;
  return std::stod(text.substr(start, at - start));
}

}  // namespace

TEST_CASE("prt make-scene --scene level refuses bad values with one line, nothing written",
          "[cli][level]") {
  const fs::path dir = prt::test::cli::scratch("make_scene_level");
  const std::string out = " -o " + (dir / "out.glb").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--scene level --rooms 0", "--rooms 0: expected 1 to 64"},
      {"--scene level --rooms 65", "--rooms 65"},
      {"--scene level --objects 20001", "--objects 20001"},
      {"--scene level --triangles 0", "--triangles 0"},
      {"--scene level --triangles -5", "--triangles -5: expected 1 to"},
      {"--scene level --triangles 100", "--triangles 100: the level comes no closer"},
      {"--scene field --vertices 20000000", "--vertices 20000000"},
      {"--scene field --seed 3", "--seed: only for --scene level"},
      {"--scene demo --triangles 5000", "--triangles: only for --scene level, field"},
      {"--scene level --triangles 5000 --vertices 5000", "give one size target"},
      {"--scene level --rooms x", "--rooms"},
      {"--scene hall", "--scene"},
  };
  for (const auto& [args, expected] : cases) {
    const RunResult r = make_scene(args + out);
    INFO(args << "\nstderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out.glb"));
  }
}

TEST_CASE("prt make-scene --scene level: the same seed gives the same bytes", "[cli][level]") {
  const fs::path dir = prt::test::cli::scratch("make_scene_level_seed");
  const std::string common = "--scene level --rooms 3 --objects 60 -o ";
  REQUIRE(make_scene(common + (dir / "a.glb").string()).exit_code == 0);
  REQUIRE(make_scene(common + (dir / "b.glb").string() + " --seed 1").exit_code == 0);
  REQUIRE(make_scene(common + (dir / "c.glb").string() + " --seed 2").exit_code == 0);
  CHECK(slurp(dir / "a.glb") == slurp(dir / "b.glb"));  // --seed 1 is the default
  CHECK(slurp(dir / "a.glb") != slurp(dir / "c.glb"));
}

TEST_CASE("prt make-scene size targets land within 5% of the request", "[cli][level]") {
  const fs::path dir = prt::test::cli::scratch("make_scene_sizes");
  for (const char* scene : {"field", "field-glossy"}) {
    const RunResult r = make_scene(std::string("--scene ") + scene + " --vertices 30000 -o " +
                                   (dir / (std::string(scene) + ".glb")).string());
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(std::abs(number_before(r.out, "vertices") - 30000) <= 0.05 * 30000);
  }
  const RunResult r =
      make_scene("--scene level --triangles 80000 -o " + (dir / "level.glb").string());
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(std::abs(number_before(r.out, "triangles") - 80000) <= 0.05 * 80000);
  CHECK(r.out.find("lamp_warm, lamp_cool, lamp_corridor") != std::string::npos);
  const RunResult glossy = prt::test::cli::run(prt::test::cli::prt_cli() + " info " +
                                               (dir / "field-glossy.glb").string());
  CHECK(glossy.out.find("glossy_red") != std::string::npos);
  CHECK(glossy.out.find("metal") != std::string::npos);
}

// A small level (2 rooms, a corridor, ~1200 patches) solved with analytic (dense) form factors:
// every emitting material and a named object are accepted by --emission and --move, and the
// rooms are lit: at most 5% of the vertices stay black (floor under objects), and the median
// vertex is neither black nor as bright as the lamps (1e-3 to 0.5 of the brightest vertex).
TEST_CASE("a small level is lit by its own lamps in prt radiosity", "[cli][level][radiosity]") {
  const fs::path dir = prt::test::cli::scratch("make_scene_level_radiosity");
  const std::string glb = (dir / "level.glb").string();
  REQUIRE(make_scene("--scene level --rooms 2 --objects 30 --triangles 1200 -o " + glb).exit_code ==
          0);
  const RunResult r = prt::test::cli::run(
      prt::test::cli::prt_cli() + " radiosity " + glb +
      " --form-factors analytic --emission lamp_cool=0.5,0.6,0.8 --move crate_0=0.1,0,0 --csv " +
      (dir / "out.csv").string() + " -o " + (dir / "out.png").string() + " --size 160x90");
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  std::ifstream csv(dir / "out.csv");
  std::string line;
  std::getline(csv, line);
  std::vector<double> luminance;
  while (std::getline(csv, line)) {
    double i, x, y, z, red, green, blue;
    char c;
    std::istringstream s(line);
    s >> i >> c >> x >> c >> y >> c >> z >> c >> red >> c >> green >> c >> blue;
    luminance.push_back(0.2126 * red + 0.7152 * green + 0.0722 * blue);
  }
  REQUIRE(luminance.size() > 500);
  const std::size_t black = std::count(luminance.begin(), luminance.end(), 0.0);
  CHECK(black <= luminance.size() / 20);
  std::sort(luminance.begin(), luminance.end());
  const double median = luminance[luminance.size() / 2], brightest = luminance.back();
  CHECK(median > 1e-3 * brightest);
  CHECK(median < 0.5 * brightest);
  CHECK(fs::exists(dir / "out.png"));
}
