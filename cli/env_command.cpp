// `prt env FILE... [--layout L] [--order N] [--window W] [--window-strength X] [--irradiance]
//                  [--rotate yaw,pitch,roll] [--json] [--strict] [--quiet]`
// Projects environment maps onto SH and prints the RGB coefficients.
//   * Radiance coefficients L_lm by default; --irradiance prints E_lm = A_l·L_lm (A_l the
//     clamped-cosine factors of sh/zonal.h, so a constant radiance L gives E = πL).
//   * Order of operations: project → window (band factors h_l) → rotate → irradiance.
//   * --rotate turns the environment by M = Ry(yaw)·Rx(pitch)·Rz(roll) (degrees; sh/rotation.h):
//     a light from direction d ends up coming from M·d.
//   * Maps are read, screened and checked as every command does (relight/environment_input.h):
//     NaN/Inf texels are taken as black and negative channels clamped to 0, with a warning
//     (--strict makes them an error); a map too coarse for --order is refused, one that aliases
//     is warned about.
//   * Text output: a header with the layout, order, basis and frame, then one line per index
//     k = l(l+1)+m with l, m, r, g, b. --json: one object per file (an array for several files).
//   * Long projections (high orders; maps that are not lat-long take the direct sum) show progress
//     on stderr (cli/progress_reporter.h); --quiet silences it.
// Errors: one line "PATH: problem", exit status 1 (2 for a bad option).
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_parsing.h"
#include "command_registry.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "relight/environment_input.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_map.h"
#include "sh/projection.h"
#include "sh/rotation.h"
#include "sh/window.h"
#include "sh/zonal.h"

