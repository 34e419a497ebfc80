// `prt relight SCENE FILE.prt ENV -o OUT.(exr|png|hdr) [...]`: shade a baked scene under an
// environment map and render it (relight/relight_pipeline.h does the work; glossy files:
// relight/glossy_relight.h, with --eye for the CSV and vertex colours, --turntable-orbit and
// --material, relight/glossy_material_override.h);
// also `prt relight RESPONSES.prte -o OUT` and `--emitters RESPONSES.prte` (emitter_cli.h).
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake/glossy_emitter_gather.h"
#include "cli_parsing.h"
#include "command_registry.h"
#include "emitter_cli.h"
#include "glossy_cli.h"
#include "haar_cli.h"
#include "material_option.h"
#include "option_rules.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "prt/emitters/emitter_responses.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/formats/haar_transfer_file.h"
#include "relight/glossy_relight.h"
#include "relight/relight_pipeline.h"
#include "sh/env_map.h"
#include "sh/window.h"

namespace prt::cli {
namespace {

struct RelightArguments {
  std::string scene, transfer, environment, output;
  std::string layout = "auto";
  std::string rotate = "0,0,0";
  std::string window = "auto";
  double window_strength = -1.0;
  float exposure = 0.f;
  bool exposure_given = false;  // false: automatic (relight/auto_exposure.h)
  std::string size = "960x540";
  int spp = 3;
  std::string camera = "auto";
  std::string vertex_colors, csv;
  bool vertex_colors_tonemap = false;
  int turntable = 0;
  bool quiet = false;
  HaarRelightArguments haar;             // --terms, --approx for Haar files (haar_cli.h)
  EmitterRelightArguments emitters;      // --emitter, --emitters, --max-edge (emitter_cli.h)
  std::string eye;                       // glossy files: x,y,z for --csv and --vertex-colors
  std::string turntable_orbit = "both";  // glossy files: both | camera | light
  std::string target;                    // glossy turntables: the orbit's centre x,y,z
  std::vector<std::string> materials;    // glossy files: --material (cli/material_option.h)
};

glm::vec3 parse_point(const char* option, const std::string& text) {
  std::vector<double> v;
  std::size_t at = 0;
  try {
    while (at <= text.size()) {
      const std::size_t comma = std::min(text.find(',', at), text.size());
      const std::string part = text.substr(at, comma - at);
      std::size_t used = 0;
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
      at = comma + 1;
    }
  } catch (const std::exception&) {
    v.clear();
  }
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    throw UsageError(std::string(option) + " " + text + ": expected three finite numbers x,y,z");
  return {float(v[0]), float(v[1]), float(v[2])};
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

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
    throw UsageError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 960x540");
  }
  if (*width < 1 || *height < 1 || *width > 16384 || *height > 16384)
    throw UsageError("--size " + text + ": each side must be in 1..16384");
}

// Options that do not apply to this run are refused by name (`given` = on the command line).
void check_options(const RelightArguments& args, const CLI::App& cmd) {
  const auto given = [&cmd](const char* option) { return cmd.count(option) > 0; };
  check_exposure(args.exposure, cmd.get_option("--exposure")->as<std::string>());
  const std::string ext = lower_extension(args.output);
  if (given("--exposure") && ext != ".png")
    throw UsageError("--exposure applies to .png output; " + args.output +
                     " is written linear, without exposure");
  if (given("--window-strength")) {
    if (!std::isfinite(args.window_strength) || !(args.window_strength > 0))
      throw UsageError("--window-strength: must be a positive number");
    if (args.window == "none") throw UsageError("--window-strength needs a --window (it is none)");
    if (args.window == "auto")
      throw UsageError("--window-strength does not apply to --window auto (it chooses its own)");
  }
  if (args.vertex_colors_tonemap && args.vertex_colors.empty())
    throw UsageError("--vertex-colors-tonemap: needs --vertex-colors OUT.glb");
  if (args.spp < 1 || args.spp > 16)
    throw UsageError("--spp " + std::to_string(args.spp) + ": must be in 1..16 (N×N per pixel)");
  if (args.turntable < 0 || args.turntable > 3600)
    throw UsageError("--turntable " + std::to_string(args.turntable) + ": must be in 0..3600");
  // The kind of the coefficient file decides which options apply (a missing file is reported
  // by check_files, an unreadable one by the pipeline).
  if (!std::filesystem::exists(args.transfer)) return;
  const bool glossy = is_glossy_file(args.transfer);
  if (!glossy && given("--material"))
    throw UsageError("--material applies to glossy files (and to prt bake); " + args.transfer +
                     " is not one (its materials are baked into its coefficients)");
  for (const char* option : {"--eye", "--turntable-orbit"})
    if (!glossy && given(option))
      throw UsageError(std::string(option) + " applies to glossy files; " + args.transfer +
                       " is not one (its vertex values do not depend on the view)");
  if (glossy && !args.eye.empty() && args.csv.empty() && args.vertex_colors.empty())
    throw UsageError(
        "--eye applies to --csv and --vertex-colors (images are shaded toward the "
        "camera's eye)");
  if (given("--target") && !(glossy && args.turntable > 0 && args.turntable_orbit != "light"))
    throw UsageError(
        "--target applies to glossy turntables whose camera orbits (--turntable N with "
        "--turntable-orbit both|camera); the camera's own target is set with --camera");
  if (glossy && given("--turntable-orbit") && args.turntable == 0)
    throw UsageError("--turntable-orbit needs --turntable N");
  if (glossy && args.eye.empty() && (!args.csv.empty() || !args.vertex_colors.empty()))
    throw UsageError(args.transfer +
                     ": is a glossy file, whose vertex values depend on the view: --csv and "
                     "--vertex-colors need --eye x,y,z");
  const bool haar = prt::is_haar_transfer_file(args.transfer);
  for (const char* option : {"--terms", "--approx"})
    if (!haar && given(option))
      throw UsageError(std::string(option) + " applies to Haar files; " + args.transfer +
                       " holds SH coefficients");
  if (haar && given("--window") && args.window != "none")
    throw UsageError("--window applies to SH files; " + args.transfer + " holds Haar wavelets");
  for (const char* option : {"--emitters", "--max-edge"})
    if (haar && given(option))
      throw UsageError(std::string(option) + " applies to SH files; " + args.transfer +
                       " holds Haar wavelets");
  if (haar && given("--window-strength"))
    throw UsageError("--window-strength applies to SH files; " + args.transfer +
                     " holds Haar wavelets");
}

// What the run reads and writes (checked by main before the run, command_registry.h).
CommandFiles relight_files(const RelightArguments& args) {
  CommandFiles files;
  if (args.transfer.empty()) {  // a responses file alone
    files.add_input("emitter responses", args.scene);
  } else {
    files.add_scene(args.scene);
    files.add_input("coefficient file", args.transfer);
    files.add_environment(args.environment);
    if (!args.emitters.emitters.empty())
      files.add_input("emitter responses", args.emitters.emitters);
  }
  if (args.turntable > 0) {
    for (int frame = 0; frame < args.turntable; ++frame)
      files.add_output_file("--turntable frame", relight::turntable_frame_path(args.output, frame),
                            {".exr", ".hdr", ".png"}, "an image");
  } else {
    files.add_output_file("-o", args.output, {".exr", ".hdr", ".png"}, "an image");
  }
  files.add_output_file("--vertex-colors", args.vertex_colors, {".glb"}, "a binary glTF");
  files.add_output_file("--csv", args.csv, {".csv"});
  return files;
}

// What to say about vertices with a negative channel (SH ringing), true for the window used.
std::string ringing_advice(const std::string& window) {
  if (window == "none") return "SH ringing: try --window auto";
  if (window == "auto") return "SH ringing that the auto window could not remove";
  return "SH ringing that the " + window + " window did not remove: try --window auto";
}

// `prt relight RESPONSES.prte -o OUT`: a responses file alone (no scene, no environment).
void check_responses_alone(const RelightArguments& args, const CLI::App& cmd) {
  if (!args.transfer.empty() || !args.environment.empty())
    throw UsageError(args.scene + " holds emitter responses: give it alone (prt relight " +
                     "RESPONSES.prte -o OUT), or add it to an SH relight with --emitters");
  for (const char* option : {"--layout", "--rotate", "--window", "--window-strength", "--turntable",
                             "--terms", "--approx", "--material", "--eye", "--turntable-orbit"})
    if (cmd.count(option) > 0)
      throw UsageError(std::string(option) +
                       " does not apply to emitter responses (no "
                       "environment lighting)");
}

// The command line, before the files are checked: the mode (a responses file alone, or SCENE
// FILE ENV) and the options that apply to it. A lone argument that is missing is left to the
// file check ("no such file"); one that is not a readable responses file is named with its
// problem (exit 1).
void check_usage(const RelightArguments& args, const CLI::App& cmd) {
  if (args.transfer.empty() && args.environment.empty()) {
    std::error_code ec;
    if (!std::filesystem::exists(args.scene, ec)) return;
    check_responses_file(args.scene);
    check_responses_alone(args, cmd);
  } else if (prt::is_emitter_responses_file(args.scene)) {
    check_responses_alone(args, cmd);
  } else if (args.transfer.empty() || args.environment.empty()) {
    throw UsageError("expected SCENE FILE.prt ENVIRONMENT (or an emitter responses file alone)");
  } else if (prt::is_emitter_responses_file(args.transfer)) {
    throw UsageError(args.transfer +
                     " holds emitter responses, not SH transfer: relight it alone "
                     "or add it to an SH relight with --emitters");
  }
  check_options(args, cmd);
}

void run(const RelightArguments& args) {
  const bool responses = prt::is_emitter_responses_file(args.scene);
  const std::vector<scene::MaterialOverride> overrides = parse_material_options(args.materials);
  relight::RelightRequest request;
  request.scene_path = args.scene;
  request.transfer_path = responses ? args.scene : args.transfer;
  request.environment_path = args.environment;
  request.output_path = args.output;
  request.layout = parse_layout_option(args.layout);
  request.lighting.yaw_pitch_roll_deg = parse_yaw_pitch_roll(args.rotate);
  if (!prt::sh::parse_window(args.window, &request.lighting.window))
    throw UsageError("--window " + args.window + ": expected none|hanning|lanczos|laplacian|auto");
  request.lighting.window_strength = args.window_strength;
  if (args.exposure_given) request.exposure_ev = args.exposure;
  parse_size(args.size, &request.render.width, &request.render.height);
  request.render.samples_per_axis = args.spp;
  request.camera = args.camera;
  request.vertex_colors_path = args.vertex_colors;
  request.vertex_colors_tonemapped = args.vertex_colors_tonemap;
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

  if (relight_if_emitter_responses(request, args.emitters, args.quiet)) {
    progress.finish();
    return;
  }
  apply_emitter_options(args.emitters, &request);
  if (relight_if_haar(request, args.haar, args.quiet)) {
    progress.finish();
    return;
  }
  relight::RelightSummary summary;
  if (is_glossy_file(args.transfer)) {
    relight::GlossyRelightOptions glossy;
    if (!args.eye.empty()) glossy.eye = parse_point("--eye", args.eye);
    if (!args.target.empty()) glossy.orbit_centre = parse_point("--target", args.target);
    glossy.turntable = args.turntable_orbit == "camera"  ? relight::GlossyTurntable::kCamera
                       : args.turntable_orbit == "light" ? relight::GlossyTurntable::kLight
                                                         : relight::GlossyTurntable::kBoth;
    glossy.material_overrides = overrides;
    glossy.gather_emitters = [](const scene::Scene& scene, const prt::GlossyTransferData& data,
                                const prt::EmitterResponses& emitters) {
      return bake::gather_glossy_emitters(scene, data, emitters);  // bake/glossy_emitter_gather.h
    };
    summary = relight::run_glossy_relight(request, glossy);
  } else {
    summary = relight::run_relight(request);
  }
  progress.finish();
  if (args.quiet) return;
  std::printf("relit %zu vertices at SH order %d (%s%s%s); shading %.2f ms, rendering %.3f s",
              summary.vertex_count, summary.order, summary.window_note.c_str(),
              summary.layout_note.empty() ? "" : "; ", summary.layout_note.c_str(),
              1e3 * summary.shade_seconds, summary.render_seconds);
  if (summary.negative_vertices > 0)
    std::printf("; %zu vertices got negative radiance (%s)", summary.negative_vertices,
                ringing_advice(args.window).c_str());
  std::printf(".\n%s\n", describe_view(request, summary).c_str());
  std::printf("wrote:");
  for (const std::string& file : summary.files_written) std::printf(" %s", file.c_str());
  std::printf("\n");
}

Command register_relight(CLI::App& app) {
  auto args = std::make_shared<RelightArguments>();
  CLI::App* cmd =
      app.add_subcommand("relight", "Shade a baked scene under an environment map and render it");
  cmd->add_option("scene", args->scene,
                  "Scene (.glb, .gltf, .obj) the file was baked from, or emitter responses "
                  "(.prte, prt radiosity --per-emitter) to relight alone")
      ->required();
  cmd->add_option("transfer", args->transfer,
                  "Coefficient file (.prt: SH or Haar), glossy transfer file (.prtg) or its CPCA "
                  "compression (.prtq, prt compress)");
  cmd->add_option("environment", args->environment, "Environment map (.hdr, .exr, .pfm)");
  cmd->add_option("-o,--output", args->output, "Image to write: .exr/.hdr linear, .png tone mapped")
      ->required();
  cmd->add_option("--layout", args->layout, "auto|latlong|angular|cross|faces")
      ->capture_default_str();
  cmd->add_option("--rotate", args->rotate, "Rotate the lighting: yaw,pitch,roll in degrees")
      ->capture_default_str();
  cmd->add_option("--window", args->window,
                  "none|hanning|lanczos|laplacian|auto (auto: the weakest window, none or "
                  "Laplacian, that keeps the irradiance non-negative: no ringing)")
      ->capture_default_str();
  cmd->add_option("--window-strength", args->window_strength,
                  "Strength of a hanning|lanczos|laplacian window (default: the window's own)");
  cmd->add_option("--exposure", args->exposure,
                  "Exposure in EV, for .png output only (default: automatic, the median vertex "
                  "luminance brought to 0.3 before the filmic curve, rounded to 1/4 EV; the "
                  "output says which)");
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--spp", args->spp, "N: N×N stratified samples per pixel")->capture_default_str();
  cmd->add_option("--camera", args->camera,
                  "auto | NAME | ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg (auto: the scene's first "
                  "camera, else an object from outside, a room from inside or through its open "
                  "side; the output says which)")
      ->capture_default_str();
  cmd->add_option("--vertex-colors", args->vertex_colors,
                  "Also write a .glb with COLOR_0 = exit radiance (linear) and an unlit white "
                  "material (KHR_materials_unlit), so viewers show the colours as baked");
  cmd->add_flag("--vertex-colors-tonemap", args->vertex_colors_tonemap,
                "For LDR viewers: COLOR_0 gets the PNG's exposure and filmic curve (values in "
                "[0, 1], still linear; the viewer's sRGB output then matches the PNG)");
  cmd->add_option("--csv", args->csv,
                  "Also write a .csv of index,x,y,z,r,g,b per vertex (the first frame's)");
  cmd->add_option("--turntable", args->turntable,
                  "Write N frames OUT_000… with the light turning about +Y (glossy files: and "
                  "the camera orbiting, see --turntable-orbit; an interrupted turntable keeps "
                  "the frames it finished)");
  cmd->add_option("--turntable-orbit", args->turntable_orbit,
                  "Glossy files: what the turntable turns: both (light and camera), camera "
                  "(highlights slide under fixed light) or light")
      ->check(CLI::IsMember({"both", "camera", "light"}))
      ->capture_default_str();
  cmd->add_option("--target", args->target,
                  "Glossy turntables: the point x,y,z whose vertical axis the camera orbits "
                  "(default: the centre of the scene's bounding box)");
  cmd->add_option("--eye", args->eye,
                  "Glossy files: the eye point x,y,z (scene units) toward which --csv and "
                  "--vertex-colors are shaded (images use the camera's eye)");
  cmd->add_option("--material", args->materials,
                  "Glossy files: replace a material's BRDF for shading, without baking again: "
                  "NAME=MODEL[:KEY=VALUE,...] as for prt bake --material. Only the vertex's own "
                  "BRDF changes; light interreflected in the bake stays as baked (with the "
                  "baked materials) and so do the tangent frames. Repeatable")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_flag("--quiet", args->quiet, "No summary (warnings still go to stderr)");
  add_haar_relight_options(cmd, &args->haar);
  add_emitter_relight_options(cmd, &args->emitters);
  const auto check = [args, cmd] {
    args->exposure_given = cmd->count("--exposure") > 0;
    check_usage(*args, *cmd);
  };
  return {cmd, check, [args] { return relight_files(*args); }, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(30, register_relight);

}  // namespace prt::cli
