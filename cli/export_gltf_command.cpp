// `prt export-gltf SCENE FILE.prt [ENV] -o OUT.glb`: the mesh with its transfer as
// application-specific vertex attributes (relight/transfer_glb.h), through the GLB writer of
// scene/glb_writer.h (written atomically); with ENV, the map's SH lighting in the scene's extras.
// web/prt-relight.js relights the file in any three.js app (docs/VIEWER.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "glossy_cli.h"
#include "output_safety.h"
#include "relight/environment_input.h"
#include "relight/relight_pipeline.h"
#include "relight/transfer_glb.h"
#include "scene/glb_writer.h"
#include "scene/scene_loader.h"

namespace prt::cli {
namespace {

struct ExportArguments {
  std::string scene, transfer, environment, output;
  bool quiet = false;
};

void run(const ExportArguments& args) {
  if (is_glossy_file(args.transfer))
    throw CommandError(args.transfer +
                       ": is a glossy file; prt export-gltf writes SH files (.prt)");
  const scene::Scene scene = scene::load_scene(args.scene);
  const prt::TransferData data = relight::load_transfer_for_scene(args.transfer, scene);
  if (data.kind == prt::TransferKind::Haar)
    throw CommandError(args.transfer + ": holds Haar wavelets; prt export-gltf writes SH files");
  std::optional<prt::ShLighting> lighting;
  if (!args.environment.empty()) {
    relight::EnvironmentUse use;
    use.sh_order = static_cast<int>(data.order);
    const sh::EnvMap env =
        relight::read_checked_environment(args.environment, std::nullopt, use).env;
    relight::LightingOptions unwindowed;  // window none: the app chooses its own
    lighting = relight::project_lighting(env, static_cast<int>(data.order), unwindowed);
  }
  const scene::GlbCustomData custom =
      relight::transfer_glb_data(data, scene, lighting ? &*lighting : nullptr, args.environment);
  scene::write_glb(args.output, scene, nullptr, &custom);
  if (args.quiet) return;
  std::printf("wrote %s: %zu vertices, %s SH order %u, %u channel(s) in %zu _PRT_SH attributes%s\n",
              args.output.c_str(), scene.vertex_count(), prt::transfer_kind_name(data.kind),
              data.order, data.channels,
              std::size_t(data.channels * data.coefficients_per_channel() + 3) / 4,
              lighting ? ", and the lighting of the map" : "");
}

Command register_export_gltf(CLI::App& app) {
  auto args = std::make_shared<ExportArguments>();
  CLI::App* cmd = app.add_subcommand(
      "export-gltf",
      "Write the mesh with its SH transfer as glTF vertex attributes (_PRT_SH0…), for web "
      "engines (web/prt-relight.js relights it in three.js)");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj) the file was baked from")
      ->required();
  cmd->add_option("transfer", args->transfer, "Coefficient file (.prt, SH)")->required();
  cmd->add_option("environment", args->environment,
                  "Environment map whose SH lighting goes into the file's extras (optional)");
  cmd->add_option("-o,--output", args->output, "The binary glTF to write (.glb)")->required();
  cmd->add_flag("--quiet", args->quiet, "No summary");
  const auto files = [args] {
    CommandFiles f;
    f.add_scene(args->scene);
    f.add_input("coefficient file", args->transfer);
    if (!args->environment.empty()) f.add_environment(args->environment);
    f.add_output_file("-o", args->output, {".glb"}, "a binary glTF");
    return f;
  };
  return {cmd, {}, files, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(31, register_export_gltf);

}  // namespace prt::cli
