// tests/cli/test_cli_farm.cpp — farm bakes (docs/FARM.md): `prt bake --shard I/N` parts merged by
// `prt merge` give the bytes of one `prt bake` (SH shadowed and interreflected, Haar shadowed and
// interreflected, glossy, subsurface), for N = 1, 2, 7 and 64; the merge refuses parts
// that do not belong together in one line, writing nothing; --shard reads the Slurm and
// Kubernetes variables and refuses bad values.
//
// The scene is `prt make-scene --scene field` at about 400 vertices (spheres and boxes on a
// ground: occlusion and interreflection everywhere), 32 samples a vertex: every comparison is of
// whole files, byte for byte, so no tolerance is involved.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "prt/formats/part_file.h"

namespace fs = std::filesystem;
using namespace prt::test::cli;

namespace {

// The field scene (or `kind`: field-glossy) with about `vertices` vertices, in `dir`.
fs::path make_field(const fs::path& dir, int vertices, const std::string& name = "field.glb",
                    const std::string& kind = "field") {
  const fs::path scene = dir / name;
  const RunResult r = run(prt_cli() + " make-scene --scene " + kind + " --vertices " +
                          std::to_string(vertices) + " -o " + scene.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  return scene;
}

std::string bake_line(const fs::path& scene, const std::string& options, const fs::path& out) {
  return prt_cli() + " bake " + scene.string() + " " + options + " --quiet -o " + out.string();
}

// Bakes the N shards of `options` into dir/part_I.prtpart; returns their paths.
std::vector<fs::path> bake_shards(const fs::path& scene, const std::string& options, int n,
                                  const fs::path& dir) {
  std::vector<fs::path> parts;
  for (int i = 0; i < n; ++i) {
    parts.push_back(dir / ("part_" + std::to_string(i) + ".prtpart"));
    const RunResult r = run(bake_line(
        scene, options + " --shard " + std::to_string(i) + "/" + std::to_string(n), parts.back()));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
  }
  return parts;
}

RunResult merge(const std::vector<fs::path>& parts, const fs::path& out) {
  std::string line = prt_cli() + " merge --quiet -o " + out.string();
  for (const fs::path& p : parts) {
    line += ' ';
    line += p.string();
  }
  return run(line);
}

// Merges the parts in reverse order (the merge takes any order) and compares with `single`.
void check_merge_identical(const std::vector<fs::path>& parts, const fs::path& single,
                           const fs::path& out) {
  const std::vector<fs::path> reversed(parts.rbegin(), parts.rend());
  const RunResult r = merge(reversed, out);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(fs::exists(out.string() + ".run.json"));
  const std::string a = slurp(single), b = slurp(out);
  REQUIRE(a.size() > 1000);
  CHECK(a == b);
}

void check_identity_for_every_n(const std::string& name, const std::string& options,
                                const std::string& kind = "field",
                                const std::string& extension = ".prt") {
  const fs::path dir = scratch(name);
  const fs::path scene = make_field(dir, 400, "field.glb", kind),
                 single = dir / ("single" + extension);
  const RunResult s = run(bake_line(scene, options, single));
  INFO(s.err);
  REQUIRE(s.exit_code == 0);
  for (const int n : {1, 2, 7, 64}) {
    INFO("N = " << n);
    fs::path sub = dir / "n";
    sub += std::to_string(n);
    fs::create_directories(sub);
    check_merge_identical(bake_shards(scene, options, n, sub), single,
                          sub / ("merged" + extension));
  }
}

// For each line of `options`: the single bake to dir/single.EXT and 3 shards merged to
// dir/merged.EXT give the same bytes (`extension` with its dot: ".prt", ".prtg").
void check_each_merges_identical(const fs::path& dir, const fs::path& scene,
                                 const std::vector<std::string>& options,
                                 const std::string& extension) {
  for (const std::string& o : options) {
    INFO(o);
    const fs::path single = dir / ("single" + extension), merged = dir / ("merged" + extension);
    REQUIRE(run(bake_line(scene, o, single)).exit_code == 0);
    check_merge_identical(bake_shards(scene, o, 3, dir), single, merged);
    fs::remove(merged);
    fs::remove(merged.string() + ".run.json");
  }
}

// Bakes shard 1/3 of `options` to dir/NAME (a part to slip among another bake's); returns its
// path.
fs::path bake_shard1(const fs::path& scene, const fs::path& dir, const std::string& options,
                     const std::string& name) {
  const fs::path path = dir / name;
  const RunResult r = run(bake_line(scene, options + " --shard 1/3", path));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  return path;
}

// A refused merge: a non-zero exit, one line naming `expected`, neither OUT nor its record.
void check_refused(const std::vector<fs::path>& parts, const fs::path& out,
                   const std::string& expected) {
  const RunResult r = merge(parts, out);
  INFO(r.err);
  CHECK(r.exit_code != 0);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find(expected) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".run.json"));
}

}  // namespace

