// Relighting the emitters as a user runs it: `prt radiosity --per-emitter` writes the responses;
// `prt relight RESPONSES.prte` with the stored colours reproduces the plain solve, and with a
// doubled emitter adds exactly that emitter's contribution once more; `prt relight SCENE
// FILE.prt ENV --max-edge L --emitters RESPONSES` equals the sum of the two separate relights;
// unknown names, bad colours, corrupt and truncated files and mismatched geometry are refused
// with one line and nothing written; `prt info` describes the file.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"
#include "support/test_data.h"

namespace fs = std::filesystem;

namespace {

using prt::test::cli::line_count;
using prt::test::cli::RunResult;
using prt::test::cli::slurp;

fs::path scratch(const std::string& name) {
  return prt::test::cli::scratch("emitter_cli/" + name);
}

// Runs `prt ARGS` as a user does (tests/cli/cli_test_support.h).
RunResult prt_run(const std::string& args) {
  return prt::test::cli::run(prt::test::cli::prt_cli() + " " + args);
}

// A room open at the front (z = 0), 1 unit wide: white walls (Kd 0.7 0.6 0.5), a lamp under the
// ceiling (Ke 5 5 5) and a panel low on the back wall (Ke 0.5 1 2): two emitting materials.
fs::path write_room(const fs::path& dir) {
  std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.7 0.6 0.5\n"
                                     "newmtl lamp\nKd 0.5 0.5 0.5\nKe 5 5 5\n"
                                     "newmtl panel\nKd 0.3 0.3 0.3\nKe 0.5 1 2\n";
  std::ofstream obj(dir / "room.obj");
  obj << "mtllib room.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
         "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"
         "v 0.2 0.1 0.99\nv 0.2 0.3 0.99\nv 0.6 0.3 0.99\nv 0.6 0.1 0.99\n"
         "o walls\nusemtl white\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\n"
         "o lamp\nusemtl lamp\nf 9 10 11 12\n"      // facing -y
         "o panel\nusemtl panel\nf 13 14 15 16\n";  // facing -z
  return dir / "room.obj";
}

// The r,g,b columns (5–7) of a prt CSV, one value per vertex and channel.
std::vector<double> csv_rgb(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<double> rgb;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string cell;
    for (int column = 0; std::getline(s, cell, ','); ++column)
      if (column >= 4 && column <= 6) rgb.push_back(std::stod(cell));
  }
  return rgb;
}

// max |a − b| / max |b|.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  REQUIRE_FALSE(a.empty());
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return worst / scale;
}

void check_refused(const fs::path& dir, const std::string& args, const std::string& expected) {
  const RunResult r = prt_run(args);
  INFO(args << "\nstderr: " << r.err);
  CHECK(r.exit_code != 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(expected) != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "refused.csv"));
  CHECK_FALSE(fs::exists(dir / "refused.exr"));
}

constexpr const char* kSmall = " --size 32x24 --spp 1 --quiet";

}  // namespace

