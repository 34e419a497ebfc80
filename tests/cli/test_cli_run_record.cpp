// tests/cli/test_cli_run_record.cpp — what changes from run to run (wall times, the thread count,
// the host) is kept out of the files prt writes and recorded beside the main output in
// OUT.run.json (cli/run_record.h); `prt info` prints it from there, says when it is absent, and
// `--json` gives it under "run". The sidecar is an output like any other: it cannot be an input.
// (tests/scripts/check_reproducible_outputs.sh compares every file kind's bytes across thread
// counts.)
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"

namespace fs = std::filesystem;
using namespace prt::test::cli;

namespace {

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("cli run record: times and threads beside the bake, not in it, and prt info reads them") {
  const fs::path dir = scratch("run_record_bake");
  const fs::path box = write_lit_box(dir), out = dir / "box.prt";
  const std::string record = out.string() + ".run.json";
  const RunResult baked =
      run(prt_cli() + " bake " + box.string() + " -o " + out.string() +
          " --transfer interreflected --order 2 --samples 16 --threads 1 --quiet");
  INFO(baked.err);
  REQUIRE(baked.exit_code == 0);
  REQUIRE(fs::exists(record));
  const nlohmann::json r = read_json(record);
  CHECK(r["threads"] == 1);
  CHECK(r["seconds"].get<double>() > 0.0);
  CHECK(r["phase_seconds"].contains("rays"));
  CHECK(r["phase_seconds"].contains("interreflection solve"));
  // CPU seconds per phase: all there, none negative, and the bake's phases (the BVH, the gather
  // setup and the rays are the sampling pass; then the solve) within the whole bake's CPU time,
  // all read from one process clock (1e-9 s: the rounding of the differences).
  const nlohmann::json& cpu = r["phase_cpu_seconds"];
  double parts = 0.0;
  for (const char* phase :
       {"scene load", "bvh", "gather setup", "rays", "interreflection solve", "bake", "write"}) {
    INFO(phase);
    REQUIRE(cpu.contains(phase));
    CHECK(cpu[phase].get<double>() >= 0.0);
  }
  for (const char* phase : {"bvh", "gather setup", "rays", "interreflection solve"})
    parts += cpu[phase].get<double>();
  CHECK(parts <= cpu["bake"].get<double>() + 1e-9);
  CHECK(r["peak_resident_bytes"].get<double>() > 1e6);  // any process holds more than 1 MB
  CHECK(r["output"] == out.string());
  CHECK(r["command"].get<std::string>().find(" bake " + box.string()) != std::string::npos);
  CHECK(r.contains("host"));

  // The file's metadata keeps what the result is (samples, seed, the solve's residual, the
  // scene path as given) and nothing of the run.
  const RunResult json = run(prt_cli() + " info --json " + out.string());
  REQUIRE(json.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  const nlohmann::json& meta = j["metadata"];
  CHECK(meta["scene"] == box.string());
  CHECK(meta["seed"] == 1);
  CHECK(meta["interreflection"].contains("relative_residual"));
  for (const char* key : {"seconds", "seconds_rays", "threads"}) CHECK_FALSE(meta.contains(key));
  CHECK_FALSE(meta["interreflection"].contains("seconds"));
  REQUIRE(j.contains("run"));
  CHECK(j["run"]["threads"] == 1);

  const RunResult text = run(prt_cli() + " info " + out.string());
  INFO(text.out);
  CHECK(text.out.find("on 1 thread(s)") != std::string::npos);
  CHECK(text.out.find("interreflection solve") != std::string::npos);

  // Without the sidecar prt info says so, and --json has no "run".
  fs::remove(record);
  const RunResult bare = run(prt_cli() + " info " + out.string());
  CHECK(bare.exit_code == 0);
  CHECK(bare.out.find("not recorded (" + record + " is absent)") != std::string::npos);
  const RunResult bare_json = run(prt_cli() + " info --json " + out.string());
  CHECK_FALSE(nlohmann::json::parse(bare_json.out).contains("run"));

  // A damaged record is reported as it is, never trusted: not JSON, or numbers out of any range
  // (printed as given, never converted to a narrower type).
  std::ofstream(record) << "{bad";
  const RunResult damaged = run(prt_cli() + " info " + out.string());
  CHECK(damaged.exit_code == 0);
  CHECK(damaged.out.find(record + " is not a JSON object") != std::string::npos);
  std::ofstream(record) << R"({"threads": 1e30, "peak_resident_bytes": -5})";
  const RunResult absurd = run(prt_cli() + " info " + out.string());
  INFO(absurd.out);
  CHECK(absurd.exit_code == 0);
  CHECK(absurd.out.find("on 1000000000000000019884624838656 thread(s)") != std::string::npos);
  CHECK(absurd.out.find("peak resident 0 B") != std::string::npos);
}

TEST_CASE(
    "cli run record: radiosity writes it beside --per-emitter, prt info of the .prte reads it") {
  const fs::path dir = scratch("run_record_radiosity");
  const fs::path box = write_lit_box(dir), prte = dir / "box.prte";
  const fs::path cache = dir / "box.ffc";
  const RunResult solved =
      run(prt_cli() + " radiosity " + box.string() + " --per-emitter " + prte.string() + " --csv " +
          (dir / "box.csv").string() + " --form-factor-cache " + cache.string() +
          " --max-edge 0.5 --threads 2 --quiet");
  INFO(solved.err);
  REQUIRE(solved.exit_code == 0);
  REQUIRE(fs::exists(prte.string() + ".run.json"));
  CHECK_FALSE(fs::exists(dir / "box.csv.run.json"));  // one record per run, beside the main output
  const nlohmann::json r = read_json(prte.string() + ".run.json");
  CHECK(r["threads"] == 2);
  CHECK(r["phase_seconds"].contains("per-emitter solves"));
  CHECK_FALSE(r["phase_seconds"].contains("render"));  // no image was asked for
  const RunResult json = run(prt_cli() + " info --json " + prte.string());
  REQUIRE(json.exit_code == 0);
  CHECK(nlohmann::json::parse(json.out)["run"]["threads"] == 2);
  // The cache never has a record of its own: prt info does not call it missing.
  const RunResult ffc = run(prt_cli() + " info " + cache.string());
  INFO(ffc.out);
  REQUIRE(ffc.exit_code == 0);
  CHECK(ffc.out.find("not recorded") == std::string::npos);
}

TEST_CASE("cli run record: OUT.run.json is checked like any output, never an input") {
  const fs::path dir = scratch("run_record_input");
  const fs::path box = write_lit_box(dir);
  // compress IN -o OUT where IN is OUT.run.json: the record would overwrite the input.
  const RunResult glossy = run(prt_cli() + " bake " + box.string() + " --glossy --order 2 " +
                               "--samples 16 -o " + (dir / "g.prtg").string() + " --quiet");
  REQUIRE(glossy.exit_code == 0);
  fs::copy_file(dir / "g.prtg", dir / "c.prtq.run.json", fs::copy_options::overwrite_existing);
  const RunResult clash = run(prt_cli() + " compress " + (dir / "c.prtq.run.json").string() +
                              " -o " + (dir / "c.prtq").string() + " --quiet");
  INFO(clash.err);
  CHECK(clash.exit_code == 2);
  CHECK(line_count(clash.err) == 1);
  CHECK(clash.err.find("run record") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "c.prtq"));
}
