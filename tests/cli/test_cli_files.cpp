// tests/cli/test_cli_files.cpp — nothing is ever destroyed: every subcommand refuses an output
// that is one of its inputs (by file identity: symlinks, hard links and "./" do not get around
// it) or another of its outputs, before any work, leaving the inputs' bytes as they were and
// no file behind; and an output that cannot be written gets the same message from every
// command (cli/output_safety.h).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

namespace {

// A quad (two triangles) as OBJ with a material library, baked at order 3 with 16 samples.
struct Inputs {
  fs::path dir, scene, mtl, transfer, env;
};

Inputs make_inputs(const std::string& name) {
  Inputs in;
  in.dir = scratch(name);
  in.mtl = in.dir / "quad.mtl";
  std::ofstream(in.mtl) << "newmtl grey\nKd 0.5 0.5 0.5\n";
  in.scene = in.dir / "quad.obj";
  std::ofstream(in.scene) << "mtllib quad.mtl\nusemtl grey\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\n"
                             "f 1 2 3\nf 1 3 4\n";
  in.transfer = in.dir / "quad.prt";
  const RunResult baked = run(prt_cli() + " bake " + in.scene.string() + " -o " +
                              in.transfer.string() + " --samples 16 --quiet");
  REQUIRE(baked.exit_code == 0);
  in.env = in.dir / "sky.hdr";
  const float c[3] = {1.0f, 0.8f, 0.6f};
  write_constant_env(in.env, 32, 16, c);
  return in;
}

// Every input's bytes, to compare after a refused command.
std::vector<std::string> bytes_of(const std::vector<fs::path>& files) {
  std::vector<std::string> bytes;
  for (const fs::path& f : files) bytes.push_back(slurp(f));
  return bytes;
}

// A refusal for the same-file reason: exit 2 (usage), one line, naming the rule.
void require_overwrite_refusal(const RunResult& r, const std::string& must_mention) {
  require_one_line_error(r, must_mention);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("is the same file as") != std::string::npos);
}

}  // namespace

TEST_CASE("cli files: relight refuses every output that is one of its inputs") {
  const Inputs in = make_inputs("files_relight");
  const std::vector<fs::path> inputs = {in.scene, in.mtl, in.transfer, in.env};
  const std::vector<std::string> before = bytes_of(inputs);
  const std::vector<std::string> files_before = files_in(in.dir);
  const std::string base = prt_cli() + " relight " + in.scene.string() + " " +
                           in.transfer.string() + " " + in.env.string() + " --size 16x16";

  SECTION("the environment map as the image, through ./") {
    const std::string dotted = (in.dir / "." / "sky.hdr").string();
    require_overwrite_refusal(run(base + " -o " + dotted), "environment map");
  }
  SECTION("the environment map through a symlink") {
    fs::create_symlink(in.env, in.dir / "link.hdr");
    require_overwrite_refusal(run(base + " -o " + (in.dir / "link.hdr").string()), "link.hdr");
    fs::remove(in.dir / "link.hdr");
  }
  SECTION("the environment map through a hard link") {
    fs::create_hard_link(in.env, in.dir / "hard.hdr");
    require_overwrite_refusal(run(base + " -o " + (in.dir / "hard.hdr").string()), "hard.hdr");
    fs::remove(in.dir / "hard.hdr");
  }
  SECTION("the scene as --vertex-colors") {
    require_overwrite_refusal(run(base + " -o " + (in.dir / "img.png").string() +
                                  " --vertex-colors " + in.scene.string()),
                              "--vertex-colors");
  }
  SECTION("the scene's material library as --csv") {
    require_overwrite_refusal(
        run(base + " -o " + (in.dir / "img.png").string() + " --csv " + in.mtl.string()),
        "file read by the scene");
  }
  SECTION("the coefficient file as --csv") {
    require_overwrite_refusal(
        run(base + " -o " + (in.dir / "img.png").string() + " --csv " + in.transfer.string()),
        "coefficient file");
  }
  SECTION("a turntable frame that is the environment map") {
    // -o sky.hdr --turntable 3 writes sky_000.hdr, sky_001.hdr, sky_002.hdr: sky_001.hdr is
    // the map here.
    const fs::path frame_env = in.dir / "sky_001.hdr";
    fs::copy_file(in.env, frame_env);
    const std::string frame_bytes = slurp(frame_env);
    const RunResult r = run(prt_cli() + " relight " + in.scene.string() + " " +
                            in.transfer.string() + " " + frame_env.string() + " -o " +
                            (in.dir / "sky.hdr").string() + " --turntable 3 --size 16x16");
    require_overwrite_refusal(r, "--turntable frame");
    CHECK(slurp(frame_env) == frame_bytes);
    CHECK_FALSE(fs::exists(in.dir / "sky_000.hdr"));
    fs::remove(frame_env);
  }
  SECTION("two outputs that are one file, through a symlinked folder") {
    fs::create_directory(in.dir / "real");
    fs::create_directory_symlink(in.dir / "real", in.dir / "alias");
    const RunResult r = run(base + " -o " + (in.dir / "real" / "a.png").string() + " --csv " +
                            (in.dir / "alias" / "a.png").string());
    require_one_line_error(r, "two outputs cannot share a file");
    CHECK(r.exit_code == 2);
    CHECK(files_in(in.dir / "real").empty());
    fs::remove(in.dir / "alias");
    fs::remove(in.dir / "real");
  }
  CHECK(bytes_of(inputs) == before);
  CHECK(files_in(in.dir) == files_before);  // nothing written, no stray temporary
}

