// tests/cli/test_cli_environment.cpp — one set of checks for environment maps, whichever command
// reads them (relight/environment_input.h, sh/env_check.h): the same refusals and the same
// warnings from prt env, relight, bake --auto --env and report; negative channels clamped per
// channel (never a silent all-zero projection); maps mostly NaN/Inf refused.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "sh/constants.h"

using namespace prt::test::cli;

namespace {

struct Baked {
  fs::path dir, scene, transfer;
};

// A quad baked at order 3 (16 samples): enough for relight to read a map at order 3.
Baked bake_quad(const std::string& name) {
  Baked b;
  b.dir = scratch(name);
  b.scene = b.dir / "quad.obj";
  std::ofstream(b.scene) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n";
  b.transfer = b.dir / "quad.prt";
  REQUIRE(run(prt_cli() + " bake " + b.scene.string() + " -o " + b.transfer.string() +
              " --samples 16 --quiet")
              .exit_code == 0);
  return b;
}

fs::path write_map(const fs::path& path, int width, int height,
                   const std::vector<float>& rgb_per_texel_or_constant) {
  std::vector<float> pixels(3 * static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = rgb_per_texel_or_constant.size() == 3 ? rgb_per_texel_or_constant[i % 3]
                                                      : rgb_per_texel_or_constant[i];
  prt::relight::write_image(path.string(), width, height, 3, pixels.data());
  return path;
}

std::string relight(const Baked& b, const fs::path& map, const fs::path& out) {
  return prt_cli() + " relight " + b.scene.string() + " " + b.transfer.string() + " " +
         map.string() + " -o " + out.string() + " --size 16x16";
}

// The message after "prt SUBCOMMAND: " (or the whole line).
std::string message_of(const std::string& line) {
  const std::size_t at = line.find(": ");
  return at == std::string::npos ? line : line.substr(at + 2);
}

}  // namespace

TEST_CASE("cli environment: a 1x1 map is far too small for order 3 in env and relight alike") {
  const Baked b = bake_quad("env_one_texel");
  const fs::path map = write_map(b.dir / "one.exr", 1, 1, {1, 1, 1});
  const RunResult env = run(prt_cli() + " env " + map.string());
  require_one_line_error(env, "one.exr: 1x1 is far too small for order 3");
  const fs::path png = b.dir / "out.png";
  const RunResult relit = run(relight(b, map, png));
  require_one_line_error(relit, "one.exr: 1x1 is far too small for order 3");
  CHECK(env.exit_code == 1);
  CHECK(relit.exit_code == 1);
  CHECK(message_of(env.err) == message_of(relit.err));  // one check, one message
  CHECK_FALSE(fs::exists(png));
}

TEST_CASE("cli environment: a 2x1 map gets the same aliasing warning from env and relight") {
  const Baked b = bake_quad("env_two_texels");
  const fs::path map = write_map(b.dir / "two.exr", 2, 1, {1, 1, 1});
  const RunResult env = run(prt_cli() + " env " + map.string());
  const RunResult relit = run(relight(b, map, b.dir / "out.png") + " --quiet");
  REQUIRE(env.exit_code == 0);
  REQUIRE(relit.exit_code == 0);
  const std::string warning =
      "two.exr: warning: 2x1 resolves bands up to about l = 1; order 3 asks for l = 2 (aliasing)";
  CHECK(env.err.find(warning) != std::string::npos);
  CHECK(relit.err.find(warning) != std::string::npos);  // --quiet does not hide a warning
}

TEST_CASE("cli environment: negative channels are clamped per channel, never zeroing the map") {
  // Every texel (1, 0.5, -0.25): the old policy skipped every texel and printed zeros with exit
  // 0. Clamped per channel the map is the constant (1, 0.5, 0), whose L00 is c·√(4π) exactly
  // (the solid angles sum to 4π); the warning gives the count, 64×32 = 2048.
  const fs::path dir = scratch("env_negative");
  const fs::path map = write_map(dir / "neg.exr", 64, 32, {1.0f, 0.5f, -0.25f});
  const RunResult r = run(prt_cli() + " env " + map.string() + " --json");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("neg.exr: warning: 2048 texels have a negative channel: clamped to 0") !=
        std::string::npos);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["clamped_texels"]["negative"] == 2048);
  const double root4pi = std::sqrt(4.0 * prt::sh::kPi);
  CHECK(j["coefficients"][0][0].get<double>() == Approx(root4pi).epsilon(1e-9));
  CHECK(j["coefficients"][0][1].get<double>() == Approx(0.5 * root4pi).epsilon(1e-9));
  CHECK(j["coefficients"][0][2].get<double>() == 0.0);
  // --strict refuses it instead, in one line.
  require_one_line_error(run(prt_cli() + " env " + map.string() + " --strict"),
                         "neg.exr: 2048 texels are NaN, Inf or negative");
}

TEST_CASE("cli environment: a map mostly NaN is refused by every command that reads maps") {
  // NaN in the top 20 of 32 rows: those rows hold (1 − cos(π·20/32))/2 = 69.1% of the sphere.
  const Baked b = bake_quad("env_mostly_nan");
  std::vector<float> pixels(3 * 64 * 32, 1.0f);
  for (int i = 0; i < 64 * 20; ++i) pixels[3 * i] = std::nanf("");
  const fs::path map = write_map(b.dir / "nan.exr", 64, 32, pixels);
  const std::string message = "nan.exr: NaN or Inf over 69.1% of the sphere (1280 texels)";
  const fs::path out = b.dir / "out";
  fs::create_directory(out);
  require_one_line_error(run(prt_cli() + " env " + map.string()), message);
  require_one_line_error(run(relight(b, map, out / "img.png")), message);
  require_one_line_error(run(prt_cli() + " bake " + b.scene.string() + " -o " +
                             (out / "auto.prt").string() + " --auto --env " + map.string()),
                         message);
  require_one_line_error(run(prt_cli() + " report " + b.scene.string() + " " + map.string() +
                             " -o " + (out / "report").string() + " --quick"),
                         message);
  CHECK(files_in(out).empty());  // nothing written, not even report's folder
}

TEST_CASE("cli environment: a few NaN texels are taken as black with a warning") {
  const fs::path dir = scratch("env_few_nan");
  std::vector<float> pixels(3 * 64 * 32, 1.0f);
  pixels[3 * 100 + 1] = std::nanf("");
  pixels[3 * 200] = INFINITY;
  const fs::path map = write_map(dir / "few.exr", 64, 32, pixels);
  const RunResult r = run(prt_cli() + " env " + map.string() + " --json");
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("few.exr: warning: 2 texels are NaN or Inf (") != std::string::npos);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["skipped_texels"]["nan"] == 1);
  CHECK(j["skipped_texels"]["inf"] == 1);
  CHECK(j["warnings"].size() == 1u);
  for (const auto& rgb : j["coefficients"])
    for (const auto& v : rgb) CHECK(std::isfinite(v.get<double>()));
}

TEST_CASE("cli environment: a black map is said to be black, not lit silently") {
  const fs::path dir = scratch("env_black");
  const fs::path map = write_map(dir / "black.exr", 16, 8, {0.0f, -1.0f, 0.0f});
  const RunResult r = run(prt_cli() + " env " + map.string());
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("black.exr: warning: the map is black") != std::string::npos);
}
