// tests/cli/test_cli_progress.cpp — progress on stderr: what the commands print while they work,
// that --quiet silences it and that stdout keeps only results.
//
// The binary runs with PRT_PROGRESS_INTERVAL=0 (a line on every update when stderr is not a
// terminal) so that short runs show their progress; the reporter's throttling itself is tested
// on the class with a file as its output (test_progress_reporter.cpp).
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "relight/image_io.h"
#include "support/test_data.h"
#include "support/text_lines.h"

namespace fs = std::filesystem;

namespace {

// A run of the CLI (cli_run.h) and how long it took.
struct Run : prt::test::cli::RunResult {
  double seconds = 0;
};

Run run(const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  Run r;
  static_cast<prt::test::cli::RunResult&>(r) = prt::test::cli::run(command);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::string prt_cli(const std::string& interval = "0") {
  return "PRT_PROGRESS_INTERVAL=" + interval + " " + std::string(PRT_CLI_PATH);
}

fs::path scratch(const std::string& name) {
  const fs::path dir = prt::test::output_path("cli_progress") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using prt::test::count_containing;
using prt::test::lines_of;

void write_env(const fs::path& path, int width, int height) {
  std::vector<float> pixels(static_cast<std::size_t>(3 * width * height));
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = 0.5f + 0.25f * static_cast<float>((i * 7919) % 13);
  prt::relight::write_image(path.string(), width, height, 3, pixels.data());
}

}  // namespace

TEST_CASE("cli progress: relight reports turntable frames i/N and image rows, --quiet silences") {
  const fs::path dir = scratch("turntable");
  const fs::path scene = dir / "quad.obj";
  std::ofstream(scene) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n";
  const fs::path prt_file = dir / "quad.prt", env = dir / "sky.hdr";
  REQUIRE(run(prt_cli() + " bake " + scene.string() + " -o " + prt_file.string() +
              " --samples 16 --quiet")
              .exit_code == 0);
  write_env(env, 32, 16);
  const std::string relight = " relight " + scene.string() + " " + prt_file.string() + " " +
                              env.string() + " --size 24x24 --spp 1 --turntable 4 -o ";

  const Run shown = run(prt_cli() + relight + (dir / "spin.png").string());
  INFO("stderr:\n" << shown.err);
  REQUIRE(shown.exit_code == 0);
  for (int i = 1; i <= 4; ++i)
    CHECK(count_containing(shown.err, "frame " + std::to_string(i) + "/4") == 1);
  CHECK(count_containing(shown.err, "4 frames done in") == 1);
  CHECK(shown.out.find("frame") == std::string::npos);  // stdout: the summary only
  CHECK(shown.out.find("wrote:") != std::string::npos);
  for (int i = 0; i < 4; ++i) CHECK(fs::exists(dir / ("spin_00" + std::to_string(i) + ".png")));

  const Run quiet = run(prt_cli() + relight + (dir / "hush.png").string() + " --quiet");
  REQUIRE(quiet.exit_code == 0);
  CHECK(quiet.err.empty());
  CHECK(quiet.out.empty());
  CHECK(fs::exists(dir / "hush_003.png"));

  // A single image reports its rows (24 of them here), then the usual summary on stdout.
  const Run single = run(prt_cli() + relight.substr(0, relight.find(" --turntable")) + " -o " +
                         (dir / "still.png").string());
  INFO("single image stderr:\n" << single.err);
  REQUIRE(single.exit_code == 0);
  CHECK(count_containing(single.err, "(rows): ") >= 1);
  CHECK(count_containing(single.err, "(rows): 24/24 done in") == 1);
  CHECK(single.out.find("wrote:") != std::string::npos);

  // With the default 5 s interval a run that takes less prints no progress at all.
  const Run quick = run(prt_cli("5") + relight + (dir / "quick.png").string());
  REQUIRE(quick.exit_code == 0);
  if (quick.seconds < 4.0) CHECK(quick.err.empty());
}

TEST_CASE("cli progress: a long env projection reports its progress and --quiet silences it") {
  const fs::path dir = scratch("env");
  struct Case {
    std::string name;
    int width, height, order;
  };
  // Lat-long takes the separable path (progress per row block, frequency and band), the
  // angular map the direct sum (progress per row).
  const Case cases[] = {{"sky_latlong.hdr", 600, 300, 300}, {"probe_angular.hdr", 48, 48, 24}};
  for (const Case& c : cases) {
    INFO(c.name);
    const fs::path env = dir / c.name;
    write_env(env, c.width, c.height);
    const std::string command = " env " + env.string() + " --order " + std::to_string(c.order);
    const Run shown = run(prt_cli() + command);
    INFO("stderr:\n" << shown.err);
    REQUIRE(shown.exit_code == 0);
    const std::string phase = "projecting " + env.string() + " to order " + std::to_string(c.order);
    CHECK(count_containing(shown.err, phase + ":") >= 3);
    CHECK(count_containing(shown.err, "% ") >= 2);  // percentages on the way
    CHECK(count_containing(shown.err, phase + ": done in") == 1);
    // stdout holds the coefficients only: 5 header lines and one line per coefficient.
    CHECK(lines_of(shown.out).size() == 5u + static_cast<std::size_t>(c.order) * c.order);

    const Run quiet = run(prt_cli() + command + " --quiet");
    REQUIRE(quiet.exit_code == 0);
    CHECK(quiet.err.find("projecting") == std::string::npos);
    CHECK(quiet.out == shown.out);
  }
}
