// `prt make-scene`: writes the bundled demo scene (scene/procedural_mesh.h) as a binary glTF.
//
//   prt make-scene -o data/demo.glb
//
// The demo is procedural and deterministic, so data/demo.glb can be regenerated at any time.
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "output_safety.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"

namespace prt::cli {
namespace {

void register_make_scene(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "make-scene",
      "Write the demo scene (ground, red and green walls, sphere, box, camera) as .glb");
  auto output = std::make_shared<std::string>();
  command->add_option("-o,--output", *output, "Output .glb path")->required();
  command->callback([output] {
    check_output_file("-o", *output, {".glb"}, "a binary glTF");
    const scene::Scene scene = scene::make_demo_scene();
    scene::write_glb(*output, scene);  // throws SceneError("PATH: problem")
    std::printf("%s: %zu vertices, %zu triangles, %zu primitives, %zu camera(s)\n", output->c_str(),
                scene.positions.size(), scene.triangles.size(), scene.primitives.size(),
                scene.cameras.size());
  });
}

}  // namespace

PRT_REGISTER_COMMAND(15, register_make_scene);

}  // namespace prt::cli
