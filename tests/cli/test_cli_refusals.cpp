// tests/cli/test_cli_refusals.cpp — the command line's mistakes get one line, exit 2 and no
// output (README "Bad input", "Exit status"): absurd geometry arguments (a move to 1e20, an
// edge length of 1e-8 or 1e-9) never reach the ray tracer or an integer conversion; prt
// radiosity's bad values and options that would be ignored are refused by name; an unconverged
// solve warns even with --quiet; a missing, empty or corrupt .prte is named with its problem
// (exit 1); prt compress refuses a target error of 0 and more vectors than the matrices hold.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

namespace {

// A room of side `size` (OBJ): white walls, a lamp `light` emitting 5, a square `block`.
fs::path write_room(const fs::path& dir, double size) {
  std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.5 0.5 0.5\n"
                                     "Ke 5 5 5\n";
  std::ofstream obj(dir / "room.obj");
  const auto v = [&](double x, double y, double z) {
    obj << "v " << x * size << " " << y * size << " " << z * size << "\n";
  };
  obj << "mtllib room.mtl\n";
  v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1), v(0, 1, 0), v(1, 1, 0), v(1, 1, 1), v(0, 1, 1);
  v(0.4, 0.99, 0.4), v(0.6, 0.99, 0.4), v(0.6, 0.99, 0.6), v(0.4, 0.99, 0.6);
  v(0.3, 0, 0.3), v(0.5, 0, 0.3), v(0.5, 0.2, 0.3), v(0.3, 0.2, 0.3);
  obj << "o walls\nusemtl white\nf 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\n"
         "o block\nusemtl white\nf 13 14 15 16\n"
         "o light\nusemtl light\nf 9 10 11 12\n";
  return dir / "room.obj";
}

// `prt ARGS` refused: exit `code`, one stderr line mentioning `expected`, no file in `dir`
// besides those there before.
void check_refused(const fs::path& dir, const std::string& args, const std::string& expected,
                   int code = 2) {
  const std::vector<std::string> before = files_in(dir);
  const RunResult r = run(prt_cli() + " " + args);
  INFO("prt " << args << "\nstderr: " << r.err);
  CHECK(r.exit_code == code);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(expected) != std::string::npos);
  CHECK(files_in(dir).size() == before.size());
}

}  // namespace

TEST_CASE("cli refusals: absurd geometry arguments never reach the ray tracer") {
  const fs::path dir = scratch("refusals/geometry");
  const std::string room = write_room(dir, 1.0).string();
  const std::string csv = " --csv " + (dir / "out.csv").string();
  // A move of 1e20 (an Embree assertion before): beyond 100 × the scene's extent.
  check_refused(dir, "radiosity " + room + csv + " --move block=1e20,0,0", "--move block");
  check_refused(dir, "radiosity " + room + csv + " --move block=0,-1e6,0", "scene's extent");
  // Tiny edge lengths: counted in double, refused (a room of side 100: 1e-8 overflowed int and
  // subdivided nothing; the glossy bake printed a negative count).
  const std::string big = write_room(dir, 100.0).string();
  check_refused(dir, "radiosity " + big + csv + " --max-edge 1e-8", "--max-edge 1e-08 would make");
  check_refused(dir, "bake " + big + " --glossy --max-edge 1e-9 -o " + (dir / "g.prtg").string(),
                "--max-edge 1e-09 would make");
  check_refused(dir, "bake " + big + " --max-edge 1e-9 -o " + (dir / "g.prt").string(),
                "triangles (at most");
  const RunResult r =
      run(prt_cli() + " bake " + big + " --glossy --max-edge 1e-9 -o " + (dir / "g.prtg").string());
  CHECK(r.err.find("-9223372036854775808") == std::string::npos);
  // A move within the bound is accepted.
  const RunResult ok = run(prt_cli() + " radiosity " + room + csv + " --move block=0.1,0,0");
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
}

