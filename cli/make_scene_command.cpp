// `prt make-scene`: writes a procedural scene (scene/procedural_mesh.h) as a binary glTF.
//
//   prt make-scene -o data/demo.glb                   the diffuse demo (default)
//   prt make-scene --scene glossy -o glossy.glb      glossy sphere, brushed disc, rough gold box
//
// The scenes are procedural and deterministic, so data/demo.glb can be regenerated at any time.
// The glossy scene's materials are glTF metallic-roughness with KHR_materials_specular and
// KHR_materials_anisotropy, and every primitive has TANGENT; its materials are listed.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "output_safety.h"
#include "scene/glb_writer.h"
#include "scene/material_override.h"
#include "scene/procedural_mesh.h"

namespace prt::cli {
namespace {

Command register_make_scene(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "make-scene",
      "Write the demo scene (ground, red and green walls, sphere, box, camera) as .glb");
  auto output = std::make_shared<std::string>();
  auto which = std::make_shared<std::string>("demo");
  command->add_option("-o,--output", *output, "Output .glb path")->required();
  command
      ->add_option("--scene", *which,
                   "demo (diffuse) or glossy (glossy sphere, brushed-metal disc, rough gold box "
                   "on a diffuse floor; glTF PBR materials with anisotropy and tangents)")
      ->check(CLI::IsMember({"demo", "glossy"}));
  const auto files = [output] {
    CommandFiles f;
    f.add_output_file("-o", *output, {".glb"}, "a binary glTF");
    return f;
  };
  const auto run = [output, which] {
    const bool glossy = *which == "glossy";
    const scene::Scene scene = glossy ? scene::make_glossy_scene() : scene::make_demo_scene();
    scene::write_glb(*output, scene);  // throws SceneError("PATH: problem")
    std::printf("%s: %zu vertices, %zu triangles, %zu primitives, %zu camera(s)\n", output->c_str(),
                scene.positions.size(), scene.triangles.size(), scene.primitives.size(),
                scene.cameras.size());
    if (glossy)
      for (const std::string& line : scene::describe_materials(scene))
        std::printf("  %s\n", line.c_str());
  };
  return {command, {}, files, run};
}

}  // namespace

PRT_REGISTER_COMMAND(15, register_make_scene);

}  // namespace prt::cli
