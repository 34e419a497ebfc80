// Materials on the command line: `prt make-scene --scene glossy` writes the glossy test scene,
// `prt info SCENE` lists its materials (and what --material overrides make of them), and bad
// --material values are refused in one line, before any output is written.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

TEST_CASE("prt make-scene --scene glossy, then prt info lists its materials", "[cli][materials]") {
  const fs::path dir = scratch("glossy_scene");
  const std::string scene = (dir / "glossy.glb").string();
  const RunResult made = run(prt_cli() + " make-scene --scene glossy -o " + scene);
  INFO(made.err);
  REQUIRE(made.exit_code == 0);
  CHECK(made.out.find("brushed_disc (material brushed_steel): gltf(base 0.9,0.9,0.88, metallic 1, "
                      "alpha 0.684x0.122") != std::string::npos);

  const RunResult info = run(prt_cli() + " info " + scene);
  INFO(info.err);
  REQUIRE(info.exit_code == 0);
  CHECK(info.out.find("tangents from the file") != std::string::npos);
  CHECK(info.out.find("floor/0 (material floor): lambert(0.6)") != std::string::npos);
  CHECK(info.out.find("glossy_sphere/0 (material glossy_red): gltf(base 0.7,0.08,0.06, metallic 0, "
                      "alpha 0.09x0.09, F0 0.04)") != std::string::npos);
  CHECK(info.out.find("gold_box/0 (material rough_gold): gltf(base 0.95,0.74,0.33, metallic 1, "
                      "alpha 0.25x0.25, F0 0.04)") != std::string::npos);

  const RunResult overridden =
      run(prt_cli() + " info " + scene +
          " --material rough_gold=ward:rho_s=0.5,ax=0.3,ay=0.1 --material floor=lambert:kd=0.3");
  INFO(overridden.err);
  REQUIRE(overridden.exit_code == 0);
  CHECK(overridden.out.find("gold_box/0 (material rough_gold): ward(rho_d 0, rho_s 0.5, alpha "
                            "0.3x0.1)") != std::string::npos);
  CHECK(overridden.out.find("floor/0 (material floor): lambert(0.3)") != std::string::npos);
}

TEST_CASE("bad --material values are one-line errors naming the option", "[cli][materials]") {
  const fs::path dir = scratch("bad_material");
  const std::string scene = prt::test::project_data("demo.glb").string();
  const std::string out = (dir / "out.prt").string();
  const std::vector<std::string> values = {
      "red_wall=ggx:roughness=0", "red_wall=ggx:alpha=nan", "red_wall=blinn-phong:ks=0.3,s=-2",
      "red_wall=velvet:alpha=0.2", "red_wall=merl:" + (dir / "missing.binary").string()};
  for (const std::string& value : values) {
    const RunResult r = run(prt_cli() + " bake " + scene + " -o " + out +
                            " --samples 16 --material '" + value + "'");
    INFO(value << ": " << r.err);
    require_one_line_error(r, "--material " + value + ": ");
    CHECK(r.exit_code == 2);
  }
  // A well-formed override naming a material the scene does not have.
  const RunResult unknown = run(prt_cli() + " bake " + scene + " -o " + out +
                                " --samples 16 --material chrome=ggx:alpha=0.1");
  require_one_line_error(unknown, "no material or primitive named 'chrome'");
  CHECK(files_in(dir).empty());
}