TEST_CASE("cli files: bake never replaces its scene or the files the scene reads") {
  const Inputs in = make_inputs("files_bake");
  const std::vector<fs::path> inputs = {in.scene, in.mtl, in.env};
  const std::vector<std::string> before = bytes_of(inputs);
  SECTION("-o the scene itself") {
    require_overwrite_refusal(
        run(prt_cli() + " bake " + in.scene.string() + " -o " + in.scene.string()), "scene");
  }
  SECTION("-o a .prt symlink to the scene's material library") {
    fs::create_symlink(in.mtl, in.dir / "out.prt");
    require_overwrite_refusal(run(prt_cli() + " bake " + in.scene.string() + " -o " +
                                  (in.dir / "out.prt").string() + " --samples 16"),
                              "quad.mtl");
    fs::remove(in.dir / "out.prt");
  }
  SECTION("-o a .prt symlink to the --env map") {
    fs::create_symlink(in.env, in.dir / "env.prt");
    require_overwrite_refusal(
        run(prt_cli() + " bake " + in.scene.string() + " -o " + (in.dir / "env.prt").string() +
            " --auto --env " + in.env.string()),
        "environment map");
    fs::remove(in.dir / "env.prt");
  }
  SECTION("a glTF's external buffer") {
    // One triangle in a .gltf whose positions live in tri.bin; -o is a symlink to tri.bin.
    const fs::path bin = in.dir / "tri.bin";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 0, -1};
    std::ofstream(bin, std::ios::binary).write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const fs::path gltf = in.dir / "tri.gltf";
    std::ofstream(gltf)
        << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
        << R"("min":[0,0,-1],"max":[1,0,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
        << R"("buffers":[{"uri":"tri.bin","byteLength":36}]})";
    const std::string bin_bytes = slurp(bin);
    fs::create_symlink(bin, in.dir / "tri.prt");
    require_overwrite_refusal(
        run(prt_cli() + " bake " + gltf.string() + " -o " + (in.dir / "tri.prt").string()),
        "tri.bin");
    CHECK(slurp(bin) == bin_bytes);
    fs::remove(in.dir / "tri.prt");
  }
  CHECK(bytes_of(inputs) == before);
}

