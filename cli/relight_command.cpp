// `prt relight SCENE FILE.prt ENV -o OUT.(exr|png|hdr) [...]`: shade a baked scene under an
// environment map and render it (relight/relight_pipeline.h does the work).
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_parsing.h"
#include "command_registry.h"
#include "haar_cli.h"
#include "progress_reporter.h"
#include "relight/relight_pipeline.h"
#include "sh/env_map.h"
#include "sh/window.h"

namespace prt::cli {
namespace {

struct RelightArguments {
  std::string scene, transfer, environment, output;
  std::string layout = "auto";
  std::string rotate = "0,0,0";
  std::string window = "none";
  double window_strength = -1.0;
  float exposure = 0.f;
  std::string size = "960x540";
  int spp = 3;
  std::string camera = "auto";
  std::string vertex_colors, csv;
  int turntable = 0;
  bool quiet = false;
  HaarRelightArguments haar;  // --terms, --approx for Haar files (haar_cli.h)
};

void parse_size(const std::string& text, int* width, int* height) {
  const std::size_t x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw std::invalid_argument(text);
    std::size_t used_w = 0, used_h = 0;
    const std::string w = text.substr(0, x), h = text.substr(x + 1);
    *width = std::stoi(w, &used_w);
    *height = std::stoi(h, &used_h);
    if (used_w != w.size() || used_h != h.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw CommandError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 960x540");
  }
  if (*width < 1 || *height < 1 || *width > 16384 || *height > 16384)
    throw CommandError("--size " + text + ": each side must be in 1..16384");
}

void run(const RelightArguments& args) {
  relight::RelightRequest request;
  request.scene_path = args.scene;
  request.transfer_path = args.transfer;
  request.environment_path = args.environment;
  request.output_path = args.output;
  request.layout = parse_layout_option(args.layout);
  request.lighting.yaw_pitch_roll_deg = parse_yaw_pitch_roll(args.rotate);
  if (!prt::sh::parse_window(args.window, &request.lighting.window))
    throw CommandError("--window " + args.window +
                       ": expected none|hanning|lanczos|laplacian|auto");
  request.lighting.window_strength = args.window_strength;
  request.exposure_ev = args.exposure;
  parse_size(args.size, &request.render.width, &request.render.height);
  if (args.spp < 1 || args.spp > 16)
    throw CommandError("--spp " + std::to_string(args.spp) + ": must be in 1..16 (N×N per pixel)");
  request.render.samples_per_axis = args.spp;
  request.camera = args.camera;
  request.vertex_colors_path = args.vertex_colors;
  request.csv_path = args.csv;
  request.turntable_frames = args.turntable;
  ProgressReporter progress(args.quiet);
  if (request.turntable_frames > 0) {
    progress.start_items("turntable " + args.output, request.turntable_frames, "frame");
    request.image_written = [&progress](int done, int total) { progress.set_done(done, total); };
  } else {  // one image: its rows (the phase starts with loading, which is short)
    progress.start("rendering " + args.output + " (rows)", request.render.height);
    request.render.rows_done = [&progress](int rows) { progress.advance(rows, 0); };
  }

  if (relight_if_haar(request, args.haar, args.quiet)) {
    progress.finish();
    return;
  }
  const relight::RelightSummary summary = relight::run_relight(request);
  progress.finish();
  if (args.quiet) return;
  std::printf("relit %zu vertices at SH order %d (%s%s%s); shading %.2f ms, rendering %.3f s",
              summary.vertex_count, summary.order, summary.window_note.c_str(),
              summary.layout_note.empty() ? "" : "; ", summary.layout_note.c_str(),
              1e3 * summary.shade_seconds, summary.render_seconds);
  if (summary.negative_vertices > 0)
    std::printf("; %zu vertices got negative radiance (SH ringing: try --window auto)",
                summary.negative_vertices);
  std::printf(".\nwrote:");
  for (const std::string& file : summary.files_written) std::printf(" %s", file.c_str());
  std::printf("\n");
}

void register_relight(CLI::App& app) {
  auto args = std::make_shared<RelightArguments>();
  CLI::App* cmd =
      app.add_subcommand("relight", "Shade a baked scene under an environment map and render it");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj) the file was baked from")
      ->required();
  cmd->add_option("transfer", args->transfer, "Coefficient file (.prt)")->required();
  cmd->add_option("environment", args->environment, "Environment map (.hdr, .exr, .pfm)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Image to write: .exr/.hdr linear, .png tone mapped")
      ->required();
  cmd->add_option("--layout", args->layout, "auto|latlong|angular|cross|faces")
      ->capture_default_str();
  cmd->add_option("--rotate", args->rotate, "Rotate the lighting: yaw,pitch,roll in degrees")
      ->capture_default_str();
  cmd->add_option("--window", args->window, "none|hanning|lanczos|laplacian|auto")
      ->capture_default_str();
  cmd->add_option("--window-strength", args->window_strength,
                  "Window strength (negative: the window's default)");
  cmd->add_option("--exposure", args->exposure, "Exposure in EV for PNG output")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--spp", args->spp, "N: N×N stratified samples per pixel")->capture_default_str();
  cmd->add_option("--camera", args->camera, "auto | NAME | ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg")
      ->capture_default_str();
  cmd->add_option("--vertex-colors", args->vertex_colors,
                  "Also write a .glb with COLOR_0 = exit radiance (linear)");
  cmd->add_option("--csv", args->csv, "Also write index,x,y,z,r,g,b per vertex");
  cmd->add_option("--turntable", args->turntable,
                  "Write N frames OUT_000… with the light turning about +Y");
  cmd->add_flag("--quiet", args->quiet, "Print nothing on success");
  add_haar_relight_options(cmd, &args->haar);
  cmd->callback([args] { run(*args); });
}

}  // namespace

PRT_REGISTER_COMMAND(30, register_relight);

}  // namespace prt::cli
