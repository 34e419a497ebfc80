// tests/cli/test_cli_outputs.cpp — every registered subcommand goes through one file check
// (cli/command_registry.h: main runs CommandFiles::check() on the files a command declares,
// before its work): for each subcommand `prt --help` lists, a command line whose output is one
// of its inputs or another of its outputs (or, for the commands that read nothing, an output in a
// missing folder) is refused with exit 2 (1 for the folder) and one line, and nothing is
// written. A subcommand missing from the table below fails the test: a new command must show
// here that it declares its files.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

namespace {

// The subcommands `prt --help` lists (the lines after "Subcommands:").
std::set<std::string> listed_subcommands() {
  const RunResult help = run(prt_cli() + " --help");
  REQUIRE(help.exit_code == 0);
  std::set<std::string> names;
  std::istringstream lines(help.out);
  std::string line;
  bool in_list = false;
  while (std::getline(lines, line)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    if (!in_list || line.size() < 3 || line[0] != ' ') continue;
    std::istringstream words(line);
    std::string name;
    words >> name;
    names.insert(name);
  }
  return names;
}

// A small lit room (OBJ): white walls, a lamp `light` emitting 5; a box `block` on the floor.
struct Files {
  fs::path dir, scene, env, prte, prtg;
};

fs::path write_room(const fs::path& dir) {
  std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.5 0.5 0.5\n"
                                     "Ke 5 5 5\n";
  std::ofstream(dir / "room.obj")
      << "mtllib room.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
         "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"
         "v 0.3 0 0.3\nv 0.5 0 0.3\nv 0.5 0.2 0.3\nv 0.3 0.2 0.3\n"
         "o walls\nusemtl white\nf 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\n"
         "o block\nusemtl white\nf 13 14 15 16\n"
         "o light\nusemtl light\nf 9 10 11 12\n";
  return dir / "room.obj";
}

Files make_files(const std::string& name) {
  Files f;
  f.dir = scratch("outputs/" + name);
  f.scene = write_room(f.dir);
  f.env = f.dir / "sky.hdr";
  const float c[3] = {1.0f, 0.9f, 0.8f};
  write_constant_env(f.env, 32, 16, c);
  return f;
}

void make_prte(Files& f) {
  f.prte = f.dir / "room.prte";
  const RunResult r = run(prt_cli() + " radiosity " + f.scene.string() + " --per-emitter " +
                          f.prte.string() + " --quiet");
  REQUIRE(r.exit_code == 0);
}

void make_prtg(Files& f) {
  f.prtg = f.dir / "room.prtg";
  const RunResult r = run(prt_cli() + " bake " + f.scene.string() + " --glossy --order 2 " +
                          "--samples 16 -o " + f.prtg.string() + " --quiet");
  REQUIRE(r.exit_code == 0);
}

struct Case {
  std::string args;  // after "prt"
  int exit_code;     // 2: same file; 1: a folder that does not exist
  std::string must_mention;
  std::vector<fs::path> must_not_exist;  // outputs that must not have been written
};

void check_case(const Case& c) {
  const bool subshell = !c.args.empty() && c.args.back() == ')';
  const RunResult r = run((subshell ? "(" : "") + prt_cli() + " " + c.args);
  INFO("prt " << c.args << "\nstderr: " << r.err);
  CHECK(r.exit_code == c.exit_code);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(c.must_mention) != std::string::npos);
  for (const fs::path& p : c.must_not_exist) CHECK_FALSE(fs::exists(p));
}

}  // namespace