TEST_CASE("cli farm: merged shards of a shadowed bake are the single bake, byte for byte") {
  check_identity_for_every_n("farm_shadowed",
                             "--transfer shadowed --order 3 --samples 32 --ao --bent-normals");
}

TEST_CASE("cli farm: merged shards of an interreflected bake are the single bake, byte for byte") {
  check_identity_for_every_n("farm_interreflected",
                             "--transfer interreflected --order 3 --samples 32 --ao");
}

TEST_CASE("cli farm: merged shards of an obscurance bake are the single bake, byte for byte") {
  check_identity_for_every_n("farm_obscurance",
                             "--transfer shadowed --order 3 --samples 32 --ao --bent-normals "
                             "--ao-distance 0.4 --ao-falloff smoothstep");
}

TEST_CASE("cli farm: merged shards of Haar bakes are the single bake, byte for byte") {
  check_identity_for_every_n("farm_haar", "--basis haar --cube 8 --haar-supersample 2");
  check_identity_for_every_n("farm_haar_interreflected",
                             "--basis haar --cube 8 --transfer interreflected --haar-bits 8");
}

// The glossy scene's materials (glTF metallic-roughness, specular, anisotropy) and tangent frames
// travel in shard 0's part; interreflected bakes also carry every hit for the merge's bounces.
TEST_CASE("cli farm: merged shards of glossy bakes are the single bake, byte for byte") {
  check_identity_for_every_n("farm_glossy", "--glossy --order 3 --samples 32", "field-glossy",
                             ".prtg");
  check_identity_for_every_n("farm_glossy_interreflected",
                             "--glossy --transfer interreflected --order 3 --samples 16",
                             "field-glossy", ".prtg");
}

// --bounce-precision f16 changes the bounces' values (binary16 rounding of the bounce read), so a
// merge that lost it would not match the single bake's bytes.
TEST_CASE("cli farm: glossy bounces, f16 and material overrides merge to the single bake") {
  const fs::path dir = scratch("farm_glossy_variants");
  const fs::path scene = make_field(dir, 300, "field.glb", "field-glossy");
  check_each_merges_identical(
      dir, scene,
      {"--glossy --bounces 2 --order 2 --samples 16 --precision f16",
       "--glossy --bounces 2 --order 2 --samples 16 --bounce-precision f16",
       "--glossy --order 2 --samples 16 --material '*=ward:rho_d=0.3,rho_s=0.2,ax=0.2,ay=0.4'"},
      ".prtg");
}

