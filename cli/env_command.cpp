// `prt env FILE... [--layout L] [--order N] [--window W] [--window-strength X] [--irradiance]
//                  [--rotate yaw,pitch,roll] [--json] [--strict] [--quiet]`
// Projects environment maps onto SH and prints the RGB coefficients.
//   * Radiance coefficients L_lm by default; --irradiance prints E_lm = A_l·L_lm (A_l the
//     clamped-cosine factors of sh/zonal.h, so a constant radiance L gives E = πL).
//   * Order of operations: project → window (band factors h_l) → rotate → irradiance.
//   * --rotate turns the environment by M = Ry(yaw)·Rx(pitch)·Rz(roll) (degrees; sh/rotation.h):
//     a light from direction d ends up coming from M·d.
//   * NaN/Inf/negative texels are skipped and reported; --strict makes them an error.
//   * Text output: a header with the layout, order, basis and frame, then one line per index
//     k = l(l+1)+m with l, m, r, g, b. --json: one object per file (an array for several files).
//   * Long projections (high orders; maps that are not lat-long take the direct sum) show progress
//     on stderr (cli/progress_reporter.h); --quiet silences it.
// Errors: one line "PATH: problem", exit status 1.
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
#include "progress_reporter.h"
#include "relight/image_io.h"
#include "sh/basis.h"
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

Settings parse_settings(const EnvArguments& args) {
  Settings settings;
  settings.layout = parse_layout_option(args.layout);
  if (!prt::sh::parse_window(args.window, &settings.window))
    throw CommandError("--window " + args.window +
                       ": unknown window (none, hanning, lanczos, laplacian or auto)");
  if (args.order < 1 || args.order > prt::sh::kMaxOrder)
    throw CommandError("--order " + std::to_string(args.order) + ": must be in [1, " +
                       std::to_string(prt::sh::kMaxOrder) + "]");
  if (!std::isfinite(args.window_strength))
    throw CommandError("--window-strength: must be a finite number");
  if (!args.rotate.empty()) {
    const std::array<double, 3> angles = parse_yaw_pitch_roll(args.rotate);
    if (args.order > prt::sh::kMaxRotationOrder)
      throw CommandError("--rotate: orders above " + std::to_string(prt::sh::kMaxRotationOrder) +
                         " cannot be rotated");
    settings.yaw_pitch_roll = angles;
  }
  return settings;
}

