// `prt demo [-o DIR] [--quick]`: the whole job on the bundled data. Loads data/demo.glb (or, if
// it is absent, the procedural demo scene, written to DIR/demo.glb), bakes interreflected SH
// transfer, writes DIR/demo.prt, relights it under data/sky.hdr, and writes DIR/demo.png
// (tone mapped), DIR/demo.exr (linear) and DIR/demo_compare.png (unshadowed | shadowed |
// interreflected, same lighting and exposure).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake/transfer_baker.h"
#include "command_registry.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/transfer_file.h"
#include "relight/auto_camera.h"
#include "relight/auto_exposure.h"
#include "relight/camera.h"
#include "relight/environment_input.h"
#include "relight/image_io.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "sh/rotation.h"

#ifndef PRT_DEMO_DATA_DIR
#define PRT_DEMO_DATA_DIR ""
#endif

namespace prt::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The files the demo writes into its output folder (the scene only when data/ has none).
constexpr const char* kSceneName = "demo.glb";
constexpr const char* kTransferName = "demo.prt";
constexpr const char* kImageName = "demo.png";
constexpr const char* kLinearImageName = "demo.exr";
constexpr const char* kCompareName = "demo_compare.png";
constexpr const char* kOutputNames[] = {kSceneName, kTransferName, kImageName, kLinearImageName,
                                        kCompareName};

struct DemoArguments {
  std::string output_dir = "out";
  std::string data_dir;
  bool quick = false;
  bool quiet = false;
};