TEST_CASE("cli farm: prt merge refuses glossy parts that do not belong together") {
  const fs::path dir = scratch("farm_glossy_refusals");
  const fs::path scene = make_field(dir, 300, "field.glb", "field-glossy");
  const std::string options = "--glossy --transfer interreflected --order 2 --samples 16";
  const std::vector<fs::path> p = bake_shards(scene, options, 3, dir);
  const fs::path out = dir / "merged.prtg";
  SECTION("an SH part among glossy parts") {
    check_refused(
        {p[0], bake_shard1(scene, dir, "--transfer interreflected --samples 16", "sh.prtpart"),
         p[2]},
        out, "sh.prtpart: baked with other settings: basis \"sh\" here, \"glossy\"");
  }
  SECTION("other materials") {
    check_refused(
        {p[0], bake_shard1(scene, dir, options + " --material '*=ggx:roughness=0.4'", "m.prtpart"),
         p[2]},
        out, "m.prtpart: a part of another scene than");
  }
  SECTION("other glossy settings") {
    check_refused({p[0], bake_shard1(scene, dir, options + " --bounces 3", "b.prtpart"), p[2]}, out,
                  "b.prtpart: baked with other settings: bounces 3 here, -1 in");
  }
  SECTION("a missing range") {
    check_refused({p[0], p[1]}, out, "shard 2/3 is missing");
  }
  SECTION("a corrupt part") {
    const fs::path c = dir / "c.prtpart";
    std::string bytes = slurp(p[0]);
    bytes[bytes.size() / 3] = static_cast<char>(bytes[bytes.size() / 3] ^ 0x01);
    std::ofstream(c, std::ios::binary) << bytes;
    check_refused({c, p[1], p[2]}, out, "c.prtpart: checksum mismatch");
  }
  SECTION("a glossy merge into a .prt") {
    check_refused(p, dir / "merged.prt", "merged.prt");
  }
}

// Subsurface bakes: the shards carry S and the gather rows, shard 0 the material of every vertex;
// the merge runs the dipole gather over every vertex (then, interreflected, the solve with R_total
// as the translucent vertices' albedo). Two materials and an opaque ground: a merge that lost the
// vertices' materials, a material's coefficients or the scale would not give the same bytes.
TEST_CASE("cli farm: merged shards of subsurface bakes are the single bake, byte for byte") {
  check_identity_for_every_n(
      "farm_subsurface",
      "--subsurface red=skin1 --subsurface grey=marble --transfer shadowed --order 3 --samples 32");
  check_identity_for_every_n("farm_subsurface_interreflected",
                             "--subsurface red=ketchup --subsurface-scale 2 --transfer "
                             "interreflected --order 3 --samples 16 --ao");
}

// An interreflected subsurface bake does not use a translucent vertex's base colour: the solve
// takes the material's R_total (clamped to 0.999) as its albedo. So a base colour of 1, which an
// opaque material may not have, is accepted by the single bake, and must be by its shards: a
// shard that checked the base colour refused it. Also a material whose R_total reaches 1
// (σa ≈ 0: R_total above 0.999), clamped alike. The same colour on an opaque material is refused
// by both, with the same line. A slab of `white` (base colour 1) over a ground of `grey`.
TEST_CASE("cli farm: subsurface shards accept the translucent base colours the single bake does") {
  const fs::path dir = scratch("farm_subsurface_albedo");
  const fs::path scene = dir / "slab.obj";
  std::ofstream(scene) << "mtllib slab.mtl\n"
                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0.3\n"
                          "v -2 -0.01 -2\nv 2 -0.01 -2\nv 2 -0.01 2\nv -2 -0.01 2\n"
                          "o slab\nusemtl white\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"
                          "o ground\nusemtl grey\nf 6 9 8\nf 6 8 7\n";
  std::ofstream(dir / "slab.mtl") << "newmtl white\nKd 1 1 1\nnewmtl grey\nKd 0.5 0.5 0.5\n";
  const std::string base = "--transfer interreflected --order 2 --samples 16 ";
  check_each_merges_identical(
      dir, scene,
      {base + "--subsurface white=marble",
       base + "--subsurface white=custom --sigma-a 1e-9,1e-9,1e-9 --sigma-s 1000,1000,1000"},
      ".prt");
  const std::string opaque = base + "--subsurface grey=marble";
  const RunResult single = run(bake_line(scene, opaque, dir / "opaque.prt"));
  const RunResult shard = run(bake_line(scene, opaque + " --shard 0/2", dir / "opaque.prtpart"));
  INFO(single.err << shard.err);
  CHECK(single.exit_code != 0);
  CHECK(shard.exit_code != 0);
  CHECK(single.err.find("albedo (1, 1, 1) of primitive 'slab' is outside [0, 1)") !=
        std::string::npos);
  CHECK(shard.err == single.err);
  CHECK_FALSE(fs::exists(dir / "opaque.prt"));
  CHECK_FALSE(fs::exists(dir / "opaque.prtpart"));
}