namespace prt::cli {
namespace {

constexpr const char* kFrame = "glTF: right-handed, +Y up";

struct EnvArguments {
  std::vector<std::string> files;
  std::string layout = "auto";
  int order = 3;
  std::string window = "none";
  double window_strength = 0.0;
  bool irradiance = false;
  std::string rotate;
  bool json = false;
  bool strict = false;
  bool quiet = false;
};

struct Settings {
  std::optional<prt::sh::EnvLayout> layout;
  prt::sh::Window window = prt::sh::Window::None;
  std::optional<std::array<double, 3>> yaw_pitch_roll;
};

Settings parse_settings(const EnvArguments& args, const CLI::App& cmd) {
  Settings settings;
  settings.layout = parse_layout_option(args.layout);
  if (!prt::sh::parse_window(args.window, &settings.window))
    throw UsageError("--window " + args.window +
                     ": unknown window (none, hanning, lanczos, laplacian or auto)");
  if (args.order < 1 || args.order > prt::sh::kMaxOrder)
    throw UsageError("--order " + std::to_string(args.order) + ": must be in [1, " +
                     std::to_string(prt::sh::kMaxOrder) + "]");
  if (cmd.count("--window-strength") > 0) {
    if (!std::isfinite(args.window_strength) || !(args.window_strength > 0))
      throw UsageError("--window-strength: must be a positive number");
    if (settings.window == prt::sh::Window::None)
      throw UsageError("--window-strength needs a --window (it is none)");
    if (settings.window == prt::sh::Window::Auto)
      throw UsageError("--window-strength does not apply to --window auto (it chooses its own)");
  }
  if (!args.rotate.empty()) {
    const std::array<double, 3> angles = parse_yaw_pitch_roll(args.rotate);
    if (args.order > prt::sh::kMaxRotationOrder)
      throw UsageError("--rotate: orders above " + std::to_string(prt::sh::kMaxRotationOrder) +
                       " cannot be rotated (--order " + std::to_string(args.order) + ")");
    settings.yaw_pitch_roll = angles;
  }
  return settings;
}

struct FileResult {
  nlohmann::json json;
  std::string text;
};

std::string format_row(int l, int m, double r, double g, double b) {
  char line[160];
  std::snprintf(line, sizeof line, "%3d %4d  %16.9g %16.9g %16.9g\n", l, m, r, g, b);
  return line;
}

FileResult process(const std::string& path, const EnvArguments& args, const Settings& settings,
                   ProgressReporter& progress) {
  // Read, screen and check against the order (relight/environment_input.h): refusals throw,
  // warnings are printed as "PATH: warning: ..." and kept for the JSON.
  relight::EnvironmentUse use;
  use.sh_order = args.order;
  use.strict = args.strict;
  relight::EnvironmentInput input = relight::read_checked_environment(path, settings.layout, use);
  const prt::sh::EnvMap& env = input.env;
  const std::string& layout_note = input.layout_note;
  const prt::sh::EnvTexelReport& texels = input.texels;
  std::vector<std::string> warnings = input.warnings;
  const int order = args.order;
  const int n2 = prt::sh::coefficient_count(order);

  const std::string phase = "projecting " + path + " to order " + std::to_string(order);
  std::vector<double> coefficients =
      prt::sh::project(env, order, nullptr, progress.projection(phase));
  progress.finish();
  if (coefficients.size() != 3 * static_cast<std::size_t>(n2))
    throw CommandError(path + ": projection failed (invalid map)");
  std::string texel_note = "texels: all finite and non-negative";
  if (texels.invalid_texels() + texels.negative_texels > 0)
    texel_note = "texels: " + std::to_string(texels.nan_texels) + " NaN and " +
                 std::to_string(texels.inf_texels) + " Inf (taken as black), " +
                 std::to_string(texels.negative_texels) + " with a negative channel (clamped to 0)";

  // Window.
  nlohmann::json window_json;
  prt::sh::Window window = settings.window;
  double strength = args.window_strength;
  if (window == prt::sh::Window::Auto) {
    const prt::sh::WindowChoice choice =
        prt::sh::choose_window_auto(coefficients.data(), 3, order,
                                    progress.projection("choosing the window for " + path +
                                                        " at order " + std::to_string(order)));
    progress.finish();
    window = choice.window;
    strength = choice.strength;
    window_json["requested"] = "auto";
    window_json["min_irradiance_before"] = choice.min_irradiance_before;
    window_json["min_irradiance_after"] = choice.min_irradiance_after;
    if (choice.min_irradiance_after < 0) {
      warnings.push_back("no window keeps the irradiance non-negative (minimum " +
                         std::to_string(choice.min_irradiance_after) + ")");
      std::fprintf(stderr, "%s: warning: %s\n", path.c_str(), warnings.back().c_str());
    }
  } else if (!(strength > 0)) {
    strength = prt::sh::default_window_strength(window, order);
  }
  window_json["name"] = prt::sh::window_name(window);
  window_json["strength"] = window == prt::sh::Window::None ? 0.0 : strength;
  const std::vector<double> factors = prt::sh::window_band_factors(window, order, strength);
  window_json["band_factors"] = factors;
  for (int c = 0; c < 3; ++c) prt::sh::convolve_zonal(order, factors.data(), &coefficients[c * n2]);

  // Rotation.
  nlohmann::json rotation_json = nullptr;
  if (settings.yaw_pitch_roll) {
    const auto& a = *settings.yaw_pitch_roll;
    const std::array<double, 9> matrix = prt::sh::rotation_from_yaw_pitch_roll(a[0], a[1], a[2]);
    const prt::sh::Rotation rotation(order, matrix);
    std::vector<double> rotated(coefficients.size());
    for (int c = 0; c < 3; ++c) rotation.apply(&coefficients[c * n2], &rotated[c * n2]);
    coefficients.swap(rotated);
    rotation_json = {{"yaw_deg", a[0]},
                     {"pitch_deg", a[1]},
                     {"roll_deg", a[2]},
                     {"matrix", matrix},
                     {"convention",
                      "M = Ry(yaw)*Rx(pitch)*Rz(roll), "
                      "row-major; light from d moves to M*d"}};
  }

  // Irradiance.
  if (args.irradiance) {
    std::vector<double> band_factors(order);
    for (int l = 0; l < order; ++l) band_factors[l] = prt::sh::clamped_cosine_band_factor(l);
    for (int c = 0; c < 3; ++c)
      prt::sh::convolve_zonal(order, band_factors.data(), &coefficients[c * n2]);
  }

  FileResult result;
  const char* quantity = args.irradiance ? "irradiance" : "radiance";
  nlohmann::json& j = result.json;
  j["file"] = path;
  j["width"] = env.width;
  j["height"] = env.height;
  j["order"] = order;
  j["basis"] = prt::sh::kBasisConvention;
  j["frame"] = kFrame;
  j["layout"] = prt::sh::layout_name(env.layout);
  j["layout_note"] = layout_note;
  j["window"] = window_json;
  j["quantity"] = quantity;
  j["rotation"] = rotation_json;
  j["skipped_texels"] = {{"nan", texels.nan_texels},
                         {"inf", texels.inf_texels},
                         {"solid_angle_used_sr", 4.0 * prt::sh::kPi - texels.invalid_solid_angle}};
  j["clamped_texels"] = {{"negative", texels.negative_texels}};
  j["warnings"] = warnings;
  nlohmann::json list = nlohmann::json::array();
  if (args.json)  // (a million rows at order 1000: only the output asked for is built)
    for (int k = 0; k < n2; ++k)
      list.push_back({coefficients[k], coefficients[n2 + k], coefficients[2 * n2 + k]});
  j["coefficients"] = list;

  std::string& text = result.text;
  text += "# " + path + ": " + layout_note + ", " + std::to_string(env.width) + "x" +
          std::to_string(env.height) + "\n";
  text += "# order " + std::to_string(order) + " (" + std::to_string(n2) +
          " coefficients per channel); basis: " + prt::sh::kBasisConvention + "; frame " + kFrame +
          "\n";
  text += std::string("# quantity ") + quantity +
          (args.irradiance ? " (E_lm = A_l L_lm; constant radiance L gives E = pi L)" : "") +
          "; window " + prt::sh::window_name(window);
  if (window != prt::sh::Window::None) text += " (strength " + std::to_string(strength) + ")";
  if (settings.window == prt::sh::Window::Auto) text += ", chosen by auto";
  if (settings.yaw_pitch_roll) {
    const auto& a = *settings.yaw_pitch_roll;
    text += "; rotation yaw " + std::to_string(a[0]) + ", pitch " + std::to_string(a[1]) +
            ", roll " + std::to_string(a[2]) + " deg";
  }
  text += "\n# " + texel_note + "\n";
  text += "#  l    m                 r                g                b\n";
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) {
      const int k = prt::sh::index(l, m);
      text += format_row(l, m, coefficients[k], coefficients[n2 + k], coefficients[2 * n2 + k]);
    }
  return result;
}

void run(const EnvArguments& args, const CLI::App& cmd) {
  const Settings settings = parse_settings(args, cmd);
  std::vector<FileResult> results;
  ProgressReporter progress(args.quiet);
  for (const std::string& file : args.files)
    results.push_back(process(file, args, settings, progress));
  if (args.json) {
    if (results.size() == 1) {
      std::printf("%s\n", results[0].json.dump(2).c_str());
    } else {
      nlohmann::json all = nlohmann::json::array();
      for (const FileResult& r : results) all.push_back(r.json);
      std::printf("%s\n", all.dump(2).c_str());
    }
    return;
  }
  for (std::size_t i = 0; i < results.size(); ++i)
    std::printf("%s%s", i ? "\n" : "", results[i].text.c_str());
}

Command register_env(CLI::App& app) {
  auto args = std::make_shared<EnvArguments>();
  CLI::App* cmd = app.add_subcommand(
      "env", "Project environment maps (.hdr, .exr, .pfm) onto spherical harmonics");
  cmd->add_option("files", args->files,
                  "Environment maps; for --layout faces a pattern with %s (px, nx, py, ny, pz, nz)")
      ->required();
  cmd->add_option("--layout", args->layout, "auto|latlong|angular|cross|faces (auto: by aspect)")
      ->default_str("auto");
  cmd->add_option("--order", args->order, "SH order n: bands 0..n-1, n^2 coefficients")
      ->default_str("3");
  cmd->add_option("--window", args->window, "none|hanning|lanczos|laplacian|auto")
      ->default_str("none");
  cmd->add_option("--window-strength", args->window_strength,
                  "Window parameter (Hanning width, Lanczos exponent, Laplacian lambda; "
                  "default: the window's own)");
  cmd->add_flag("--irradiance", args->irradiance,
                "Print irradiance E_lm = A_l L_lm instead of radiance");
  cmd->add_option("--rotate", args->rotate,
                  "yaw,pitch,roll in degrees: M = Ry(yaw) Rx(pitch) Rz(roll)");
  cmd->add_flag("--json", args->json, "Print JSON (an array when several files are given)");
  cmd->add_flag("--strict", args->strict, "Fail on NaN, Inf or negative texels");
  cmd->add_flag("--quiet", args->quiet, "No progress lines on stderr");
  const auto files = [args] {
    CommandFiles f;  // no files are written: only stdout must not be an input
    for (const std::string& file : args->files) f.add_environment(file);
    return f;
  };
  return {cmd, [args, cmd] { parse_settings(*args, *cmd); }, files,
          [args, cmd] { run(*args, *cmd); }};
}

}  // namespace

PRT_REGISTER_COMMAND(10, register_env);

}  // namespace prt::cli
