// tests/cli/test_cli_glossy.cpp — `prt bake --glossy` and `prt info` on glossy transfer files:
// a bake end to end, options that do not apply, and damaged files refused with one line.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "support/test_data.h"

namespace fs = std::filesystem;

using namespace prt::test::cli;

TEST_CASE("cli: prt bake --glossy writes a glossy file that prt info describes") {
  const fs::path dir = scratch("glossy_bake");
  const fs::path file = dir / "demo.prtg";
  const std::string scene = (fs::path(PRT_SOURCE_DIR) / "data" / "demo.glb").string();
  RunResult baked = run(prt_cli() + " bake " + scene + " --glossy -o " + file.string() +
                        " --order 3 --samples 16 --bounces 1");
  REQUIRE(baked.exit_code == 0);
  CHECK(baked.out.find("baked glossy interreflected transfer") != std::string::npos);
  RunResult json = run(prt_cli() + " info " + file.string() + " --json");
  REQUIRE(json.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["kind"] == "glossy interreflected");
  CHECK(j["order"] == 3);
  CHECK(j["matrix"] == "9x9");
  CHECK(j["channels"] == 3);  // the demo's red and green walls
  CHECK(j["metadata"]["interreflection"]["bounces"] == 1);
  uint64_t users = 0;
  for (const auto& m : j["materials"]) users += m["vertices"].get<uint64_t>();
  CHECK(users == j["vertices"].get<uint64_t>());
  RunResult csv = run(prt_cli() + " info " + file.string() + " --csv");
  REQUIRE(csv.exit_code == 0);
  CHECK(line_count(csv.out) == j["vertices"].get<uint64_t>() + 1);
  CHECK(csv.out.find(",m2_8_8\n") != std::string::npos);
  // Shadowed by default: one channel, no interreflection.
  RunResult shadowed = run(prt_cli() + " bake " + scene + " --glossy -o " + file.string() +
                           " --order 2 --samples 16 --quiet");
  REQUIRE(shadowed.exit_code == 0);
  CHECK(shadowed.out.empty());
  RunResult text = run(prt_cli() + " info " + file.string());
  CHECK(text.out.find("glossy shadowed") != std::string::npos);
  CHECK(text.out.find("channels      1") != std::string::npos);
}

TEST_CASE("cli: prt bake --glossy refuses what does not apply, prt info refuses damaged files") {
  const fs::path dir = scratch("glossy_refusals");
  const std::string scene = (fs::path(PRT_SOURCE_DIR) / "data" / "demo.glb").string();
  const std::string out = (dir / "x.prtg").string();
  for (const std::string& extra :
       {std::string("--ao"), std::string("--order 11"), std::string("--transfer unshadowed"),
        std::string("--bounces 2 --tolerance 0.01"), std::string("--auto"),
        std::string("--transfer shadowed --bounce-precision f16"),
        std::string("--bounces 1 --bounce-precision f64")}) {
    RunResult r = run(prt_cli() + " bake " + scene + " --glossy -o " + out + " " + extra);
    INFO(extra << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
  }
  RunResult wrong_ext =
      run(prt_cli() + " bake " + scene + " --glossy -o " + (dir / "x.prt").string());
  CHECK(wrong_ext.exit_code == 2);
  CHECK(wrong_ext.err.find(".prtg") != std::string::npos);
  CHECK(files_in(dir).empty());
  // A good file, then cut short: refused with one line naming it.
  REQUIRE(
      run(prt_cli() + " bake " + scene + " --glossy -o " + out + " --order 2 --samples 16 --quiet")
          .exit_code == 0);
  const std::string bytes = slurp(out);
  const fs::path cut = dir / "cut.prtg";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
  RunResult r = run(prt_cli() + " info " + cut.string());
  CHECK(r.exit_code == 1);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(cut.string() + ": truncated") != std::string::npos);
}