TEST_CASE("prt relight of emitter responses: stored colours reproduce the solve, doubling adds",
          "[radiosity][emitters][cli]") {
  const fs::path dir = scratch("responses");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  RunResult r = prt_run("radiosity " + room + " --max-edge 0.25 --tolerance 1e-9 --per-emitter " +
                        d + "room.prte --csv " + d + "plain.csv");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("2 emitters") != std::string::npos);

  const std::string relight = "relight " + d + "room.prte -o " + d + "out.exr" + kSmall;
  REQUIRE(prt_run(relight + " --csv " + d + "stored.csv").exit_code == 0);
  // Solver tolerance 1e-9 of the emitted power; the CSV keeps 9 digits.
  CHECK(relative_difference(csv_rgb(d + "stored.csv"), csv_rgb(d + "plain.csv")) < 1e-5);

  REQUIRE(prt_run(relight + " --emitter lamp=10 --csv " + d + "double.csv").exit_code == 0);
  REQUIRE(prt_run(relight + " --emitter panel=0 --csv " + d + "lamp.csv").exit_code == 0);
  REQUIRE(prt_run(relight + " --emitter lamp=0 --emitter panel=1,2,4 --csv " + d + "panel2.csv")
              .exit_code == 0);
  REQUIRE(prt_run(relight + " --emitter lamp=0 --csv " + d + "panel.csv").exit_code == 0);
  const std::vector<double> stored = csv_rgb(d + "stored.csv"), twice = csv_rgb(d + "double.csv"),
                            lamp = csv_rgb(d + "lamp.csv"), panel = csv_rgb(d + "panel.csv"),
                            panel2 = csv_rgb(d + "panel2.csv");
  std::vector<double> expected(stored.size()), doubled_panel(panel.size());
  for (std::size_t i = 0; i < stored.size(); ++i) {
    expected[i] = stored[i] + lamp[i];  // lamp 5 → 10: its contribution once more
    doubled_panel[i] = 2 * panel[i];
  }
  CHECK(relative_difference(twice, expected) < 1e-6);
  CHECK(relative_difference(panel2, doubled_panel) < 1e-6);
  CHECK(relative_difference(twice, stored) > 0.1);  // and the change is not negligible
  for (std::size_t i = 0; i < stored.size(); ++i)   // stored = lamp alone + panel alone
    CHECK(stored[i] == Approx(lamp[i] + panel[i]).epsilon(1e-5).margin(1e-7));

  r = prt_run("info " + d + "room.prte");
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("emitter responses") != std::string::npos);
  CHECK(r.out.find("lamp") != std::string::npos);
  CHECK(r.out.find("emission 0.5, 1, 2") != std::string::npos);
}

TEST_CASE("prt relight of emitter responses refuses bad colours, names and files",
          "[radiosity][emitters][cli]") {
  const fs::path dir = scratch("refused");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  REQUIRE(
      prt_run("radiosity " + room + " --max-edge 0.5 --per-emitter " + d + "room.prte").exit_code ==
      0);
  const std::string out = " -o " + d + "refused.exr --csv " + d + "refused.csv" + kSmall;
  check_refused(dir, "relight " + d + "room.prte --emitter sun=1" + out, "sun");
  check_refused(dir, "relight " + d + "room.prte --emitter lamp=-1" + out, "--emitter");
  check_refused(dir, "relight " + d + "room.prte --emitter lamp=nan" + out, "--emitter");
  check_refused(dir, "relight " + d + "room.prte --emitter lamp=1,2" + out, "--emitter");
  check_refused(dir, "relight " + d + "room.prte --rotate 10,0,0" + out, "--rotate");

  const std::string bytes = slurp(d + "room.prte");
  std::ofstream(d + "corrupt.prte", std::ios::binary)
      << bytes.substr(0, 200) << char(bytes[200] ^ 1) << bytes.substr(201);
  check_refused(dir, "relight " + d + "corrupt.prte" + out, "checksum");
  std::ofstream(d + "short.prte", std::ios::binary) << bytes.substr(0, bytes.size() - 7);
  check_refused(dir, "relight " + d + "short.prte" + out, "truncated");
  check_refused(dir, "info " + d + "short.prte", "truncated");
}

TEST_CASE("environment + emitters: one relight equals the sum of the two separate relights",
          "[radiosity][emitters][cli]") {
  const fs::path dir = scratch("sum");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  REQUIRE(prt_run("radiosity " + room + " --max-edge 0.25 --per-emitter " + d + "room.prte")
              .exit_code == 0);
  REQUIRE(prt_run("make-sky -o " + d + "sky.hdr --width 64 --height 32").exit_code == 0);
  RunResult r =
      prt_run("bake " + room + " --max-edge 0.25 --samples 64 -o " + d + "room.prt" + " --quiet");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string sh = "relight " + room + " " + d + "room.prt " + d + "sky.hdr --max-edge 0.25";
  REQUIRE(prt_run(sh + " -o " + d + "env.exr --csv " + d + "env.csv" + kSmall).exit_code == 0);
  r = prt_run(sh + " --emitters " + d + "room.prte --emitter lamp=2,1,0.5 -o " + d +
              "sum.exr --csv " + d + "sum.csv" + kSmall);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  REQUIRE(prt_run("relight " + d + "room.prte --emitter lamp=2,1,0.5 -o " + d + "em.exr --csv " +
                  d + "em.csv" + kSmall)
              .exit_code == 0);
  const std::vector<double> env = csv_rgb(d + "env.csv"), em = csv_rgb(d + "em.csv"),
                            sum = csv_rgb(d + "sum.csv");
  REQUIRE(env.size() == em.size());
  std::vector<double> expected(env.size());
  for (std::size_t i = 0; i < env.size(); ++i) expected[i] = env[i] + em[i];
  CHECK(relative_difference(sum, expected) < 1e-6);  // float sums, 9 printed digits
  CHECK(relative_difference(sum, env) > 0.05);       // the emitters add visibly
  CHECK(relative_difference(sum, em) > 0.05);        // and so does the sky

  // The coefficient file of the unsubdivided scene does not match the responses.
  REQUIRE(prt_run("bake " + room + " --samples 16 -o " + d + "coarse.prt --quiet").exit_code == 0);
  check_refused(dir,
                "relight " + room + " " + d + "coarse.prt " + d + "sky.hdr --emitters " + d +
                    "room.prte -o " + d + "refused.exr --csv " + d + "refused.csv" + kSmall,
                "--max-edge");
  check_refused(dir,
                "relight " + room + " " + d + "coarse.prt " + d + "sky.hdr --emitter lamp=1 -o " +
                    d + "refused.exr" + kSmall,
                "--emitters");
}

