// tests/cli/test_cli.cpp — the `prt` executable as a user meets it.
//
// Runs the built binary (PRT_CLI_PATH) in a shell and checks what the README promises:
//   * bad input gets ONE line on stderr naming the file and the problem, a non-zero exit, and
//     no output file left behind (not even a temporary);
//   * good input works end to end (env → bake → info → relight);
//   * the engine example (docs/ENGINE.md, built against prt::prt alone) computes the same
//     radiance as `prt relight --csv` for the same file and lighting.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "prt/haar/transform.h"
#include "relight/image_io.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "support/test_data.h"

namespace fs = std::filesystem;

using namespace prt::test::cli;

TEST_CASE("cli: prt env refuses bad input with one line naming the file") {
  const fs::path dir = scratch("env_errors");
  SECTION("missing file") {
    const std::string missing = (dir / "no_such_map.hdr").string();
    require_one_line_error(run(prt_cli() + " env " + missing), "no_such_map.hdr");
  }
  SECTION("not an image") {
    const fs::path junk = dir / "junk.hdr";
    std::ofstream(junk) << "this is not an image";
    require_one_line_error(run(prt_cli() + " env " + junk.string()), "junk.hdr");
  }
  SECTION("aspect ratio that fits no layout") {
    const fs::path odd = dir / "odd.exr";
    const float c[3] = {1, 1, 1};
    write_constant_env(odd, 5, 3, c);
    require_one_line_error(run(prt_cli() + " env " + odd.string()), "odd.exr");
  }
  SECTION("absurd order") {
    const fs::path ok = dir / "ok.exr";
    const float c[3] = {1, 1, 1};
    write_constant_env(ok, 16, 8, c);
    require_one_line_error(run(prt_cli() + " env " + ok.string() + " --order 100000"), "--order");
  }
}

TEST_CASE("cli: prt env counts NaN and negative texels, and --strict refuses them") {
  const fs::path dir = scratch("env_nan");
  std::vector<float> pixels(3 * 16 * 8, 1.0f);
  pixels[0] = std::nanf("");
  pixels[4] = -1.0f;
  const fs::path map = dir / "bad_texels.exr";
  prt::relight::write_image(map.string(), 16, 8, 3, pixels.data());

  const RunResult lenient = run(prt_cli() + " env " + map.string() + " --json");
  REQUIRE(lenient.exit_code == 0);
  const auto j = nlohmann::json::parse(lenient.out);
  CHECK(j["skipped_texels"]["nan"] == 1);
  CHECK(j["clamped_texels"]["negative"] == 1);  // clamped per channel, no longer skipped
  for (const auto& rgb : j["coefficients"])
    for (const auto& v : rgb) CHECK(std::isfinite(v.get<double>()));

  require_one_line_error(run(prt_cli() + " env " + map.string() + " --strict"), "bad_texels.exr");
}

