// `prt make-scene`: writes a procedural scene (scene/procedural_mesh.h, scene/level_scene.h,
// scene/field_scene.h) as a binary glTF.
//
//   prt make-scene -o data/demo.glb                   the diffuse demo (default)
//   prt make-scene --scene glossy -o glossy.glb      glossy sphere, brushed disc, rough gold box
//   prt make-scene --scene level -o level.glb [--seed S --rooms N --objects N --triangles N]
//   prt make-scene --scene field -o field.glb --vertices 1000000     (or field-glossy)
//   prt make-scene --scene translucent -o t.glb   slab, sphere, ear-like fin on a ground (mm);
//                  translucent-slab, translucent-sphere: each alone (scene/translucent_scene.h)
//
// The scenes are procedural and deterministic, so data/demo.glb can be regenerated at any time,
// and a level or field is the same file for the same options. The glossy scene's materials are
// glTF metallic-roughness with KHR_materials_specular and KHR_materials_anisotropy, and every
// primitive has TANGENT; its materials are listed. The level and field are tessellated at one
// cell size (scene/shape_layout.h): the level's default (kLevelDefaultCell) or the one whose
// count comes within kCountTolerance of --triangles / --vertices.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "output_safety.h"
#include "scene/field_scene.h"
#include "scene/glb_writer.h"
#include "scene/level_scene.h"
#include "scene/material_override.h"
#include "scene/procedural_mesh.h"
#include "scene/shape_layout.h"
#include "scene/translucent_scene.h"

