// tests/cli/test_cli_options.cpp — messages that are true, options that do not apply refused
// by name, and one exit-status scheme (README "Exit status"): 0 success, 1 bad input or
// run-time failure, 2 the command line is wrong.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

namespace {

struct Quad {
  fs::path dir, scene, sh, haar, env;
};

// A quad baked as SH (order 3) and as Haar (cube 32: 6·32² = 6144 wavelet coefficients), and
// a constant sky.
Quad make_quad(const std::string& name) {
  Quad q;
  q.dir = scratch(name);
  q.scene = q.dir / "quad.obj";
  std::ofstream(q.scene) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n";
  q.sh = q.dir / "quad.prt";
  q.haar = q.dir / "quad_haar.prt";
  REQUIRE(run(prt_cli() + " bake " + q.scene.string() + " -o " + q.sh.string() +
              " --samples 16 --quiet")
              .exit_code == 0);
  REQUIRE(run(prt_cli() + " bake " + q.scene.string() + " -o " + q.haar.string() +
              " --basis haar --cube 32 --quiet")
              .exit_code == 0);
  q.env = q.dir / "sky.exr";
  const float c[3] = {1.0f, 0.9f, 0.8f};
  write_constant_env(q.env, 32, 16, c);
  return q;
}

struct Refusal {
  std::string arguments, message;
};

// Each refused with exit 2 and one line naming the option, writing nothing into dir/out.
void require_usage_refusals(const fs::path& dir, const std::vector<Refusal>& cases) {
  for (const Refusal& c : cases) {
    INFO("prt " << c.arguments);
    const RunResult r = run(prt_cli() + " " + c.arguments);
    require_one_line_error(r, c.message);
    CHECK(r.exit_code == 2);
  }
  CHECK(files_in(dir / "out").empty());
}

}  // namespace

TEST_CASE("cli options: relight's ringing advice is true for the window in use") {
  // An order-8 shadowed bake of the demo scene under a 64×32 map holding one texel 5·10⁵ times
  // the rest (row 23, column 40: 42° below the horizon, towards +X/+Z): SH ringing leaves
  // vertices negative with no window (measured 4,898 of 11,347).
  const fs::path dir = scratch("options_ringing");
  const std::string scene = prt::test::project_data("demo.glb").string();
  const fs::path file = dir / "demo8.prt";
  REQUIRE(
      run(prt_cli() + " bake " + scene + " -o " + file.string() + " --order 8 --samples 16 --quiet")
          .exit_code == 0);
  std::vector<float> pixels(3 * 64 * 32, 0.01f);
  for (int c = 0; c < 3; ++c) pixels[3 * (23 * 64 + 40) + c] = 5000.0f;
  const fs::path sun = dir / "sun.exr";
  prt::relight::write_image(sun.string(), 64, 32, 3, pixels.data());
  const std::string base = prt_cli() + " relight " + scene + " " + file.string() + " " +
                           sun.string() + " -o " + (dir / "img.png").string() +
                           " --size 16x16 --spp 1";
  const RunResult none = run(base + " --window none");
  REQUIRE(none.exit_code == 0);
  CHECK(none.out.find("negative radiance (SH ringing: try --window auto)") != std::string::npos);
  // The auto window is chosen on these vertices (relight/shown_window.h): none stays negative
  // (the irradiance-only choice it replaced left 97).
  const RunResult automatic = run(base + " --window auto");
  REQUIRE(automatic.exit_code == 0);
  CHECK(automatic.out.find("negative radiance") == std::string::npos);
  CHECK(automatic.out.find("the weakest that leaves none of the 11347 vertices negative") !=
        std::string::npos);
}