TEST_CASE("cli outputs: every registered subcommand refuses outputs that share a file") {
  Files f = make_files("all");
  make_prte(f);
  make_prtg(f);
  const std::string scene = f.scene.string(), env = f.env.string(), dir = f.dir.string() + "/";
  const std::string same = "is the same file as";
  const std::string prte_bytes = slurp(f.prte), prtg_bytes = slurp(f.prtg);
  std::map<std::string, std::vector<Case>> cases;
  cases["bake"] = {{"bake " + scene + " -o " + scene, 2, same, {}},
                   {"bake " + scene + " --glossy -o " + dir + "room.mtl", 2, same, {}}};
  cases["compress"] = {{"compress " + f.prtg.string() + " -o " + f.prtg.string(), 2, same, {}}};
  const std::string part = dir + "room.prtpart";
  REQUIRE(run(prt_cli() + " bake " + scene + " --samples 16 --shard 0/1 --quiet -o " + part)
              .exit_code == 0);
  cases["merge"] = {{"merge " + part + " -o " + part, 2, same, {}}};
  cases["relight"] = {
      {"relight " + scene + " " + f.prtg.string() + " " + env + " -o " + dir + "a.png --csv " +
           dir + "a.png --eye 0.5,0.5,3",
       2,
       "--csv",
       {dir + "a.png"}},
      {"relight " + scene + " " + f.prtg.string() + " " + env + " -o " + dir +
           "t.png --turntable 3 --vertex-colors " + dir + "t_001.png --eye 0.5,0.5,3",
       2,
       "--turntable frame",
       {dir + "t_000.png"}},
      {"relight " + f.prte.string() + " -o " + dir + "b.png --csv " + f.prte.string(),
       2,
       "emitter responses",
       {dir + "b.png"}}};
  cases["radiosity"] = {
      {"radiosity " + scene + " -o " + dir + "o.png --per-emitter " + dir + "o.prte --csv " + dir +
           "o.prte",
       2,
       "--csv",
       {dir + "o.png", dir + "o.prte"}},
      {"radiosity " + scene + " -o " + dir + "o.png --csv " + dir + "o.png",
       2,
       "-o",
       {dir + "o.png"}},
      {"radiosity " + scene + " -o " + dir + "o.png --vertex-colors " + dir + "o.png",
       2,
       "--vertex-colors",
       {dir + "o.png"}},
      {"radiosity " + scene + " --form-factor-cache " + dir + "ff.bin --csv " + dir + "ff.bin",
       2,
       "form-factor cache",
       {dir + "ff.bin"}}};
  // In a subshell: run() redirects the subshell's stdout, the command's own `>>` wins inside.
  cases["info"] = {{"info " + f.prte.string() + " --csv >> " + f.prte.string() + ")",
                    2,
                    "stdout is the same file",
                    {}}};
  cases["env"] = {{"env " + env + " >> " + env + ")", 2, "stdout is the same file", {}}};
  cases["report"] = {
      {"report " + scene + " " + env + " -o " + env + " --quick", 2, same, {}},
      {"report --sun-study --quick -o " + scene, 1, "is a file, not a directory", {}}};
  cases["demo"] = {{"demo --data " + dir + " -o " + env + " --quick --quiet", 2, same, {}}};
  cases["make-sky"] = {{"make-sky -o " + dir + "nowhere/sky.hdr", 1, "folder", {}}};
  cases["make-scene"] = {{"make-scene -o " + dir + "nowhere/s.glb", 1, "folder", {}}};

  const std::set<std::string> listed = listed_subcommands();
  REQUIRE(listed.size() >= 10u);
  for (const std::string& name : listed) {
    INFO("subcommand " << name << " has no case here: add one that shows it declares its files");
    REQUIRE(cases.count(name) == 1);
  }
  for (const auto& [name, list] : cases)
    for (const Case& c : list) check_case(c);
  CHECK(slurp(f.prte) == prte_bytes);  // the inputs are as they were
  CHECK(slurp(f.prtg) == prtg_bytes);
}

TEST_CASE("cli outputs: the form-factor cache is an input once it exists") {
  Files f = make_files("cache");
  const std::string scene = f.scene.string(), cache = (f.dir / "ff.bin").string();
  const RunResult saved = run(prt_cli() + " radiosity " + scene + " --form-factor-cache " + cache +
                              " --csv " + (f.dir / "a.csv").string() + " --quiet");
  REQUIRE(saved.exit_code == 0);
  const std::string bytes = slurp(cache);
  const RunResult r =
      run(prt_cli() + " radiosity " + scene + " --form-factor-cache " + cache + " -o " + cache);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(cache) != std::string::npos);
  CHECK(slurp(cache) == bytes);
}
