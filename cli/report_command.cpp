// `prt report SCENE ENV -o DIR [--quick] [--layout L] [--seed S] [--haar-cubes LIST]`: sweeps SH
// order, samples per vertex, bounces and storage precision, and Haar cube size × lighting terms,
// measures bake time, relight time, file size and error against an independent Monte Carlo
// ground truth, and writes results.csv, results.json, pareto.svg/png, error_vs_order.svg/png,
// haar_error_vs_terms.svg/png and summary.md (report/report.h). --haar-cubes "8,16" overrides
// the Haar cube sizes of the mode, "none" leaves Haar out.
// `prt report --stability -o DIR [--quick]`: the stiff and extreme cases of
// report/stability_report.h; exits with status 1 when any case fails.
// `prt report --radiosity SCENE -o DIR [--emission M=rgb] [--albedo M=rgb] [--quick]
// [--max-edges LIST] [--methods LIST] [--solvers LIST] [--ground-truth-patches K]
// [--ground-truth-samples S]`: radiosity error against cost for every form-factor method × patch
// count × solver, against a path-traced ground truth (report/radiosity_report.h).
// `prt report --sun-study -o DIR [--quick] [--roughness LIST] ...`: where SH fails, a sun on
// glossy surfaces (report_sun_study.h, report/sun_study.h).
// `prt report --translucency SCENE ENV -o DIR [--subsurface P] [--more-scenes A,B] ...`: the
// real-time approximations of subsurface scattering against the dipole (report_translucency.h).
// `prt report --glossy SCENE ENV -o DIR [--quick] [--seed S] [--material M ...]`: glossy PRT
// error against cost (order, samples, bounces, CPCA size) against the glossy ground truth, with
// `prt bake`'s material overrides (cli/glossy_report_cli.h). --material needs --glossy.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_parsing.h"
#include "command_registry.h"
#include "glossy_report_cli.h"
#include "material_option.h"
#include "option_rules.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "radiosity/form_factors.h"
#include "radiosity/solver.h"
#include "report/glossy_report.h"
#include "report/radiosity_report.h"
#include "report/report.h"
#include "report/stability_report.h"
#include "report_ssao.h"
#include "report_sun_study.h"
#include "report_translucency.h"