namespace prt::cli {
namespace {

// A size target is met when the count lands within this fraction of it.
constexpr double kCountTolerance = 0.05;
constexpr int64_t kMaxTriangles = 20'000'000, kMaxVertices = 10'000'000;
constexpr std::size_t kFieldDefaultVertices = 500'000;

struct MakeSceneArgs {
  std::string output, which = "demo";
  uint64_t seed = 1;
  int rooms = scene::LevelOptions{}.rooms, objects = scene::LevelOptions{}.objects;
  int64_t triangles = 0, vertices = 0;  // signed: "-5" is refused as itself, not wrapped
  bool seed_given = false, rooms_given = false, objects_given = false;
  bool triangles_given = false, vertices_given = false;
};

void check_args(const MakeSceneArgs& a) {
  const bool level = a.which == "level";
  const bool field = a.which == "field" || a.which == "field-glossy";
  for (const auto& [given, name] :
       {std::pair{a.seed_given, "--seed"}, std::pair{a.rooms_given, "--rooms"},
        std::pair{a.objects_given, "--objects"}})
    if (given && !level)
      throw UsageError(std::string(name) + ": only for --scene level, not " + a.which);
  if ((a.triangles_given || a.vertices_given) && !level && !field)
    throw UsageError(std::string(a.triangles_given ? "--triangles" : "--vertices") +
                     ": only for --scene level, field or field-glossy, not " + a.which);
  if (a.triangles_given && a.vertices_given)
    throw UsageError("--triangles and --vertices: give one size target, not both");
  if (a.triangles_given && (a.triangles < 1 || a.triangles > kMaxTriangles))
    throw UsageError("--triangles " + std::to_string(a.triangles) + ": expected 1 to " +
                     std::to_string(kMaxTriangles));
  if (a.vertices_given && (a.vertices < 1 || a.vertices > kMaxVertices))
    throw UsageError("--vertices " + std::to_string(a.vertices) + ": expected 1 to " +
                     std::to_string(kMaxVertices));
  if (a.rooms_given && (a.rooms < 1 || a.rooms > scene::kMaxLevelRooms))
    throw UsageError("--rooms " + std::to_string(a.rooms) + ": expected 1 to " +
                     std::to_string(scene::kMaxLevelRooms));
  if (a.objects_given && (a.objects < 0 || a.objects > scene::kMaxLevelObjects))
    throw UsageError("--objects " + std::to_string(a.objects) + ": expected 0 to " +
                     std::to_string(scene::kMaxLevelObjects));
}

// The cell size that meets the size target (refused as the command line's fault when no cell
// comes within kCountTolerance, e.g. a target below the layout's coarsest tessellation).
double cell_for_target(const scene::ShapeLayout& layout, std::size_t target, bool vertices,
                       const std::string& what) {
  const double cell = scene::cell_size_for_count(layout, target, vertices);
  const scene::LayoutCounts n = scene::layout_counts(layout, cell);
  const std::size_t got = vertices ? n.vertices : n.triangles;
  const double miss = std::fabs(double(got) - double(target)) / double(target);
  if (miss > kCountTolerance)
    throw UsageError(std::string(vertices ? "--vertices " : "--triangles ") +
                     std::to_string(target) + ": the " + what + " comes no closer than " +
                     std::to_string(got) + (got > target ? " (its coarsest)" : ""));
  return cell;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The level or field: layout, cell size, tessellation, file; prints what it made.
void make_layout_scene(const MakeSceneArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const bool level = a.which == "level";
  scene::LevelLayout made;
  if (level)
    made = scene::make_level_layout({a.seed, a.rooms, a.objects});
  else
    made.layout = scene::make_field_layout(a.which == "field-glossy");
  const scene::ShapeLayout& layout = made.layout;
  double cell = scene::kLevelDefaultCell;
  if (a.triangles_given)
    cell = cell_for_target(layout, static_cast<std::size_t>(a.triangles), false, a.which);
  else if (a.vertices_given || !level)
    cell = cell_for_target(
        layout, a.vertices_given ? static_cast<std::size_t>(a.vertices) : kFieldDefaultVertices,
        true, a.which);
  const scene::Scene scene = scene::tessellate_layout(layout, cell);
  const double generate_seconds = seconds_since(start);
  const auto write_start = std::chrono::steady_clock::now();
  scene::write_glb(a.output, scene);  // throws SceneError("PATH: problem")
  const double write_seconds = seconds_since(write_start);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(a.output, ec);
  std::printf(
      "%s: %zu vertices, %zu triangles, %zu primitives, %zu camera(s); cell %.4g m; "
      "%.1f MB; generated in %.2f s, written in %.2f s\n",
      a.output.c_str(), scene.positions.size(), scene.triangles.size(), scene.primitives.size(),
      scene.cameras.size(), cell, ec ? 0.0 : static_cast<double>(bytes) / 1e6, generate_seconds,
      write_seconds);
  if (level) {
    const scene::LevelSummary& s = made.summary;
    std::string emitters;
    for (const std::string& m : s.emitter_materials) emitters += (emitters.empty() ? "" : ", ") + m;
    if (s.corridors > 0) emitters += std::string(emitters.empty() ? "" : ", ") + "lamp_corridor";
    std::printf(
        "  seed %llu: %d rooms, %d corridors, %d objects, %d lamps (emitting materials: "
        "%s)\n",
        static_cast<unsigned long long>(a.seed), s.rooms, s.corridors, s.objects,
        s.lamps + s.corridors, emitters.c_str());
  } else {
    for (const std::string& line : scene::describe_materials(scene))
      std::printf("  %s\n", line.c_str());
  }
}

Command register_make_scene(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "make-scene",
      "Write a procedural scene as .glb: the demo (ground, red and green walls, sphere, box, "
      "camera), the glossy demo, a game level or the bake benchmark field");
  auto a = std::make_shared<MakeSceneArgs>();
  command->add_option("-o,--output", a->output, "Output .glb path")->required();
  command
      ->add_option(
          "--scene", a->which,
          "demo (diffuse), glossy (glossy sphere, brushed-metal disc, rough gold box on "
          "a diffuse floor; glTF PBR materials with anisotropy and tangents), level "
          "(rooms, corridors, doors, pillars, crates, tables, clutter, ceiling lamps "
          "lamp_warm, lamp_cool, lamp_corridor), field (ground plane, spheres and boxes "
          "for bake benchmarks; diffuse), field-glossy (the same, glTF PBR), translucent (a slab, "
          "a sphere and an ear-like thin fin on a ground, 1 unit = 1 mm) or "
          "translucent-slab / translucent-sphere (each alone)")
      ->check(CLI::IsMember({"demo", "glossy", "level", "field", "field-glossy", "translucent",
                             "translucent-slab", "translucent-sphere"}));
  CLI::Option* seed = command->add_option("--seed", a->seed, "Level: random seed (default 1)");
  CLI::Option* rooms = command->add_option(
      "--rooms", a->rooms, "Level: number of rooms, 1 to 64 (default 6, on a square grid)");
  CLI::Option* objects =
      command->add_option("--objects", a->objects,
                          "Level: objects to place, 0 to 20000 (default 400; pillars come on top)");
  CLI::Option* triangles = command->add_option(
      "--triangles", a->triangles,
      "Level or field: tessellate to about N triangles (within 5%; level default: 0.5 m cells)");
  CLI::Option* vertices = command->add_option(
      "--vertices", a->vertices,
      "Level or field: tessellate to about N vertices (within 5%; field default 500000)");
  const auto check = [a, seed, rooms, objects, triangles, vertices] {
    a->seed_given = seed->count() > 0;
    a->rooms_given = rooms->count() > 0;
    a->objects_given = objects->count() > 0;
    a->triangles_given = triangles->count() > 0;
    a->vertices_given = vertices->count() > 0;
    check_args(*a);
  };
  const auto files = [a] {
    CommandFiles f;
    f.add_output_file("-o", a->output, {".glb"}, "a binary glTF");
    return f;
  };
  const auto run = [a] {
    if (a->which == "level" || a->which == "field" || a->which == "field-glossy") {
      make_layout_scene(*a);
      return;
    }
    const bool glossy = a->which == "glossy";
    const scene::Scene scene = glossy                             ? scene::make_glossy_scene()
                               : a->which == "translucent"        ? scene::make_translucent_scene()
                               : a->which == "translucent-slab"   ? scene::make_translucent_slab()
                               : a->which == "translucent-sphere" ? scene::make_translucent_sphere()
                                                                  : scene::make_demo_scene();
    scene::write_glb(a->output, scene);  // throws SceneError("PATH: problem")
    std::printf("%s: %zu vertices, %zu triangles, %zu primitives, %zu camera(s)\n",
                a->output.c_str(), scene.positions.size(), scene.triangles.size(),
                scene.primitives.size(), scene.cameras.size());
    if (glossy)
      for (const std::string& line : scene::describe_materials(scene))
        std::printf("  %s\n", line.c_str());
  };
  return {command, check, files, run};
}

}  // namespace

PRT_REGISTER_COMMAND(15, register_make_scene);

}  // namespace prt::cli