// Texels along a great circle: a rough measure of the bands a map can resolve (≈ half of it).
int great_circle_texels(const prt::sh::EnvMap& env) {
  switch (env.layout) {
    case prt::sh::EnvLayout::LatLong:
      return env.width;
    case prt::sh::EnvLayout::Angular:
      return env.width;
    case prt::sh::EnvLayout::Cross:
      return 4 * (env.width / 3);
    case prt::sh::EnvLayout::Faces:
      return 4 * env.width;
  }
  return env.width;
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
  std::string layout_note;
  const prt::sh::EnvMap env = relight::read_environment(path, settings.layout, &layout_note);
  const int order = args.order;
  const int n2 = prt::sh::coefficient_count(order);

  // Resolution: a map with C texels around a great circle resolves bands up to about C/2.
  const int circle = great_circle_texels(env);
  if (order - 1 > circle)
    throw CommandError(path + ": " + std::to_string(env.width) + "x" + std::to_string(env.height) +
                       " is far too small for order " + std::to_string(order) +
                       " (it resolves bands up to about l = " + std::to_string(circle / 2) + ")");
  std::vector<std::string> warnings;
  if (order - 1 > circle / 2)
    warnings.push_back(path + ": " + std::to_string(env.width) + "x" + std::to_string(env.height) +
                       " resolves bands up to about l = " + std::to_string(circle / 2) +
                       "; order " + std::to_string(order) +
                       " asks for l = " + std::to_string(order - 1) + " (aliasing)");

  prt::sh::ProjectionStats stats;
  const std::string phase = "projecting " + path + " to order " + std::to_string(order);
  std::vector<double> coefficients =
      prt::sh::project(env, order, &stats, progress.projection(phase));
  progress.finish();
  if (coefficients.size() != 3 * static_cast<std::size_t>(n2))
    throw CommandError(path + ": projection failed (invalid map)");
  const std::size_t skipped = stats.skipped_texels();
  std::string skipped_note = "skipped texels: none";
  if (skipped > 0) {
    skipped_note = "skipped texels: " + std::to_string(skipped) + " (" +
                   std::to_string(stats.nan_texels) + " NaN, " + std::to_string(stats.inf_texels) +
                   " Inf, " + std::to_string(stats.negative_texels) + " negative)";
    if (args.strict)
      throw CommandError(path + ": " + std::to_string(skipped) +
                         " texels are NaN, Inf or negative (" + std::to_string(stats.nan_texels) +
                         " NaN, " + std::to_string(stats.inf_texels) + " Inf, " +
                         std::to_string(stats.negative_texels) + " negative; --strict)");
  }

  // Window.
  nlohmann::json window_json;
  prt::sh::Window window = settings.window;
  double strength = args.window_strength;
  if (window == prt::sh::Window::Auto) {
    const prt::sh::WindowChoice choice = prt::sh::choose_window_auto(coefficients.data(), 3, order);
    window = choice.window;
    strength = choice.strength;
    window_json["requested"] = "auto";
    window_json["min_irradiance_before"] = choice.min_irradiance_before;
    window_json["min_irradiance_after"] = choice.min_irradiance_after;
    if (choice.min_irradiance_after < 0)
      warnings.push_back(path + ": no window keeps the irradiance non-negative (minimum " +
                         std::to_string(choice.min_irradiance_after) + ")");
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

  for (const std::string& warning : warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());

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
  j["skipped_texels"] = {{"nan", stats.nan_texels},
                         {"inf", stats.inf_texels},
                         {"negative", stats.negative_texels},
                         {"solid_angle_used_sr", stats.solid_angle_sum}};
  nlohmann::json list = nlohmann::json::array();
  if (args.json)  // (a million rows at order 1000: only the output asked for is built)
    for (int k = 0; k < n2; ++k)
      list.push_back({coefficients[k], coefficients[n2 + k], coefficients[2 * n2 + k]});
  j["coefficients"] = list;

  std::string& text = result.text;
  text += "# " + path + ": " + layout_note + ", " + std::to_string(env.width) + "x" +
          std::to_string(env.height) + "\n";
  text += "# order " + std::to_string(order) + " (" + std::to_string(n2) +
          " coefficients per channel); basis: " + prt::sh::kBasisConvention + "; frame " + kFrame + "\n";
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
  text += "\n# " + skipped_note + "\n";
  text += "#  l    m                 r                g                b\n";
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) {
      const int k = prt::sh::index(l, m);
      text += format_row(l, m, coefficients[k], coefficients[n2 + k], coefficients[2 * n2 + k]);
    }
  return result;
}

void run(const EnvArguments& args) {
  const Settings settings = parse_settings(args);
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

void register_env(CLI::App& app) {
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
                  "Window parameter (Hanning width, Lanczos exponent, Laplacian lambda); "
                  "0 = the window's default");
  cmd->add_flag("--irradiance", args->irradiance,
                "Print irradiance E_lm = A_l L_lm instead of radiance");
  cmd->add_option("--rotate", args->rotate,
                  "yaw,pitch,roll in degrees: M = Ry(yaw) Rx(pitch) Rz(roll)");
  cmd->add_flag("--json", args->json, "Print JSON (an array when several files are given)");
  cmd->add_flag("--strict", args->strict, "Fail on NaN, Inf or negative texels");
  cmd->add_flag("--quiet", args->quiet, "No progress lines on stderr");
  cmd->callback([args] { run(*args); });
}

}  // namespace

PRT_REGISTER_COMMAND(10, register_env);

}  // namespace prt::cli