namespace prt::cli {
namespace {

struct ReportArguments {
  std::string scene, environment, output, layout = "auto", haar_cubes, auto_tolerances;
  bool quick = false, stability = false, quiet = false, radiosity = false, glossy = false;
  uint64_t seed = 1;
  double budget = 110;
  std::vector<std::string> materials;  // --glossy: --material overrides
  // --radiosity
  std::vector<std::string> emission, albedo;
  std::string max_edges, methods, solvers;
  int ground_truth_patches = 0, ground_truth_samples = 0, rays = 1024, hemicube = 64;
  SunStudyArguments sun;
  SsaoReportArguments ssao;  // --ssao (report_ssao.h)
  TranslucencyArguments translucency;
  uint64_t memory_limit = 0;  // --memory-limit (option_rules.h): the SH and glossy sweeps' bakes
};

// Options of one mode only, refused by name in the others.
const char* const kRadiosityOnly[] = {"--emission",
                                      "--albedo",
                                      "--max-edges",
                                      "--methods",
                                      "--solvers",
                                      "--ground-truth-patches",
                                      "--ground-truth-samples",
                                      "--rays",
                                      "--hemicube"};
const char* const kEnvironmentOnly[] = {"--layout", "--haar-cubes", "--auto-tolerances",
                                        "--ground-truth-budget"};

// A comma-separated option: "" → nullopt (the mode's default); "none" → an empty list; else
// every item through parse(), which returns nullopt for an item it refuses. Throws CommandError
// naming the option and the item ("is not <expected>").
template <class T, class Parse>
std::optional<std::vector<T>> parse_list(const std::string& option, const std::string& text,
                                         const std::string& expected, Parse parse) {
  if (text.empty()) return std::nullopt;
  std::vector<T> items;
  if (text == "none") return items;
  if (text.back() == ',') throw CommandError(option + ": '" + text + "' ends with a comma");
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const std::optional<T> value = parse(item);
    if (!value)
      throw UsageError(option + ": '" + item + "' is not " + expected + " (or pass none)");
    items.push_back(*value);
  }
  return items;
}

// The whole item as a number (std::stoi / std::stod), else nullopt.
template <class T>
std::optional<T> whole_number(const std::string& item) {
  std::size_t used = 0;
  T value{};
  try {
    if constexpr (std::is_integral_v<T>)
      value = static_cast<T>(std::stoi(item, &used));
    else
      value = static_cast<T>(std::stod(item, &used));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || used != item.size()) return std::nullopt;
  return value;
}

std::optional<std::vector<int>> parse_haar_cubes(const std::string& text) {
  return parse_list<int>("--haar-cubes", text, "a power of two in [8, 128]",
                         [](const std::string& item) -> std::optional<int> {
                           const std::optional<int> n = whole_number<int>(item);
                           if (!n || *n < 8 || *n > 128 || (*n & (*n - 1)) != 0)
                             return std::nullopt;
                           return n;
                         });
}

std::optional<std::vector<double>> parse_auto_tolerances(const std::string& text) {
  return parse_list<double>("--auto-tolerances", text, "a relative error in (0, 1)",
                            [](const std::string& item) -> std::optional<double> {
                              const std::optional<double> t = whole_number<double>(item);
                              if (!t || !(*t > 0.0) || !(*t < 1.0)) return std::nullopt;
                              return t;
                            });
}

GlossyReportRequest glossy_request(const ReportArguments& a) {
  return {
      a.scene,     a.environment, a.output, a.quick,     a.quiet,
      a.stability, a.radiosity,   a.seed,   a.materials, memory_limit_or_default(a.memory_limit)};
}

// Options that do not apply are refused by name; values out of range too.
void check_options(const ReportArguments& a, const CLI::App& cmd) {
  if (!a.radiosity)
    for (const char* option : kRadiosityOnly)
      if (cmd.count(option) > 0) throw UsageError(std::string(option) + " needs --radiosity");
  if ((a.radiosity || a.stability) && cmd.count("--memory-limit") > 0)
    throw UsageError(std::string("--memory-limit does not apply to ") +
                     (a.radiosity ? "--radiosity" : "--stability") +
                     " (it limits the bakes of the SH and glossy sweeps)");
  if (!a.glossy && cmd.count("--material") > 0)
    throw UsageError(
        "--material needs --glossy (the other report modes use the scene's materials)");
  if (a.glossy) {
    check_glossy_report_options(glossy_request(a), cmd);
    return;
  }
  if (a.radiosity) {
    if (a.stability) throw UsageError("--radiosity and --stability exclude each other");
    if (a.scene.empty() || !a.environment.empty())
      throw UsageError("--radiosity takes a SCENE and no ENV (the scene's emitters light it)");
    for (const char* option : kEnvironmentOnly)
      if (cmd.count(option) > 0)
        throw UsageError(std::string(option) + " does not apply to --radiosity");
    if (a.ground_truth_patches < 0 || a.ground_truth_samples < 0)
      throw UsageError("--ground-truth-patches and --ground-truth-samples must be positive");
    if (a.rays < 1 || a.rays > 1 << 24) throw UsageError("--rays: must be in 1..16777216");
    if (a.hemicube < 2 || a.hemicube > 4096 || a.hemicube % 2 != 0)
      throw UsageError("--hemicube: must be even, 2..4096");
    return;
  }
  if (a.stability) {
    if (!a.scene.empty() || !a.environment.empty())
      throw UsageError("--stability takes no SCENE or ENV (its cases make their own)");
    for (const char* option :
         {"--layout", "--seed", "--haar-cubes", "--auto-tolerances", "--ground-truth-budget"})
      if (cmd.count(option) > 0)
        throw UsageError(std::string(option) + " does not apply to --stability");
    return;
  }
  if (a.scene.empty() || a.environment.empty())
    throw UsageError("SCENE and ENV are required (or pass --stability)");
  if (!std::isfinite(a.budget) || !(a.budget > 0))
    throw UsageError("--ground-truth-budget: must be a positive number of seconds");
  if (a.quick && cmd.count("--ground-truth-budget") > 0 &&
      a.budget > prt::report::kQuickGroundTruthBudgetSeconds)
    throw UsageError("--ground-truth-budget: --quick caps it at " +
                     std::to_string(static_cast<int>(prt::report::kQuickGroundTruthBudgetSeconds)) +
                     " s");
}

// The output folder, and every file the run would write there, against the inputs.
CommandFiles report_files(const ReportArguments& a) {
  if (a.sun.enabled) return sun_study_files(a.output);
  if (a.ssao.enabled) return ssao_report_files(a.ssao, a.scene, a.output, a.quick);
  if (a.translucency.enabled)
    return translucency_files(a.translucency, a.scene, a.environment, a.output);
  CommandFiles files;
  if (!a.scene.empty()) files.add_scene(a.scene);
  if (!a.environment.empty()) files.add_environment(a.environment);
  files.add_output_directory("-o", a.output);
  const std::vector<std::string> names = a.glossy      ? prt::report::glossy_report_file_names()
                                         : a.stability ? prt::report::stability_file_names()
                                         : a.radiosity ? prt::report::radiosity_report_file_names()
                                                       : prt::report::report_file_names();
  for (const std::string& name : names)
    files.add_output("-o", (std::filesystem::path(a.output) / name).string());
  return files;
}

std::optional<std::vector<double>> parse_max_edges(const std::string& text) {
  return parse_list<double>("--max-edges", text, "a positive length",
                            [](const std::string& item) -> std::optional<double> {
                              const std::optional<double> e = whole_number<double>(item);
                              if (!e || !(*e > 0.0) || !std::isfinite(*e)) return std::nullopt;
                              return e;
                            });
}

// A comma-separated list of names → values (empty text: `all`).
template <class T>
std::vector<T> parse_names(const std::string& option, const std::string& text,
                           const std::vector<std::pair<std::string, T>>& names) {
  std::vector<T> out;
  if (text.empty()) {
    for (const auto& [name, value] : names) out.push_back(value);
    return out;
  }
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    bool found = false;
    for (const auto& [name, value] : names)
      if (item == name) out.push_back(value), found = true;
    if (!found) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : "|") + n.first;
      throw UsageError(option + ": '" + item + "' is not one of " + known);
    }
  }
  return out;
}