TEST_CASE("cli files: info, env, report and demo refuse to write over their inputs") {
  const Inputs in = make_inputs("files_other");
  const std::string transfer_bytes = slurp(in.transfer);
  SECTION("info --csv appended to its own file") {
    // In a subshell: run() redirects the subshell's stdout, the command's own `>>` wins inside.
    std::string command = "(";
    command += prt_cli() + " info " + in.transfer.string() + " --csv >> " + in.transfer.string();
    const RunResult r = run(command + ")");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("stdout is the same file as the coefficient file") != std::string::npos);
    CHECK(slurp(in.transfer) == transfer_bytes);
  }
  SECTION("report -o a folder holding one of its inputs under a name it writes") {
    const fs::path out = in.dir / "report";
    fs::create_directory(out);
    const fs::path scene_copy = out / "summary.md";  // the scene, under a name report writes
    fs::copy_file(in.scene, scene_copy);
    const RunResult r = run(prt_cli() + " report " + scene_copy.string() + " " + in.env.string() +
                            " -o " + out.string() + " --quick");
    require_overwrite_refusal(r, "summary.md");
    CHECK(slurp(scene_copy) == slurp(in.scene));
    CHECK(files_in(out).size() == 1u);
  }
  SECTION("report -o an input file") {
    const RunResult r = run(prt_cli() + " report " + in.scene.string() + " " + in.env.string() +
                            " -o " + in.env.string() + " --quick");
    require_overwrite_refusal(r, "environment map");
  }
  SECTION("demo -o a folder where one of its outputs links to its sky") {
    const fs::path data = in.dir / "data";
    fs::create_directory(data);
    fs::copy_file(in.env, data / "sky.hdr");
    const fs::path out = in.dir / "demo_out";
    fs::create_directory(out);
    fs::create_symlink(data / "sky.hdr", out / "demo.exr");
    const std::string sky_bytes = slurp(data / "sky.hdr");
    const RunResult r = run(prt_cli() + " demo --data " + data.string() + " -o " + out.string() +
                            " --quick --quiet");
    require_overwrite_refusal(r, "demo.exr");
    CHECK(slurp(data / "sky.hdr") == sky_bytes);
    CHECK(files_in(out).size() == 1u);
  }
}

TEST_CASE("cli files: an output that is a folder gets the same true message from every command") {
  const Inputs in = make_inputs("files_folder");
  const fs::path folder = in.dir / "a_folder";
  fs::create_directory(folder);
  const std::string f = folder.string();
  const std::string expected = "-o " + f + ": is a directory, not a file";
  const std::vector<std::string> commands = {
      "relight " + in.scene.string() + " " + in.transfer.string() + " " + in.env.string() + " -o " +
          f,
      "bake " + in.scene.string() + " -o " + f,
      "make-sky -o " + f,
      "make-scene -o " + f,
  };
  for (const std::string& command : commands) {
    INFO(command);
    const RunResult r = run(prt_cli() + " " + command);
    require_one_line_error(r, expected);
    CHECK(r.exit_code == 1);
  }
  // And the opposite for commands that write a folder: a file is not one.
  for (const std::string& command :
       {"report " + in.scene.string() + " " + in.env.string() + " -o " + in.transfer.string(),
        "demo -o " + in.transfer.string() + " --quick"}) {
    INFO(command);
    const RunResult r = run(prt_cli() + " " + command);
    require_one_line_error(r, "-o " + in.transfer.string() + ": is a file, not a directory");
    CHECK(r.exit_code == 1);
  }
  CHECK(files_in(folder).empty());
}

TEST_CASE("cli files: relight --help says an interrupted turntable keeps its finished frames") {
  const RunResult r = run(prt_cli() + " relight --help");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("interrupted turntable keeps the frames it finished") != std::string::npos);
}

TEST_CASE("cli files: an input that is missing or a folder gets the same message everywhere") {
  const Inputs in = make_inputs("files_input_folder");
  const fs::path folder = in.dir / "a_folder";
  fs::create_directory(folder);
  const fs::path out = in.dir / "out";
  fs::create_directory(out);
  for (const auto& [bad, problem] :
       {std::pair<fs::path, std::string>{folder, "is a directory, not a file"},
        std::pair<fs::path, std::string>{in.dir / "missing.file", "no such file"}}) {
    const std::string b = bad.string();
    const std::vector<std::string> commands = {
        "env " + b,
        "info " + b,
        "bake " + b + " -o " + (out / "x.prt").string(),
        "bake " + in.scene.string() + " -o " + (out / "x.prt").string() + " --auto --env " + b,
        "relight " + b + " " + in.transfer.string() + " " + in.env.string() + " -o " +
            (out / "x.png").string(),
        "relight " + in.scene.string() + " " + b + " " + in.env.string() + " -o " +
            (out / "x.png").string(),
        "relight " + in.scene.string() + " " + in.transfer.string() + " " + b + " -o " +
            (out / "x.png").string(),
        "report " + b + " " + in.env.string() + " -o " + (out / "r").string(),
    };
    for (const std::string& command : commands) {
      INFO(command);
      const RunResult r = run(prt_cli() + " " + command);
      require_one_line_error(r, b + ": " + problem);
      CHECK(r.exit_code == 1);
    }
  }
  CHECK(files_in(out).empty());
}