TEST_CASE("cli refusals: prt radiosity's command-line mistakes exit 2 by name") {
  const fs::path dir = scratch("refusals/radiosity");
  const std::string room = "radiosity " + write_room(dir, 1.0).string();
  const std::string csv = " --csv " + (dir / "out.csv").string();
  const std::string png = " -o " + (dir / "out.png").string();
  check_refused(dir, room + csv + " --emission light=-1", "--emission light=-1");
  check_refused(dir, room + csv + " --max-edge 0", "--max-edge 0");
  check_refused(dir, room + csv + " --solver foo", "--solver foo");
  check_refused(dir, room + csv + " --form-factors rays --rays 0", "--rays");
  check_refused(dir, room + csv + " --albedo white=1.2", "below 1");
  check_refused(dir, room + csv + " --emission nosuch=1", "nosuch");
  check_refused(dir, room + " --form-factor-cache " + (dir / "out.png").string() + png,
                "form-factor cache");
  check_refused(dir, room + csv + " --max-iterations 0", "--max-iterations 0");
  check_refused(dir, room + png + " --size 0x10", "--size");
  check_refused(dir, room + png + " --spp 0", "--spp");
  check_refused(dir, room, "nothing to write");
  // Options that would be ignored.
  check_refused(dir, room + csv + " --rays 100", "--rays applies only to --form-factors rays");
  check_refused(dir, room + csv + " --seed 3", "--seed applies only to --form-factors rays");
  check_refused(dir, room + csv + " --hemicube 32", "--hemicube applies only");
  check_refused(dir, room + csv + " --form-factors hemicube --quadrature 1", "--quadrature");
  check_refused(dir, room + csv + " --max-patches 100", "--max-patches");
  check_refused(dir, room + csv + " --adaptive-passes 3", "--adaptive-passes");
  check_refused(dir, room + csv + " --exposure 1", "--exposure applies only to an image");
  check_refused(dir, room + " -o " + (dir / "out.exr").string() + " --exposure 1",
                "--exposure applies only to .png");
  check_refused(dir, room + png + " --exposure nan", "--exposure nan");
  check_refused(dir, room + png + " --exposure inf", "--exposure inf");
  check_refused(dir, room + csv + " --size 64x48", "--size applies only to an image");
  // The scene file's own problem stays exit 1.
  std::ofstream(dir / "bad.obj") << "v 0 0 nan\n";
  check_refused(dir, "radiosity " + (dir / "bad.obj").string() + csv, "bad.obj", 1);
}

TEST_CASE("cli refusals: an unconverged radiosity solve warns, --quiet or not") {
  const fs::path dir = scratch("refusals/unconverged");
  const std::string room = write_room(dir, 1.0).string();
  const RunResult r = run(prt_cli() + " radiosity " + room + " --csv " +
                          (dir / "out.csv").string() + " --max-iterations 2 --quiet");
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.empty());
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("warning: the solve stopped after 2 sweeps") != std::string::npos);
  const RunResult converged =
      run(prt_cli() + " radiosity " + room + " --csv " + (dir / "out2.csv").string() + " --quiet");
  CHECK(converged.exit_code == 0);
  CHECK(converged.err.empty());
}

TEST_CASE("cli refusals: a missing, empty or corrupt .prte is named with its problem") {
  const fs::path dir = scratch("refusals/prte");
  const std::string room = write_room(dir, 1.0).string();
  const fs::path prte = dir / "room.prte";
  REQUIRE(run(prt_cli() + " radiosity " + room + " --per-emitter " + prte.string() + " --quiet")
              .exit_code == 0);
  std::ofstream(dir / "empty.prte");
  std::ofstream(dir / "corrupt.prte", std::ios::binary) << slurp(prte).substr(0, 100);
  for (const char* name : {"missing.prte", "empty.prte", "corrupt.prte"}) {
    const std::string path = (dir / name).string();
    check_refused(dir, "relight " + path + " -o " + (dir / "out.png").string(), path, 1);
    check_refused(dir, "info " + path, path, 1);
  }
  // A scene alone is still the command line's mistake.
  check_refused(dir, "relight " + room + " -o " + (dir / "out.png").string(),
                "expected SCENE FILE.prt ENVIRONMENT");
  // Options for glossy files are refused for a responses file.
  check_refused(dir,
                "relight " + prte.string() + " -o " + (dir / "out.png").string() + " --eye 0,0,3",
                "--eye");
  check_refused(
      dir, "relight " + prte.string() + " -o " + (dir / "out.png").string() + " --exposure nan",
      "--exposure nan");
}

TEST_CASE("cli refusals: prt compress refuses a zero target error and vectors beyond D") {
  const fs::path dir = scratch("refusals/compress");
  const std::string room = write_room(dir, 1.0).string();
  const fs::path prtg = dir / "room.prtg";
  REQUIRE(run(prt_cli() + " bake " + room + " --glossy --order 2 --samples 16 -o " + prtg.string() +
              " --quiet")
              .exit_code == 0);
  const std::string compress = "compress " + prtg.string() + " -o " + (dir / "c.prtq").string();
  check_refused(dir, compress + " --target-error 0", "--target-error");
  check_refused(dir, compress + " --target-error -0.1", "--target-error");
  check_refused(dir, compress + " --target-error 2", "--target-error");
  // Order 2, one channel (grey walls): D = 2⁴ = 16 entries per vertex.
  check_refused(dir, compress + " --vectors 1000", "--vectors 1000: at most 16");
  check_refused(dir, compress + " --vectors 17", "--vectors 17: at most 16");
  check_refused(dir, compress + " --target-error 0.1 --max-vectors 100", "--max-vectors 100");
  const RunResult ok = run(prt_cli() + " " + compress + " --vectors 4 --clusters 2 --quiet");
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(fs::exists(dir / "c.prtq"));
}