void run_radiosity(const ReportArguments& a) {
  namespace rad = prt::radiosity;
  prt::report::RadiosityReportOptions o;
  o.scene_path = a.scene;
  o.output_dir = a.output;
  o.quick = a.quick;
  o.seed = a.seed;
  for (const std::string& e : a.emission)
    o.emission.push_back(scene::parse_material_colour("--emission", e));
  for (const std::string& e : a.albedo)
    o.albedo.push_back(scene::parse_material_colour("--albedo", e));
  o.max_edges = parse_max_edges(a.max_edges).value_or(std::vector<double>{});
  o.methods = parse_names<rad::FormFactorMethod>("--methods", a.methods,
                                                 {{"analytic", rad::FormFactorMethod::Analytic},
                                                  {"rays", rad::FormFactorMethod::Rays},
                                                  {"hemicube", rad::FormFactorMethod::Hemicube}});
  o.solvers = parse_names<rad::SolverKind>("--solvers", a.solvers,
                                           {{"gauss-seidel", rad::SolverKind::GaussSeidel},
                                            {"jacobi", rad::SolverKind::Jacobi},
                                            {"progressive", rad::SolverKind::Progressive}});
  o.ground_truth_patches = a.ground_truth_patches;
  o.ground_truth_samples = a.ground_truth_samples;
  o.rays_per_patch = a.rays;
  o.hemicube_resolution = a.hemicube;
  ProgressReporter progress(a.quiet);
  o.log = [&progress](const std::string& line) { progress.message(line); };
  const prt::report::RadiosityReportResult r = prt::report::run_radiosity_report(o);
  for (const std::string& f : r.files_written) std::printf("wrote %s\n", f.c_str());
}

// The first positional argument, mode flag or other mode's option given, for --sun-study to
// refuse ("" when none).
std::string other_mode_argument(const ReportArguments& a, const CLI::App& cmd) {
  if (!a.scene.empty()) return "SCENE '" + a.scene + "'";
  if (!a.environment.empty()) return "ENV '" + a.environment + "'";
  if (a.stability) return "--stability";
  if (a.radiosity) return "--radiosity";
  if (a.glossy) return "--glossy";
  for (const char* option : kRadiosityOnly)
    if (cmd.count(option) > 0) return option;
  for (const char* option : kEnvironmentOnly)
    if (cmd.count(option) > 0) return option;
  if (cmd.count("--seed") > 0) return "--seed";
  if (cmd.count("--memory-limit") > 0) return "--memory-limit";
  if (cmd.count("--material") > 0) return "--material";
  return "";
}

// The command line, before the files are checked.
void check_usage(const ReportArguments& a, const CLI::App& cmd) {
  // The modes with a command line of their own exclude each other; each refuses the others'
  // options.
  if (a.sun.enabled && a.ssao.enabled)
    throw UsageError("--ssao and --sun-study exclude each other");
  if (a.translucency.enabled && (a.sun.enabled || a.ssao.enabled))
    throw UsageError(std::string("--translucency and ") +
                     (a.sun.enabled ? "--sun-study" : "--ssao") + " exclude each other");
  if (!a.ssao.enabled) refuse_ssao_options(cmd);
  if (!a.translucency.enabled) refuse_translucency_options(cmd);
  if (a.sun.enabled) return check_sun_study_mode(a.sun, other_mode_argument(a, cmd));
  refuse_sun_study_options(cmd);
  if (a.ssao.enabled) {
    ReportArguments others = a;  // SCENE is the mode's own
    others.scene.clear();
    return check_ssao_mode(a.ssao, a.scene, other_mode_argument(others, cmd));
  }
  if (a.translucency.enabled) {
    const std::string other = a.stability   ? "--stability"
                              : a.radiosity ? "--radiosity"
                              : a.glossy    ? "--glossy"
                                            : "";
    return check_translucency_mode(a.translucency, a.scene, a.environment, other);
  }
  check_options(a, cmd);
}