TEST_CASE("prt bake --albedo MATERIAL=value sets one material's albedo and refuses bad ones",
          "[radiosity][emitters][cli]") {
  const fs::path dir = scratch("bake_albedo");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  REQUIRE(prt_run("make-sky -o " + d + "sky.hdr --width 64 --height 32").exit_code == 0);
  const std::string bake = "bake " + room + " --transfer unshadowed --samples 16 --quiet -o ";
  REQUIRE(prt_run(bake + d + "kd.prt").exit_code == 0);
  REQUIRE(prt_run(bake + d + "white.prt --albedo white=0.2").exit_code == 0);
  const auto relight = [&](const std::string& file) {
    REQUIRE(prt_run("relight " + room + " " + d + file + ".prt " + d + "sky.hdr -o " + d + file +
                    ".exr --csv " + d + file + ".csv" + kSmall)
                .exit_code == 0);
    return csv_rgb(d + file + ".csv");
  };
  const std::vector<double> kd = relight("kd"), white = relight("white");
  REQUIRE(kd.size() == white.size());
  // Unshadowed transfer is albedo/π × the visible lighting: the white walls' vertices scale by
  // 0.2 / Kd per channel (Kd 0.7 0.6 0.5); the lamp's and panel's vertices keep theirs.
  std::size_t scaled = 0, kept = 0;
  for (std::size_t v = 0; v + 2 < kd.size(); v += 3) {
    if (kd[v] <= 0) continue;
    const double r = white[v] / kd[v], g = white[v + 1] / kd[v + 1], b = white[v + 2] / kd[v + 2];
    if (std::abs(r - 0.2 / 0.7) < 1e-4 && std::abs(g - 0.2 / 0.6) < 1e-4 &&
        std::abs(b - 0.2 / 0.5) < 1e-4)
      ++scaled;
    else if (std::abs(r - 1) < 1e-6 && std::abs(g - 1) < 1e-6 && std::abs(b - 1) < 1e-6)
      ++kept;
  }
  CHECK(scaled >= 8);  // the walls' eight corners
  CHECK(kept == 8);    // the lamp's and the panel's corners
  CHECK(scaled + kept == kd.size() / 3);
  for (const char* bad :
       {" --albedo nosuch=0.5", " --albedo white=1", " --albedo white=0.5,x,1", " --max-edge 0"}) {
    const RunResult r = prt_run(bake + d + "refused.prt" + bad);
    INFO(bad << ": " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(line_count(r.err) == 1);
    CHECK_FALSE(fs::exists(d + "refused.prt"));
  }
}

namespace {

// A black lat-long map (PFM, 64 × 32): glossy relights under it show the emitters alone.
std::string write_black_map(const fs::path& dir) {
  const fs::path path = dir / "black.pfm";
  std::ofstream out(path, std::ios::binary);
  out << "PF\n64 32\n-1.0\n";
  const std::vector<float> zeros(64 * 32 * 3, 0.f);
  out.write(reinterpret_cast<const char*>(zeros.data()), std::streamsize(zeros.size() * 4));
  return path.string();
}

// The line of `text` that starts with `start` ("" when none).
std::string line_with(const std::string& text, const std::string& start) {
  const std::size_t at = text.find(start);
  if (at == std::string::npos) return std::string();
  return text.substr(at, text.find('\n', at) - at);
}

// prt radiosity SCENE_ARGS --per-emitter, then prt relight of the responses with their stored
// colours: the same camera line, the same exposure line (automatic, a multiple of 1/4 EV) and
// the same PNG.
void check_same_camera_and_exposure(const fs::path& dir, const std::string& scene_args) {
  const std::string d = dir.string() + "/";
  const RunResult solve = prt_run("radiosity " + scene_args + " --per-emitter " + d +
                                  "room.prte -o " + d + "solve.png --size 64x48 --spp 1");
  INFO(solve.out << solve.err);
  REQUIRE(solve.exit_code == 0);
  const RunResult relit =
      prt_run("relight " + d + "room.prte -o " + d + "relit.png --size 64x48 --spp 1");
  INFO(relit.out << relit.err);
  REQUIRE(relit.exit_code == 0);
  const std::string camera = line_with(solve.out, "camera: ");
  CHECK_THAT(camera, Catch::Contains("automatic, a room"));
  CHECK(camera == line_with(relit.out, "camera: "));
  const std::string exposure = line_with(solve.out, "exposure ");
  CHECK_THAT(exposure, Catch::Contains("(automatic"));
  CHECK(exposure == line_with(relit.out, "exposure "));
  const double ev = std::stod(line_with(exposure, "exposure ").substr(9));
  CHECK(std::fmod(ev * 4.0, 1.0) == 0.0);  // printed with 2 decimals: exact for quarters
  // The two images are the same picture.
  CHECK(slurp(dir / "solve.png") == slurp(dir / "relit.png"));
}

}  // namespace

TEST_CASE("glossy file + emitters: doubling an emitter adds its contribution, the sky adds",
          "[radiosity][emitters][glossy][cli]") {
  const fs::path dir = scratch("glossy");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  REQUIRE(prt_run("radiosity " + room + " --max-edge 0.25 --per-emitter " + d + "room.prte")
              .exit_code == 0);
  RunResult r = prt_run("bake " + room + " --glossy --max-edge 0.25 --order 4 --samples 32 -o " +
                        d + "room.prtg --quiet");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string black = write_black_map(dir);
  REQUIRE(prt_run("make-sky -o " + d + "sky.hdr --width 64 --height 32").exit_code == 0);
  const auto relight = [&](const std::string& file, const std::string& env,
                           const std::string& extra, const std::string& csv) {
    const RunResult run = prt_run("relight " + room + " " + d + file + " " + env +
                                  " --max-edge 0.25 --eye 0.5,0.6,-1 -o " + d + csv +
                                  ".exr --csv " + d + csv + ".csv" + extra + kSmall);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    return csv_rgb(d + csv + ".csv");
  };
  const std::string em = " --emitters " + d + "room.prte";
  const std::vector<double> stored = relight("room.prtg", black, em, "stored"),
                            twice = relight("room.prtg", black, em + " --emitter lamp=10", "twice"),
                            lamp = relight("room.prtg", black, em + " --emitter panel=0", "lamp"),
                            sky = relight("room.prtg", d + "sky.hdr", "", "sky"),
                            both = relight("room.prtg", d + "sky.hdr", em, "both");
  std::vector<double> expected_twice(stored.size()), expected_both(stored.size());
  for (std::size_t i = 0; i < stored.size(); ++i) {
    expected_twice[i] = stored[i] + lamp[i];  // lamp 5 → 10: its contribution once more
    expected_both[i] = sky[i] + stored[i];
  }
  CHECK(relative_difference(twice, expected_twice) < 1e-6);  // float sums, 9 printed digits
  CHECK(relative_difference(twice, stored) > 0.1);
  CHECK(relative_difference(both, expected_both) < 1e-6);
  CHECK(relative_difference(both, sky) > 0.05);
  CHECK(relative_difference(both, stored) > 0.01);  // of the lamp's emission 5, the brightest

  // A .prtq keeps the geometry, frames and materials: its emitter part is the .prtg's.
  r = prt_run("compress " + d + "room.prtg -o " + d + "room.prtq --clusters 4 --vectors 4 --quiet");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(relative_difference(relight("room.prtq", black, em, "cpca"), stored) < 1e-6);
}

TEST_CASE("glossy file + emitters: responses of another scene and bad names are refused",
          "[radiosity][emitters][glossy][cli]") {
  const fs::path dir = scratch("glossy_refused");
  const std::string room = write_room(dir).string();
  const std::string d = dir.string() + "/";
  // The same room with the lamp 5 cm lower: the same vertex count, other positions.
  fs::create_directories(dir / "other");
  const std::string other = write_room(dir / "other").string();
  {
    std::string text = slurp(other);
    const std::string from = "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n";
    REQUIRE(text.find(from) != std::string::npos);
    text.replace(text.find(from), from.size(),
                 "v 0.4 0.94 0.4\nv 0.6 0.94 0.4\nv 0.6 0.94 0.6\nv 0.4 0.94 0.6\n");
    std::ofstream(other) << text;
  }
  REQUIRE(
      prt_run("radiosity " + room + " --max-edge 0.5 --per-emitter " + d + "room.prte").exit_code ==
      0);
  REQUIRE(prt_run("radiosity " + other + " --max-edge 0.5 --per-emitter " + d + "other.prte")
              .exit_code == 0);
  REQUIRE(prt_run("bake " + room + " --glossy --max-edge 0.5 --order 3 --samples 16 -o " + d +
                  "room.prtg --quiet")
              .exit_code == 0);
  const std::string black = write_black_map(dir);
  const std::string relight = "relight " + room + " " + d + "room.prtg " + black;
  const std::string out =
      " -o " + d + "refused.exr --csv " + d + "refused.csv --eye 0.5,0.5,-1" + kSmall;
  check_refused(dir, relight + " --max-edge 0.5 --emitters " + d + "other.prte" + out,
                "other.prte: was not computed for");
  check_refused(
      dir, relight + " --max-edge 0.5 --emitters " + d + "room.prte --emitter sun=1" + out, "sun");
  check_refused(dir, relight + " --emitters " + d + "room.prte" + out, "vertex count");
  check_refused(dir, relight + " --max-edge 0.5 --emitter lamp=1" + out, "--emitters");
}

TEST_CASE("prt radiosity and prt relight of its responses pick the same camera and exposure",
          "[radiosity][emitters][cli]") {
  // One camera rule and one exposure rule: the solve's PNG and the relight of its .prte with the
  // stored colours show the same vertex radiance on the same mesh, so they must choose the same
  // automatic camera (the room from inside or through its open side, never its wall backs) and
  // the same exposure, a multiple of 1/4 EV. Before, prt radiosity framed the room from outside
  // and exposed the log-average of its pixels (unrounded).
  const fs::path dir = scratch("same_view");
  check_same_camera_and_exposure(dir, write_room(dir).string() + " --max-edge 0.25");
  // --quiet silences the camera line.
  const RunResult quiet = prt_run("relight " + (dir / "room.prte").string() + " -o " +
                                  (dir / "quiet.png").string() + " --size 64x48 --spp 1 --quiet");
  CHECK(quiet.exit_code == 0);
  CHECK(quiet.out.find("camera: ") == std::string::npos);
}

TEST_CASE("the Cornell box: prt radiosity and the relight of its responses agree",
          "[radiosity][emitters][cli]") {
  const fs::path mesh = prt::test::shared_data("meshes/cornell_box.obj");
  PRT_REQUIRE_SHARED_DATA(mesh);
  // Its lamp has no Ke (Ka 20 in the file): --emission gives it one; its albedos of 1 are
  // lowered so that the solve converges as in a real box.
  check_same_camera_and_exposure(scratch("same_view_cornell"),
                                 mesh.string() +
                                     " --max-edge 100 --emission light=20,20,20 --albedo "
                                     "white=0.73,0.73,0.73 --albedo red=0.63,0.065,0.05 --albedo "
                                     "green=0.14,0.45,0.091 --albedo light=0.78,0.78,0.78");
}