TEST_CASE("cli farm: prt merge refuses subsurface parts that do not belong together") {
  const fs::path dir = scratch("farm_subsurface_refusals");
  const fs::path scene = make_field(dir, 300);
  const std::string options = "--transfer interreflected --samples 16";
  const std::string subsurface = options + " --subsurface red=marble";
  const std::vector<fs::path> p = bake_shards(scene, subsurface, 3, dir);
  const fs::path out = dir / "merged.prt";
  SECTION("a plain part among subsurface parts") {
    check_refused({p[0], bake_shard1(scene, dir, options, "plain.prtpart"), p[2]}, out,
                  "plain.prtpart: baked with other settings: no --subsurface here, --subsurface");
  }
  SECTION("a subsurface part among plain parts") {
    const fs::path sub = dir / "plain";
    fs::create_directories(sub);
    const std::vector<fs::path> q = bake_shards(scene, options, 3, sub);
    check_refused({q[0], p[1], q[2]}, out,
                  "part_1.prtpart: baked with other settings: --subsurface here, none");
  }
  SECTION("another subsurface material") {
    check_refused(
        {p[0], bake_shard1(scene, dir, options + " --subsurface red=skin1", "m.prtpart"), p[2]},
        out, "m.prtpart: baked with other settings: subsurface materials");
  }
  SECTION("another subsurface scale") {
    check_refused(
        {p[0], bake_shard1(scene, dir, subsurface + " --subsurface-scale 3", "sc.prtpart"), p[2]},
        out, "sc.prtpart: baked with other settings: subsurface mm_per_unit 3.0 here, 0.0 in");
  }
  SECTION("the material on other vertices") {
    const fs::path v = dir / "v";
    fs::create_directories(v);
    const std::vector<fs::path> q = bake_shards(scene, options + " --subsurface grey=marble", 3, v);
    check_refused({p[0], q[1], p[2]}, out, "part_1.prtpart: a part of another scene than");
  }
  SECTION("a missing range") {
    check_refused({p[0], p[1]}, out, "shard 2/3 is missing");
  }
}