TEST_CASE("cli options: the default-albedo note is bake's, names bake's option, obeys --quiet") {
  // One triangle with no material: the loader gives it 0.8 grey. bake has --albedo; relight
  // does not (the albedo is folded into the file), so relight says nothing about it.
  const fs::path dir = scratch("options_albedo");
  const fs::path glb = dir / "tri.gltf";
  std::ofstream(glb)
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
      << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
      << R"("min":[0,0,-1],"max":[1,0,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
      << R"("buffers":[{"uri":"data:application/octet-stream;base64,)"
      << R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIC/","byteLength":36}]})";
  const fs::path file = dir / "tri.prt";
  const RunResult baked =
      run(prt_cli() + " bake " + glb.string() + " -o " + file.string() + " --samples 16");
  REQUIRE(baked.exit_code == 0);
  CHECK(baked.err.find("albedo 0.80 grey (--albedo r,g,b overrides it)") != std::string::npos);
  const RunResult quiet =
      run(prt_cli() + " bake " + glb.string() + " -o " + file.string() + " --samples 16 --quiet");
  REQUIRE(quiet.exit_code == 0);
  CHECK(quiet.err.empty());
  const fs::path env = dir / "sky.exr";
  const float c[3] = {1, 1, 1};
  write_constant_env(env, 32, 16, c);
  const RunResult relit = run(prt_cli() + " relight " + glb.string() + " " + file.string() + " " +
                              env.string() + " -o " + (dir / "img.png").string() + " --size 16x16");
  REQUIRE(relit.exit_code == 0);
  CHECK(relit.err.find("--albedo") == std::string::npos);
  CHECK(relit.err.empty());
}

TEST_CASE("cli options: --terms beyond the cube's coefficients is said, and reported truly") {
  const Quad q = make_quad("options_terms");
  const RunResult r =
      run(prt_cli() + " relight " + q.scene.string() + " " + q.haar.string() + " " +
          q.env.string() + " -o " + (q.dir / "img.png").string() + " --size 16x16 --terms 1000000");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("--terms 1000000 is more than the 6144 wavelet coefficients of the cube") !=
        std::string::npos);
  CHECK(r.out.find("all 6144 terms") != std::string::npos);
  CHECK(r.out.find("1000000 terms") == std::string::npos);
}

