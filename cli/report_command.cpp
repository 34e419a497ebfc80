// `prt report SCENE ENV -o DIR [--quick] [--layout L] [--seed S] [--haar-cubes LIST]`: sweeps SH
// order, samples per vertex, bounces and storage precision, and Haar cube size × lighting terms,
// measures bake time, relight time, file size and error against an independent Monte Carlo
// ground truth, and writes results.csv, results.json, pareto.svg/png, error_vs_order.svg/png,
// haar_error_vs_terms.svg/png and summary.md (relight/report.h). --haar-cubes "8,16" overrides
// the Haar cube sizes of the mode, "none" leaves Haar out.
// `prt report --stability -o DIR [--quick]`: the stiff and extreme cases of
// relight/stability_report.h; exits with status 1 when any case fails.
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_parsing.h"
#include "command_registry.h"
#include "relight/report.h"
#include "relight/stability_report.h"

namespace prt::cli {
namespace {

struct ReportArguments {
  std::string scene, environment, output, layout = "auto", haar_cubes, auto_tolerances;
  bool quick = false, stability = false;
  uint64_t seed = 1;
  double budget = 110;
};

// "none" → empty list; "8,16" → {8, 16}; "" → the mode's default. Throws CommandError.
std::optional<std::vector<int>> parse_haar_cubes(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::vector<int> cubes;
  if (text == "none") return cubes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    int n = 0;
    try {
      n = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || n < 8 || n > 128 || (n & (n - 1)) != 0)
      throw CommandError("--haar-cubes: '" + item +
                         "' is not a power of two in [8, 128] (or pass none)");
    cubes.push_back(n);
  }
  return cubes;
}

// "none" → empty list; "0.01,0.05" → {0.01, 0.05}; "" → the mode's default. Throws
// CommandError.
std::optional<std::vector<double>> parse_auto_tolerances(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::vector<double> tolerances;
  if (text == "none") return tolerances;
  if (text.back() == ',') throw CommandError("--auto-tolerances: '" + text + "' ends with a comma");
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    double t = 0.0;
    try {
      t = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !(t > 0.0) || !(t < 1.0))
      throw CommandError("--auto-tolerances: '" + item +
                         "' is not a relative error in (0, 1) (or pass none)");
    tolerances.push_back(t);
  }
  return tolerances;
}

void run(const ReportArguments& a) {
  if (a.stability) {
    const int failed = prt::relight::run_stability_report(a.output, a.quick);
    std::printf("stability: %d failed case(s); report in %s\n", failed, a.output.c_str());
    if (failed > 0)
      throw CommandError(a.output + ": " + std::to_string(failed) + " stability case(s) failed");
    return;
  }
  if (a.scene.empty() || a.environment.empty())
    throw CommandError("report: SCENE and ENV are required (or pass --stability)");
  prt::relight::ReportOptions o;
  o.scene_path = a.scene;
  o.environment_path = a.environment;
  o.output_dir = a.output;
  o.quick = a.quick;
  o.seed = a.seed;
  o.ground_truth_budget_seconds = a.budget;
  o.layout = parse_layout_option(a.layout);
  o.haar_cubes = parse_haar_cubes(a.haar_cubes);
  o.auto_tolerances = parse_auto_tolerances(a.auto_tolerances);
  const prt::relight::ReportResult r = prt::relight::run_report(o);
  for (const std::string& f : r.files_written) std::printf("wrote %s\n", f.c_str());
}

void register_report(CLI::App& app) {
  auto args = std::make_shared<ReportArguments>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Error against run time of PRT settings, measured against a Monte Carlo ground truth");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj)");
  cmd->add_option("environment", args->environment, "Environment map (.hdr, .exr, .pfm)");
  cmd->add_option("-o,--output", args->output, "Output directory")->required();
  cmd->add_flag("--quick", args->quick, "Small sweep (under a minute on data/)");
  cmd->add_flag("--stability", args->stability, "Run the stability cases instead of the sweep");
  cmd->add_option("--layout", args->layout, "auto|latlong|angular|cross|faces")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Seed of the bakes and the ground truth")
      ->capture_default_str();
  cmd->add_option("--haar-cubes", args->haar_cubes,
                  "Haar cube sizes, e.g. 8,16,32 (default: quick 8; full 8,16), or none");
  cmd->add_option("--auto-tolerances", args->auto_tolerances,
                  "Tolerances of the prt bake --auto rows, e.g. 0.01,0.05 (default: quick 0.05; "
                  "full 0.01,0.05,0.1), or none");
  cmd->add_option("--ground-truth-budget", args->budget,
                  "Seconds the ground-truth refinement may take (full run)")
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
}

}  // namespace

PRT_REGISTER_COMMAND(40, register_report);

}  // namespace prt::cli