TEST_CASE("cli: prt env --json states the convention and the coefficients") {
  const fs::path dir = scratch("env_json");
  const fs::path map = dir / "const.exr";
  const float c[3] = {0.25f, 0.5f, 1.0f};
  write_constant_env(map, 64, 32, c);
  const RunResult r = run(prt_cli() + " env " + map.string() + " --order 4 --json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["order"] == 4);
  CHECK(j["layout"] == "latlong");
  CHECK(j["basis"].get<std::string>().find("no Condon-Shortley") != std::string::npos);
  CHECK(j["basis"] == prt::sh::kBasisConvention);
  REQUIRE(j["coefficients"].size() == 16);
  // A constant radiance c projects to L00 = c·√(4π) (exact quadrature of a constant).
  const double root4pi = std::sqrt(4.0 * prt::sh::kPi);
  for (int ch = 0; ch < 3; ++ch)
    CHECK(j["coefficients"][0][ch].get<double>() == Approx(c[ch] * root4pi).epsilon(1e-6));
}

TEST_CASE("cli: prt bake refuses bad scenes and options, leaving nothing behind") {
  const fs::path dir = scratch("bake_errors");
  const fs::path out_dir = dir / "out";
  fs::create_directories(out_dir);
  const std::string out = (out_dir / "x.prt").string();
  SECTION("a file that does not parse") {
    const fs::path broken = dir / "broken.gltf";
    std::ofstream(broken) << "{ not json";
    require_one_line_error(run(prt_cli() + " bake " + broken.string() + " -o " + out),
                           "broken.gltf");
  }
  SECTION("NaN position") {
    const fs::path obj = dir / "nan.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 nan 1\nf 1 2 3\n";
    require_one_line_error(run(prt_cli() + " bake " + obj.string() + " -o " + out), "nan.obj");
  }
  SECTION("index out of range") {
    const fs::path obj = dir / "range.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
    require_one_line_error(run(prt_cli() + " bake " + obj.string() + " -o " + out), "range.obj");
  }
  SECTION("empty scene") {
    const fs::path obj = dir / "empty.obj";
    std::ofstream(obj) << "# nothing\n";
    require_one_line_error(run(prt_cli() + " bake " + obj.string() + " -o " + out), "empty.obj");
  }
  SECTION("albedo of 1 or more") {
    require_one_line_error(run(prt_cli() + " bake " + prt::test::project_data("demo.glb").string() +
                               " -o " + out + " --albedo 1,1,1"),
                           "albedo");
  }
  SECTION("unwritable output") {
    require_one_line_error(run(prt_cli() + " bake " + prt::test::project_data("demo.glb").string() +
                               " -o /nonexistent_dir/x.prt --samples 16"),
                           "x.prt");
  }
  CHECK(files_in(out_dir).empty());
}

TEST_CASE("cli: prt report refuses a bad --auto-tolerances list before any work") {
  const fs::path dir = scratch("report_errors");
  const fs::path out_dir = dir / "out";
  for (const char* bad : {"2", "0", "x", "0.05,", "0.01,-1"}) {
    INFO("--auto-tolerances " << bad);
    require_one_line_error(
        run(prt_cli() + " report " + prt::test::project_data("demo.glb").string() + " " +
            prt::test::project_data("sky.hdr").string() + " -o " + out_dir.string() +
            " --quick --auto-tolerances '" + bad + "'"),
        "--auto-tolerances");
    CHECK_FALSE(fs::exists(out_dir));
  }
}

TEST_CASE("cli: prt info and prt relight refuse corrupt and mismatched files") {
  const fs::path dir = scratch("relight_errors");
  const fs::path scene = dir / "quad.obj";
  std::ofstream(scene) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n";
  const fs::path other = dir / "other.obj";
  std::ofstream(other) << "v 0 0 0\nv 2 0 0\nv 2 0 -2\nv 0 0 -2\nf 1 2 3\nf 1 3 4\n";
  const fs::path prt_file = dir / "quad.prt";
  REQUIRE(run(prt_cli() + " bake " + scene.string() + " -o " + prt_file.string() +
              " --samples 16 --quiet")
              .exit_code == 0);
  const fs::path env = dir / "sky.exr";
  const float c[3] = {1, 1, 1};
  write_constant_env(env, 32, 16, c);

  const fs::path out_dir = dir / "out";
  fs::create_directories(out_dir);
  const std::string png = (out_dir / "img.png").string();

  SECTION("mismatched geometry") {
    require_one_line_error(run(prt_cli() + " relight " + other.string() + " " + prt_file.string() +
                               " " + env.string() + " -o " + png + " --size 32x32"),
                           "quad.prt");
  }
  SECTION("a flipped byte fails the checksum") {
    std::string bytes = slurp(prt_file);
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5a);
    const fs::path corrupt = dir / "corrupt.prt";
    std::ofstream(corrupt, std::ios::binary) << bytes;
    require_one_line_error(run(prt_cli() + " info " + corrupt.string()), "corrupt.prt");
    require_one_line_error(run(prt_cli() + " relight " + scene.string() + " " + corrupt.string() +
                               " " + env.string() + " -o " + png + " --size 32x32"),
                           "corrupt.prt");
  }
  SECTION("a truncated file") {
    const std::string bytes = slurp(prt_file);
    const fs::path cut = dir / "cut.prt";
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    require_one_line_error(run(prt_cli() + " info " + cut.string()), "cut.prt");
  }
  CHECK(files_in(out_dir).empty());
}