void run(const ReportArguments& a) {
  if (a.sun.enabled) return run_sun_study_mode(a.sun, a.output, a.quick, a.quiet);
  if (a.ssao.enabled) return run_ssao_mode(a.ssao, a.scene, a.output, a.quick, a.quiet);
  if (a.translucency.enabled)
    return run_translucency_mode(a.translucency, a.scene, a.environment, a.output, a.layout, a.seed,
                                 a.quick, a.quiet, memory_limit_or_default(a.memory_limit));
  if (a.glossy) {
    run_glossy_report_command(glossy_request(a));
    return;
  }
  if (a.radiosity) {
    run_radiosity(a);
    return;
  }
  if (a.stability) {
    const int failed = prt::report::run_stability_report(a.output, a.quick);
    std::printf("stability: %d failed case(s); report in %s\n", failed, a.output.c_str());
    if (failed > 0)
      throw CommandError(a.output + ": " + std::to_string(failed) + " stability case(s) failed");
    return;
  }
  prt::report::ReportOptions o;
  o.scene_path = a.scene;
  o.environment_path = a.environment;
  o.output_dir = a.output;
  o.quick = a.quick;
  o.seed = a.seed;
  o.ground_truth_budget_seconds = a.budget;
  o.layout = parse_layout_option(a.layout);
  o.haar_cubes = parse_haar_cubes(a.haar_cubes);
  o.auto_tolerances = parse_auto_tolerances(a.auto_tolerances);
  o.memory_limit = memory_limit_or_default(a.memory_limit);
  ProgressReporter progress(a.quiet);
  o.log = [&progress](const std::string& line) { progress.message(line); };
  o.progress = &progress;
  const prt::report::ReportResult r = prt::report::run_report(o);
  for (const std::string& f : r.files_written) std::printf("wrote %s\n", f.c_str());
}

Command register_report(CLI::App& app) {
  auto args = std::make_shared<ReportArguments>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Error against run time of PRT settings, measured against a Monte Carlo ground truth");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj)");
  cmd->add_option("environment", args->environment, "Environment map (.hdr, .exr, .pfm)");
  cmd->add_option("-o,--output", args->output, "Output directory")->required();
  cmd->add_flag("--quick", args->quick, "Small sweep (under a minute on data/)");
  cmd->add_flag("--stability", args->stability, "Run the stability cases instead of the sweep");
  cmd->add_flag("--quiet", args->quiet, "No progress lines on stderr");
  cmd->add_flag("--radiosity", args->radiosity,
                "Radiosity (form factors x patches x solver) against a path-traced ground truth "
                "of the scene's own emitters; no ENV");
  cmd->add_flag("--glossy", args->glossy,
                "Glossy PRT (order, samples, bounces, CPCA size) against a path-traced glossy "
                "ground truth of the scene's materials");
  cmd->add_option("--emission", args->emission,
                  "--radiosity: MATERIAL=r,g,b emission of a material (repeatable)");
  cmd->add_option("--albedo", args->albedo,
                  "--radiosity: MATERIAL=r,g,b albedo of a material (repeatable)");
  cmd->add_option("--max-edges", args->max_edges,
                  "--radiosity: patch sizes, e.g. 200,100,70 (default: quick 200,100; full "
                  "200,100,70,50)");
  cmd->add_option(
      "--methods", args->methods,
      "--radiosity: form factors, e.g. analytic,rays (default: analytic,rays,hemicube)");
  cmd->add_option("--solvers", args->solvers,
                  "--radiosity: e.g. gauss-seidel,progressive (default: all three)");
  cmd->add_option("--ground-truth-patches", args->ground_truth_patches,
                  "--radiosity: patches the ground truth integrates per patch count (default: "
                  "quick 512; full 1024)");
  cmd->add_option("--rays", args->rays, "--radiosity: rays per patch of the rays method")
      ->capture_default_str();
  cmd->add_option("--hemicube", args->hemicube, "--radiosity: cells across the hemicube's top face")
      ->capture_default_str();
  cmd->add_option("--ground-truth-samples", args->ground_truth_samples,
                  "--radiosity: paths per ground-truth patch (default: quick 1024; full 4096)");
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
                  "Seconds the ground-truth refinement may take (--quick: at most 15)")
      ->capture_default_str();
  add_memory_limit_option(*cmd, &args->memory_limit);
  add_material_option(*cmd, args->materials);
  CLI::Option* material = cmd->get_option("--material");
  material->description("--glossy: " + material->get_description());
  add_sun_study_options(cmd, &args->sun);
  add_ssao_report_options(cmd, &args->ssao);
  add_translucency_options(cmd, &args->translucency);
  return {cmd, [args, cmd] { check_usage(*args, *cmd); }, [args] { return report_files(*args); },
          [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(40, register_report);

}  // namespace prt::cli