TEST_CASE("cli farm: merged form-factor shards are the cache one prt radiosity writes") {
  const fs::path dir = scratch("farm_radiosity");
  const fs::path fixtures = fs::path(PRT_SOURCE_DIR) / "tests" / "scripts" / "fixtures";
  fs::copy_file(fixtures / "room.obj", dir / "room.obj");
  fs::copy_file(fixtures / "room.mtl", dir / "room.mtl");
  const std::string room = (dir / "room.obj").string();
  for (const std::string options :
       {"--max-edge 0.25", "--max-edge 0.25 --form-factors rays --rays 64 --seed 3"}) {
    INFO(options);
    const fs::path single = dir / "single.ffc";
    fs::remove(single);
    const RunResult s =
        run(prt_cli() + " radiosity " + room + " " + options + " --quiet --csv " +
            (dir / "single.csv").string() + " --form-factor-cache " + single.string());
    INFO(s.err);
    REQUIRE(s.exit_code == 0);
    for (const int n : {1, 2, 7, 64}) {
      INFO("N = " << n);
      std::vector<fs::path> parts;
      for (int i = 0; i < n; ++i) {
        parts.push_back(dir / ("ff_" + std::to_string(i) + ".prtpart"));
        const RunResult r =
            run(prt_cli() + " radiosity " + room + " " + options + " --shard " + std::to_string(i) +
                "/" + std::to_string(n) + " --quiet -o " + parts.back().string());
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
      }
      const fs::path merged = dir / "merged.ffc";
      fs::remove(merged);
      const RunResult m = merge(parts, merged);
      INFO(m.err);
      REQUIRE(m.exit_code == 0);
      CHECK(slurp(merged) == slurp(single));
      for (const fs::path& p : parts) fs::remove(p);
    }
  }
  // prt radiosity takes the merged cache as its own.
  const RunResult used =
      run(prt_cli() + " radiosity " + room + " --max-edge 0.25 --form-factors rays --rays 64 " +
          "--seed 3 --quiet --csv " + (dir / "merged.csv").string() + " --form-factor-cache " +
          (dir / "merged.ffc").string());
  INFO(used.err);
  REQUIRE(used.exit_code == 0);
  CHECK(slurp(dir / "merged.csv") == slurp(dir / "single.csv"));
  // What does not apply to a shard is refused by name, nothing written.
  for (const std::string extra : {"--solver jacobi", "--move room=0.1,0,0", "--size 8x8",
                                  "--form-factors hemicube", "--csv x.csv", "--adaptive 0.1"}) {
    INFO(extra);
    const fs::path out = dir / "refused.prtpart";
    const RunResult r = run(prt_cli() + " radiosity " + room + " --max-edge 0.25 " + extra +
                            " --shard 0/2 -o " + out.string());
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE(
    "cli farm: f16, f16 bounces, fixed bounces and unshadowed AO merge to the single bake's "
    "bytes") {
  const fs::path dir = scratch("farm_variants");
  const fs::path scene = make_field(dir, 300);
  check_each_merges_identical(
      dir, scene,
      {"--transfer interreflected --bounces 2 --order 4 --samples 16 --precision f16",
       "--transfer interreflected --bounces 2 --order 4 --samples 16 --bounce-precision f16",
       "--transfer interreflected --order 3 --samples 16 --bounce-precision f16",
       "--transfer unshadowed --ao --samples 16"},
      ".prt");
}

TEST_CASE("cli farm: a shard baked again writes the same part bytes") {
  const fs::path dir = scratch("farm_rerun");
  const fs::path scene = make_field(dir, 300);
  const std::string options = "--transfer interreflected --samples 16 --shard 1/3";
  REQUIRE(run(bake_line(scene, options + " --threads 1", dir / "a.prtpart")).exit_code == 0);
  REQUIRE(run(bake_line(scene, options + " --threads 2", dir / "b.prtpart")).exit_code == 0);
  const std::string a = slurp(dir / "a.prtpart");
  CHECK(a.size() > 1000);
  CHECK(a == slurp(dir / "b.prtpart"));
}

TEST_CASE("cli farm: prt merge refuses parts that do not belong together, in one line") {
  const fs::path dir = scratch("farm_refusals");
  const fs::path scene = make_field(dir, 300), other = make_field(dir, 350, "other.glb");
  const std::string options = "--transfer interreflected --samples 16";
  const std::vector<fs::path> p = bake_shards(scene, options, 3, dir);
  const fs::path out = dir / "merged.prt";
  const auto shard1 = [&](const std::string& extra, const fs::path& s, const std::string& name) {
    return bake_shard1(s, dir, options + " " + extra, name);
  };
  SECTION("a missing range") {
    check_refused({p[0], p[2]}, out, "shard 1/3 is missing");
  }
  SECTION("a range given twice") {
    const fs::path copy = dir / "copy.prtpart";
    fs::copy_file(p[1], copy);
    check_refused({p[0], p[1], copy, p[2]}, out, "given twice");
  }
  SECTION("another scene") {
    check_refused({p[0], shard1("", other, "o.prtpart"), p[2]}, out,
                  "o.prtpart: a part of another scene");
  }
  SECTION("another albedo") {
    check_refused({p[0], shard1("--albedo 0.3", scene, "a.prtpart"), p[2]}, out,
                  "a.prtpart: a part of another scene");
  }
  SECTION("other settings") {
    check_refused({p[0], shard1("--order 4", scene, "s.prtpart"), p[2]}, out,
                  "s.prtpart: baked with other settings: order 4 here, 3 in");
  }
  SECTION("another obscurance distance") {
    const fs::path sub = dir / "ao";
    fs::create_directories(sub);
    const std::vector<fs::path> ao = bake_shards(scene, options + " --ao", 3, sub);
    check_refused({ao[0], shard1("--ao --ao-distance 0.3", scene, "ob.prtpart"), ao[2]}, out,
                  "ob.prtpart: baked with other settings: obscurance");
  }
  SECTION("another seed") {
    check_refused({p[0], shard1("--seed 7", scene, "d.prtpart"), p[2]}, out,
                  "d.prtpart: baked with --seed 7");
  }
  SECTION("another split") {
    const fs::path q = dir / "q.prtpart";
    REQUIRE(run(bake_line(scene, options + " --shard 1/4", q)).exit_code == 0);
    check_refused({p[0], q, p[2]}, out, "q.prtpart: shard 1/4 of another split");
  }
  SECTION("another prt version") {
    // The same part, its settings section saying another version (checksum recomputed).
    prt::PartFile f;
    REQUIRE(prt::read_part_file(p[1].string(), &f).ok());
    for (prt::PartSection& s : f.sections) {
      if (s.tag != 1) continue;
      nlohmann::json j = nlohmann::json::parse(
          std::string(reinterpret_cast<const char*>(s.data()), static_cast<std::size_t>(s.size())));
      j["prt_version"] = "0.0.1";
      const std::string text = j.dump();
      s.view = nullptr;  // the read section is a view into the mapped file: own bytes instead
      s.bytes.assign(text.begin(), text.end());
    }
    const fs::path v = dir / "v.prtpart";
    REQUIRE(prt::write_part_file(v.string(), f).ok());
    check_refused({p[0], v, p[2]}, out, "v.prtpart: written by prt 0.0.1");
  }
  SECTION("a part of another part layout or settings table") {
    // What a prt with another settings table (or section layout) writes: the same part with
    // another layout id in its header, its checksum valid. Refused as another version, not as
    // other settings.
    prt::PartFile f;
    REQUIRE(prt::read_part_file(p[1].string(), &f).ok());
    f.layout ^= 1;
    const fs::path v = dir / "layout.prtpart";
    REQUIRE(prt::write_part_file(v.string(), f).ok());
    check_refused({p[0], v, p[2]}, out, "layout.prtpart: written by another prt version");
    check_refused({v}, out, "layout.prtpart: written by another prt version");
  }
  SECTION("a part of another part file format") {
    // A part whose header says format 1 (as written before the layout field): refused by name
    // before its checksum, its settings or its sections are looked at.
    std::string bytes = slurp(p[1]);
    REQUIRE(bytes.size() > 8);
    bytes[4] = 1, bytes[5] = bytes[6] = bytes[7] = 0;
    const fs::path o = dir / "old.prtpart";
    std::ofstream(o, std::ios::binary) << bytes;
    check_refused({p[0], o, p[2]}, out,
                  "old.prtpart: written by another prt version (part file format 1");
  }
  SECTION("a truncated part") {
    const fs::path t = dir / "t.prtpart";
    const std::string bytes = slurp(p[1]);
    std::ofstream(t, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    check_refused({p[0], t, p[2]}, out, "t.prtpart: truncated");
  }
  SECTION("a corrupt part") {
    const fs::path c = dir / "c.prtpart";
    std::string bytes = slurp(p[1]);
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
    std::ofstream(c, std::ios::binary) << bytes;
    check_refused({p[0], c, p[2]}, out, "c.prtpart: checksum mismatch");
  }
  SECTION("not a part") {
    check_refused({p[0], scene, p[2]}, out, "bad magic");
  }
}

TEST_CASE("cli farm: --shard auto reads the Slurm array and Kubernetes Indexed Job variables") {
  const fs::path dir = scratch("farm_auto");
  const fs::path scene = make_field(dir, 300);
  const std::string options = "--transfer shadowed --samples 16";
  const fs::path ref = dir / "ref.prtpart";
  REQUIRE(run(bake_line(scene, options + " --shard 1/3", ref)).exit_code == 0);
  const std::string expected = slurp(ref);
  const auto bake_env = [&](const std::string& env, const std::string& shard, const fs::path& out) {
    return run(env + " " + bake_line(scene, options + " --shard " + shard, out));
  };
  const std::string unset =
      "env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_MIN -u SLURM_ARRAY_TASK_COUNT "
      "-u JOB_COMPLETION_INDEX";
  struct Case {
    std::string env, shard;
  };
  for (const Case& c :
       {Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=3", "auto"},
        Case{"SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_COUNT=3", "auto"},
        Case{"JOB_COMPLETION_INDEX=1", "auto/3"}, Case{"SLURM_ARRAY_TASK_ID=1", "auto/3"}}) {
    INFO(c.env << " --shard " << c.shard);
    const fs::path out = dir / "auto.prtpart";
    fs::remove(out);
    const RunResult r = bake_env(unset + " " + c.env, c.shard, out);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(out) == expected);
  }
  for (const Case& c :
       {Case{"", "auto"}, Case{"", "auto/3"},
        Case{"SLURM_ARRAY_TASK_ID=x SLURM_ARRAY_TASK_COUNT=3", "auto"},
        Case{"SLURM_ARRAY_TASK_ID=1", "auto"},
        Case{"SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_COUNT=3", "auto"},
        Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_MIN=2 SLURM_ARRAY_TASK_COUNT=3", "auto"},
        Case{"SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=4", "auto/3"},
        Case{"JOB_COMPLETION_INDEX=-1", "auto/3"}, Case{"JOB_COMPLETION_INDEX=3", "auto/3"}}) {
    INFO("refused: " << c.env << " --shard " << c.shard);
    const fs::path out = dir / "refused.prtpart";
    const RunResult r = bake_env(unset + " " + c.env, c.shard, out);
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find("--shard auto") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(out.string() + ".run.json"));
  }
  // Without --shard the variables are not read: the whole bake, as outside a job.
  const fs::path whole = dir / "whole.prt", inside = dir / "inside.prt";
  REQUIRE(run(bake_line(scene, options, whole)).exit_code == 0);
  REQUIRE(run("SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=3 " + bake_line(scene, options, inside))
              .exit_code == 0);
  CHECK(slurp(whole) == slurp(inside));
}

TEST_CASE("cli farm: bad --shard values and bakes that cannot be sharded are refused") {
  const fs::path dir = scratch("farm_bad_values");
  const fs::path scene = make_field(dir, 300), out = dir / "p.prtpart";
  for (const char* value : {"0/0", "3/2", "2/2", "-1/2", "junk", "1/", "/2", "1/2/3", "1.5/2",
                            "0/99999999999", "auto/0"}) {
    INFO("--shard " << value);
    const RunResult r = run(bake_line(scene, std::string("--shard '") + value + "'", out));
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.find("--shard") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
  for (const std::string options :
       {"--auto", "--subsurface marble --transfer unshadowed", "--transfer shadowed"}) {
    INFO(options);
    const fs::path wrong = dir / "p.prt";  // a part must be a .prtpart
    const RunResult r = run(
        bake_line(scene, options + " --shard 0/2", options == "--transfer shadowed" ? wrong : out));
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(wrong));
  }
}