TEST_CASE("cli: bake, info and relight work end to end on the bundled scene") {
  const fs::path dir = scratch("end_to_end");
  const std::string scene = prt::test::project_data("demo.glb").string();
  const std::string sky = prt::test::project_data("sky.hdr").string();
  const fs::path prt_file = dir / "demo.prt";
  REQUIRE(run(prt_cli() + " bake " + scene + " -o " + prt_file.string() +
              " --samples 32 --order 3 --ao --quiet")
              .exit_code == 0);

  const RunResult info = run(prt_cli() + " info " + prt_file.string() + " --json");
  REQUIRE(info.exit_code == 0);
  const auto j = nlohmann::json::parse(info.out);
  CHECK(j.dump().find("shadowed") != std::string::npos);
  // One convention text: prt info prints the one the baker wrote into the file's metadata.
  CHECK(j["sh_basis"] == prt::sh::kBasisConvention);
  CHECK(j["metadata"]["sh_basis"] == prt::sh::kBasisConvention);

  const fs::path png = dir / "demo.png", csv = dir / "demo.csv", glb = dir / "demo_colors.glb";
  const RunResult relit = run(prt_cli() + " relight " + scene + " " + prt_file.string() + " " +
                              sky + " -o " + png.string() + " --size 96x54 --spp 1 --csv " +
                              csv.string() + " --vertex-colors " + glb.string() + " --quiet");
  INFO(relit.err);
  REQUIRE(relit.exit_code == 0);
  CHECK(fs::file_size(png) > 1000);
  CHECK(fs::file_size(glb) > 1000);
  // One CSV row per vertex (plus the header): the demo scene's 11,347 vertices.
  CHECK(line_count(slurp(csv)) == 11347 + 1);
}

TEST_CASE("cli: the engine example computes what prt relight --csv computes") {
  // The engine example (docs/ENGINE.md) loads a file, projects a 64×32 constant lat-long sky
  // of radiance (0.5, 0.7, 1.0), turns it by yaw 30° and applies the auto window, then prints
  // vertex 0's radiance with 4 decimals. The CLI does the same from an image file. Both use
  // prt::prt's kernel on the same file, so they must agree to the printed precision.
  const fs::path dir = scratch("engine_vs_cli");
  const std::string scene = prt::test::project_data("demo.glb").string();
  const fs::path prt_file = dir / "demo.prt";
  REQUIRE(run(prt_cli() + " bake " + scene + " -o " + prt_file.string() +
              " --samples 32 --order 3 --quiet")
              .exit_code == 0);
  const fs::path env = dir / "sky.exr";
  const float sky[3] = {0.5f, 0.7f, 1.0f};
  write_constant_env(env, 64, 32, sky);
  const fs::path csv = dir / "relit.csv";
  REQUIRE(run(prt_cli() + " relight " + scene + " " + prt_file.string() + " " + env.string() +
              " -o " + (dir / "img.exr").string() + " --size 16x16 --spp 1 --rotate 30,0,0" +
              " --window auto --csv " + csv.string() + " --quiet")
              .exit_code == 0);

  const RunResult example = run(std::string(PRT_ENGINE_EXAMPLE_PATH) + " " + prt_file.string());
  INFO(example.err);
  REQUIRE(example.exit_code == 0);
  // "... vertex 0: RGB r g b"
  const std::size_t at = example.out.find("RGB");
  REQUIRE(at != std::string::npos);
  double engine_rgb[3];
  std::istringstream(example.out.substr(at + 3)) >> engine_rgb[0] >> engine_rgb[1] >> engine_rgb[2];

  std::istringstream rows(slurp(csv));
  std::string header, row0;
  std::getline(rows, header);
  std::getline(rows, row0);
  for (char& ch : row0)
    if (ch == ',') ch = ' ';
  double index, x, y, z, cli_rgb[3];
  std::istringstream(row0) >> index >> x >> y >> z >> cli_rgb[0] >> cli_rgb[1] >> cli_rgb[2];
  REQUIRE(index == 0);
  for (int c = 0; c < 3; ++c) {
    // 5e-5: half a unit in the example's 4th printed decimal.
    CHECK(engine_rgb[c] == Approx(cli_rgb[c]).margin(5e-5));
    CHECK(engine_rgb[c] > 0.01);  // the vertex is lit, so agreement is not 0 == 0
  }
}