TEST_CASE("cli options: options that do not apply, or values out of range, are refused by name") {
  const Quad q = make_quad("options_refused");
  fs::create_directory(q.dir / "out");
  const std::string out = (q.dir / "out").string();
  const std::string scene = q.scene.string(), env = q.env.string();
  const std::string bake = "bake " + scene + " -o " + out + "/x.prt ";
  const std::string relight_sh = "relight " + scene + " " + q.sh.string() + " " + env + " -o " +
                                 out + "/img.png --size 16x16 ";
  const std::string relight_haar = "relight " + scene + " " + q.haar.string() + " " + env + " -o " +
                                   out + "/img.png --size 16x16 ";
  require_usage_refusals(
      q.dir,
      {
          {bake + "--auto --basis haar", "--auto does not apply to --basis haar"},
          {bake + "--basis haar --haar-terms 0", "--haar-terms 0: must be >= 1"},
          {bake + "--basis haar --cube 12", "--cube 12: must be a power of two"},
          {bake + "--basis haar --haar-threshold 2", "--haar-threshold: must be in [0, 1)"},
          {bake + "--basis haar --order 5", "--order does not apply to --basis haar"},
          {bake + "--basis haar --precision f16", "--precision does not apply to --basis haar"},
          {bake + "--basis haar --ao", "--ao does not apply to --basis haar"},
          {bake + "--cube 16", "--cube applies to --basis haar only"},
          {bake + "--env " + env, "--env applies to --auto only"},
          {bake + "--auto --samples 64", "--samples does not apply to --auto"},
          {bake + "--auto --env " + env + " --order 4", "--order does not apply to --auto --env"},
          {bake + "--transfer shadowed --bounces 2",
           "--bounces applies to --transfer interreflected only"},
          {bake + "--transfer shadowed --bounce-precision f16",
           "--bounce-precision applies to --transfer interreflected"},
          {bake + "--basis haar --transfer interreflected --bounce-precision f16",
           "--bounce-precision applies to --transfer interreflected"},
          {bake + "--transfer interreflected --bounce-precision f8",
           "--bounce-precision f8: expected f32 or f16"},
          {bake + "--transfer interreflected --bounces 3 --tolerance 0.01",
           "--tolerance applies to a solve to convergence"},
          {bake + "--samples 0", "--samples 0: must be in"},
          {relight_sh + "--terms -5", "--terms applies to Haar files"},
          {relight_sh + "--approx linear", "--approx applies to Haar files"},
          {relight_sh + "--exposure nan", "--exposure nan: must be a number of EV"},
          {relight_sh + "--exposure inf", "--exposure inf: must be a number of EV"},
          {"relight " + scene + " " + q.sh.string() + " " + env + " -o " + out +
               "/img.exr --exposure 1",
           "--exposure applies to .png output"},
          {relight_sh + "--window none --window-strength 2", "--window-strength needs a --window"},
          {relight_sh + "--window-strength 2", "--window-strength does not apply to --window auto"},
          {relight_sh + "--window auto --window-strength 2",
           "--window-strength does not apply to --window auto"},
          {relight_sh + "--window lanczos --window-strength -1",
           "--window-strength: must be a positive number"},
          {relight_sh + "--turntable -1", "--turntable -1: must be in 0..3600"},
          {relight_sh + "--spp 0", "--spp 0: must be in 1..16"},
          {"relight " + scene + " " + q.sh.string() + " " + env + " -o " + out +
               "/img.png --size 0x5",
           "--size 0x5: each side must be in 1..16384"},
          {relight_haar + "--terms -5", "--terms -5: must be >= 0"},
          {relight_haar + "--window lanczos", "--window applies to SH files"},
          {"env " + env + " --window-strength 1", "--window-strength needs a --window"},
          {"env " + env + " --order 0", "--order 0: must be in [1, "},
          {"env " + env + " --rotate 1,2", "--rotate 1,2: expected yaw,pitch,roll"},
          {"info " + q.sh.string() + " --json --csv", "excludes"},
          {"report --stability -o " + out + "/r --seed 3", "--seed does not apply to --stability"},
          {"report " + scene + " " + env + " --stability -o " + out + "/r",
           "--stability takes no SCENE or ENV"},
          {"report " + scene + " " + env + " -o " + out + "/r --ground-truth-budget nan",
           "--ground-truth-budget: must be a positive number"},
          {"report " + scene + " " + env + " -o " + out + "/r --quick --ground-truth-budget 100",
           "--ground-truth-budget: --quick caps it at 15 s"},
          {"report " + scene + " " + env + " -o " + out + "/r --emission a=1",
           "--emission needs --radiosity"},
          {"report --radiosity " + scene + " " + env + " -o " + out + "/r",
           "--radiosity takes a SCENE and no ENV"},
          {"report --radiosity " + scene + " -o " + out + "/r --haar-cubes 8",
           "--haar-cubes does not apply to --radiosity"},
          {"report --radiosity " + scene + " -o " + out + "/r --methods radial",
           "--methods: 'radial' is not one of analytic|rays|hemicube"},
          {"report --radiosity " + scene + " -o " + out + "/r --max-edges 0",
           "--max-edges: '0' is not a positive length"},
          {"make-sky -o " + out + "/s.hdr --sun-elevation 100", "--sun-elevation: must be in"},
          {"make-sky -o " + out + "/s.hdr --sun-radiance inf", "--sun-radiance: must be a finite"},
          {"make-sky -o " + out + "/s.hdr --width 100 --height 10", "width = 2 x height"},
          {"make-scene -o " + out + "/scene.gltf", "expected a binary glTF (.glb)"},
      });
}

TEST_CASE("cli options: one exit-status scheme, and prt --version") {
  const fs::path dir = scratch("options_exit");
  SECTION("a parse error of any subcommand is a usage error: 2, one line, with the way to help") {
    for (const std::string& arguments :
         {std::string("relight a b c -o x.png --no-such-option"), std::string("bake"),
          std::string("env --order three x.hdr"), std::string("info"), std::string(""),
          std::string("no-such-command")}) {
      INFO("prt " << arguments);
      const RunResult r = run(prt_cli() + " " + arguments);
      CHECK(r.exit_code == 2);
      CHECK(line_count(r.err) == 1);
      CHECK(r.err.find("--help") != std::string::npos);
    }
  }
  SECTION("a bad input file is 1") {
    const RunResult r = run(prt_cli() + " env " + (dir / "missing.hdr").string());
    require_one_line_error(r, "missing.hdr");
    CHECK(r.exit_code == 1);
  }
  SECTION("--version prints the project's version and exits 0") {
    const RunResult r = run(prt_cli() + " --version");
    CHECK(r.exit_code == 0);
    CHECK(r.out == std::string("prt ") + PRT_PROJECT_VERSION + "\n");
  }
}