// The demo's look, chosen by eye (see docs/images/demo.png).
struct DemoSettings {
  int order = 5;
  int samples = 1024;
  int width = 960, height = 540, samples_per_axis = 3;
  // Exposure: automatic, as prt relight's default (relight/auto_exposure.h).
  // The sky turned so the sun comes from the front right, casting the shadows of
  // the sphere and the box toward the green wall (chosen by eye).
  std::array<double, 3> yaw_pitch_roll{300.0, 0.0, 0.0};
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// data/ from --data, the working directory, or the source tree the binary was built from.
fs::path find_data_dir(const std::string& requested) {
  if (!requested.empty()) {
    if (!fs::is_directory(requested))
      throw CommandError("--data " + requested + ": is not a directory");
    return requested;
  }
  for (const fs::path& candidate : {fs::path("data"), fs::path(PRT_DEMO_DATA_DIR)})
    if (!candidate.empty() && fs::exists(candidate / "sky.hdr")) return candidate;
  throw CommandError("data/sky.hdr: not found (run from the repository root, or pass --data DIR)");
}

prt::TransferData bake_kind(const scene::Scene& scene, prt::TransferKind kind,
                            const DemoSettings& settings, bool quiet, double* seconds) {
  bake::BakeOptions options;
  options.kind = kind;
  options.order = settings.order;
  options.samples = settings.samples;
  options.ao = kind == prt::TransferKind::Interreflected;
  ProgressReporter progress(quiet);
  const auto start = Clock::now();
  bake::BakeResult result = bake_transfer(scene, options, &progress);
  *seconds = seconds_since(start);
  return std::move(result.data);
}

std::vector<float> shade(const prt::TransferData& data, const prt::ShLighting& lighting) {
  prt::Result<prt::Relighter> relighter = prt::Relighter::create(data);
  if (!relighter.ok()) throw CommandError(relighter.status().message());
  return relight::shade_all_vertices(*relighter, lighting, data.vertex_count);
}

// The bundled data read, the output folder and every file written in it.
CommandFiles demo_files(const DemoArguments& args) {
  const fs::path data_dir = find_data_dir(args.data_dir);
  CommandFiles files;
  if (fs::exists(data_dir / "demo.glb")) files.add_scene((data_dir / "demo.glb").string());
  files.add_environment((data_dir / "sky.hdr").string());
  files.add_output_directory("-o", args.output_dir);
  for (const char* name : kOutputNames)
    files.add_output("-o", (fs::path(args.output_dir) / name).string());
  return files;
}

void run(const DemoArguments& args) {
  DemoSettings settings;
  if (args.quick) {
    settings.order = 4;
    settings.samples = 256;
    settings.width = 640;
    settings.height = 360;
    settings.samples_per_axis = 2;
  }
  const fs::path data_dir = find_data_dir(args.data_dir);
  const fs::path out_dir = args.output_dir;
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (!fs::is_directory(out_dir))
    throw CommandError(out_dir.string() + ": cannot create the output directory");
  std::vector<std::string> written;

  // 1. The scene.
  scene::Scene scene;
  std::string scene_note;
  const fs::path bundled = data_dir / "demo.glb";
  if (fs::exists(bundled)) {
    scene = scene::load_scene(bundled.string());
  } else {
    scene = scene::make_demo_scene();
    const std::string path = (out_dir / kSceneName).string();
    scene::write_glb(path, scene);
    scene.source_path = path;
    written.push_back(path);
    scene_note = " (" + bundled.string() + " is missing, so the procedural demo scene was used)";
  }

  // 2. Bake: interreflected for the main image; unshadowed and shadowed for the comparison.
  double bake_seconds = 0, unshadowed_seconds = 0, shadowed_seconds = 0;
  const prt::TransferData interreflected =
      bake_kind(scene, prt::TransferKind::Interreflected, settings, args.quiet, &bake_seconds);
  const std::string prt_path = (out_dir / kTransferName).string();
  const prt::Status saved = prt::write_transfer_file(prt_path, interreflected);
  if (!saved.ok()) throw CommandError(saved.message());
  written.push_back(prt_path);
  const prt::TransferData unshadowed =
      bake_kind(scene, prt::TransferKind::Unshadowed, settings, true, &unshadowed_seconds);
  const prt::TransferData shadowed =
      bake_kind(scene, prt::TransferKind::Shadowed, settings, true, &shadowed_seconds);

  // 3. Relight under the bundled sky.
  auto start = Clock::now();
  const std::string sky_path = (data_dir / "sky.hdr").string();
  relight::EnvironmentUse sky_use;
  sky_use.sh_order = settings.order;
  const prt::sh::EnvMap sky =
      relight::read_checked_environment(sky_path, prt::sh::EnvLayout::LatLong, sky_use).env;
  relight::LightingOptions lighting_options;
  lighting_options.yaw_pitch_roll_deg = settings.yaw_pitch_roll;
  lighting_options.window = prt::sh::Window::Auto;
  std::string window_note;
  const std::array<double, 9> rotation = prt::sh::rotation_from_yaw_pitch_roll(
      settings.yaw_pitch_roll[0], settings.yaw_pitch_roll[1], settings.yaw_pitch_roll[2]);
  const prt::ShLighting lighting = relight::rotate_lighting(
      relight::project_lighting(sky, settings.order, lighting_options, &window_note), rotation);
  const std::vector<float> radiance = shade(interreflected, lighting);
  const double shade_seconds = seconds_since(start);
  const float exposure_ev = relight::choose_auto_exposure(radiance);

  // 4. Render.
  start = Clock::now();
  const scene::RayCaster caster(scene);
  relight::RenderOptions render_options;
  render_options.width = settings.width;
  render_options.height = settings.height;
  render_options.samples_per_axis = settings.samples_per_axis;
  const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
  const relight::CameraChoice camera_choice = relight::choose_camera("auto", scene, caster, aspect);
  const relight::Camera& camera = camera_choice.camera;
  const relight::Image image =
      relight::render(scene, caster, radiance, &sky, rotation, camera, render_options);
  for (const char* name : {kImageName, kLinearImageName}) {
    const std::string path = (out_dir / name).string();
    relight::write_rendered_image(path, image, exposure_ev);
    written.push_back(path);
  }

  // 5. The comparison strip: unshadowed | shadowed | interreflected.
  relight::RenderOptions panel_options = render_options;
  panel_options.width = settings.width / 2;
  panel_options.height = settings.height / 2;
  relight::Image strip;
  strip.width = 3 * panel_options.width;
  strip.height = panel_options.height;
  strip.rgb.assign(3 * static_cast<std::size_t>(strip.width) * strip.height, 0.f);
  const prt::TransferData* panels[3] = {&unshadowed, &shadowed, &interreflected};
  for (int p = 0; p < 3; ++p) {
    const std::vector<float> panel_radiance = p == 2 ? radiance : shade(*panels[p], lighting);
    const relight::Image panel =
        relight::render(scene, caster, panel_radiance, &sky, rotation, camera, panel_options);
    for (int row = 0; row < panel.height; ++row)
      std::copy(panel.rgb.begin() + 3 * static_cast<std::ptrdiff_t>(row) * panel.width,
                panel.rgb.begin() + 3 * static_cast<std::ptrdiff_t>(row + 1) * panel.width,
                strip.rgb.begin() +
                    3 * (static_cast<std::ptrdiff_t>(row) * strip.width + p * panel.width));
  }
  const std::string compare_path = (out_dir / kCompareName).string();
  relight::write_rendered_image(compare_path, strip, exposure_ev);
  written.push_back(compare_path);
  const double render_seconds = seconds_since(start);

  if (args.quiet) return;
  std::printf(
      "prt demo: baked %zu vertices of %s%s (interreflected, SH order %d, %d samples per vertex) "
      "in %.1f s, plus unshadowed and shadowed transfer for the comparison in %.1f s; relit "
      "under %s (%s) in %.2f ms and rendered %dx%d (exposure %+.2f EV) with %dx%d samples per "
      "pixel "
      "(and the "
      "3-panel comparison) in %.1f s. Wrote:",
      scene.vertex_count(), scene.source_path.c_str(), scene_note.c_str(), settings.order,
      settings.samples, bake_seconds, unshadowed_seconds + shadowed_seconds, sky_path.c_str(),
      window_note.c_str(), 1e3 * shade_seconds, settings.width, settings.height, exposure_ev,
      settings.samples_per_axis, settings.samples_per_axis, render_seconds);
  for (const std::string& file : written) std::printf(" %s", file.c_str());
  std::printf(".\n%s\n", relight::describe_camera(camera_choice).c_str());
}

Command register_demo(CLI::App& app) {
  auto args = std::make_shared<DemoArguments>();
  CLI::App* cmd =
      app.add_subcommand("demo", "Bake and relight the bundled demo scene under the bundled sky");
  cmd->add_option("-o,--output", args->output_dir, "Output directory")->capture_default_str();
  cmd->add_option("--data", args->data_dir,
                  "Directory holding demo.glb and sky.hdr (default: ./data, else the source tree)");
  cmd->add_flag("--quick", args->quick, "Fewer samples, lower order, smaller images");
  cmd->add_flag("--quiet", args->quiet, "No progress or summary (warnings still print)");
  return {cmd, {}, [args] { return demo_files(*args); }, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(5, register_demo);

}  // namespace prt::cli
