// tests/cli/test_cli_obscurance.cpp — `prt bake --ao --ao-distance D [--ao-falloff F]`: the
// refusals (one line, exit 2, nothing written), and the distance and falloff in the metadata that
// `prt info` prints; the options of `prt report --ssao` refused where they do not apply.
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

TEST_CASE("cli obscurance: --ao-distance refusals and the metadata prt info shows") {
  const fs::path dir = scratch("obscurance");
  fs::create_directory(dir / "out");
  const fs::path scene = dir / "quad.obj";
  std::ofstream(scene) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n";
  const std::string out = (dir / "out" / "x.prt").string();
  const std::string bake = prt_cli() + " bake " + scene.string() + " -o " + out + " ";
  const struct {
    std::string arguments, message;
  } refusals[] = {
      {"--ao-distance 1", "--ao-distance applies only to --ao"},
      {"--ao --ao-falloff linear", "--ao-falloff applies only to --ao-distance"},
      {"--ao --ao-distance 0", "--ao-distance: must be a finite length > 0"},
      {"--ao --ao-distance -1", "--ao-distance: must be a finite length > 0"},
      {"--ao --ao-distance nan", "--ao-distance: must be a finite length > 0"},
      {"--ao --ao-distance 1 --ao-falloff cubic", "--ao-falloff cubic: expected linear"},
      {"--ao --ao-distance 1 --auto", "--ao-distance does not apply to --auto"},
      {"--ao --ao-distance 1 --basis haar", "--ao does not apply to --basis haar"},
  };
  for (const auto& c : refusals) {
    INFO(c.arguments);
    const RunResult r = run(bake + c.arguments);
    require_one_line_error(r, c.message);
    CHECK(r.exit_code == 2);
  }
  CHECK(files_in(dir / "out").empty());

  const RunResult ok = run(bake +
                           "--ao --bent-normals --ao-distance 0.25 --ao-falloff exponential"
                           " --quiet");
  REQUIRE(ok.exit_code == 0);
  const RunResult info = run(prt_cli() + " info --json " + out);
  REQUIRE(info.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(info.out);
  CHECK(j["metadata"]["obscurance"]["distance"] == 0.25);
  CHECK(j["metadata"]["obscurance"]["falloff"] == "exponential");
  // A plain AO bake says nothing about obscurance.
  REQUIRE(run(bake + "--samples 16 --ao --quiet").exit_code == 0);
  const nlohmann::json plain = nlohmann::json::parse(run(prt_cli() + " info --json " + out).out);
  CHECK_FALSE(plain["metadata"].contains("obscurance"));
}

TEST_CASE("cli report --ssao: its options are refused without it, and bad values with it") {
  const fs::path dir = scratch("ssao_report_options");
  const std::string scene = (fs::path(PRT_SOURCE_DIR) / "data" / "demo.glb").string();
  const std::string out = (dir / "out").string();
  const std::string report = prt_cli() + " report ";
  const struct {
    std::string arguments, message;
  } refusals[] = {
      {scene + " x.hdr -o " + out + " --ssao-radius 1", "--ssao-radius applies only to --ssao"},
      {"--ssao -o " + out, "--ssao needs SCENE"},
      {"--ssao " + scene + " x.hdr -o " + out, "ENV 'x.hdr' does not apply to --ssao"},
      {"--ssao " + scene + " -o " + out + " --stability", "--stability does not apply to --ssao"},
      {"--ssao " + scene + " -o " + out + " --ssao-radius 0", "--ssao-radius: must be a finite"},
      {"--ssao " + scene + " -o " + out + " --ssao-samples 65", "--ssao-samples: must be in"},
      {"--ssao " + scene + " -o " + out + " --ssao-size 10x10", "--ssao-size 10x10: expected"},
      {"--ssao " + scene + " -o " + out + " --ao-distance -1", "--ao-distance: must be a finite"},
      {"--ssao " + scene + " -o " + out + " --ao-falloff cubic", "--ao-falloff cubic: expected"},
      {"--ssao --sun-study -o " + out, "--ssao and --sun-study exclude each other"},
  };
  for (const auto& c : refusals) {
    INFO(c.arguments);
    const RunResult r = run(report + c.arguments);
    require_one_line_error(r, c.message);
    CHECK(r.exit_code == 2);
  }
  CHECK_FALSE(fs::exists(out));
}