TEST_CASE("cli: prt bake --auto says what it left out, and the file records it") {
  const fs::path dir = scratch("auto");
  const std::string scene = prt::test::project_data("demo.glb").string();
  const std::string sky = prt::test::project_data("sky.hdr").string();
  const fs::path prt_file = dir / "demo_auto.prt";
  const RunResult r = run(prt_cli() + " bake " + scene + " -o " + prt_file.string() +
                          " --auto --tolerance 0.02 --env " + sky);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  // The summary names the prediction and its parts, and each omission on its own line.
  CHECK(r.out.find("predicted error") != std::string::npos);
  CHECK(r.out.find("tolerance 0.02") != std::string::npos);
  CHECK(r.out.find("left out: shadow rays for") != std::string::npos);
  CHECK(r.out.find("left out: colour channels 2 and 3") == std::string::npos);  // demo is coloured
  const RunResult info = run(prt_cli() + " info " + prt_file.string() + " --json");
  REQUIRE(info.exit_code == 0);
  const auto j = nlohmann::json::parse(info.out);
  const std::string meta = j.dump();
  CHECK(meta.find("predicted_error") != std::string::npos);
  CHECK(meta.find("error_scope") != std::string::npos);
  // A bad tolerance is refused in one line, leaving nothing behind.
  const fs::path bad = dir / "bad.prt";
  require_one_line_error(
      run(prt_cli() + " bake " + scene + " -o " + bad.string() + " --auto --tolerance 2"),
      "tolerance");
  CHECK_FALSE(fs::exists(bad));
}

TEST_CASE("cli: prt info describes a Haar file, and its CSV holds every stored term") {
  // One reader for every kind (prt/formats/coefficient_file.h): a Haar bake is described with its
  // cube size, and --csv expands the per-wavelet vertex lists into dense rows: with unquantised
  // values (--haar-bits 32, every non-zero term kept) the non-zero cells are exactly the stored
  // entries × channels.
  const fs::path dir = scratch("info_haar");
  const fs::path file = dir / "demo.prt";
  const std::string scene = (fs::path(PRT_SOURCE_DIR) / "data" / "demo.glb").string();
  RunResult baked = run(prt_cli() + " bake " + scene + " -o " + file.string() +
                        " --basis haar --cube 8 --haar-bits 32 --quiet");
  REQUIRE(baked.exit_code == 0);
  RunResult json = run(prt_cli() + " info " + file.string() + " --json");
  REQUIRE(json.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["kind"] == "haar");
  CHECK(j["cube_size"] == 8);
  CHECK(j["coefficients_per_channel"] == 384);
  CHECK(j["haar_basis"] == prt::kHaarBasisConvention);
  RunResult text = run(prt_cli() + " info " + file.string());
  REQUIRE(text.exit_code == 0);
  CHECK(text.out.find("cube size     8") != std::string::npos);
  RunResult csv = run(prt_cli() + " info " + file.string() + " --csv");
  REQUIRE(csv.exit_code == 0);
  std::istringstream lines(csv.out);
  std::string line;
  std::getline(lines, line);
  CHECK(line.find(",w0_0,") != std::string::npos);
  const uint64_t channels = j["channels"].get<uint64_t>();
  CHECK(line.find(",w" + std::to_string(channels - 1) + "_383") != std::string::npos);
  uint64_t nonzero = 0, rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    std::istringstream cells(line);
    std::string cell;
    for (int column = 0; std::getline(cells, cell, ','); ++column)
      if (column >= 7 && std::stod(cell) != 0.0) ++nonzero;
  }
  CHECK(rows == j["vertices"].get<uint64_t>());
  CHECK(nonzero == j["stored_entries"].get<uint64_t>() * channels);
}
