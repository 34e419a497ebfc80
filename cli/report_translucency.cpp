// cli/report_translucency.cpp — argument mapping of `prt report --translucency`
// (report_translucency.h).
#include "report_translucency.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli_parsing.h"
#include "command_registry.h"
#include "progress_reporter.h"
#include "prt/subsurface/dipole.h"
#include "report/translucency_report.h"

namespace prt::cli {
namespace {

const char* const kTranslucencyOnly[] = {"--subsurface", "--more-scenes", "--mm-per-unit",
                                         "--opaque"};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::vector<std::string> all_scenes(const TranslucencyArguments& a, const std::string& scene) {
  std::vector<std::string> out{scene};
  if (!a.more_scenes.empty())
    for (const std::string& s : split(a.more_scenes)) out.push_back(s);
  return out;
}

std::vector<double> parse_mm_per_unit(const TranslucencyArguments& a, std::size_t scenes) {
  std::vector<double> out(scenes, 0.0);
  if (a.mm_per_unit.empty()) return out;
  const std::vector<std::string> items = split(a.mm_per_unit);
  if (items.size() > scenes)
    throw UsageError("--mm-per-unit: " + std::to_string(items.size()) + " values for " +
                     std::to_string(scenes) + " scene(s)");
  for (std::size_t i = 0; i < items.size(); ++i) {
    std::size_t used = 0;
    double v = -1;
    try {
      v = std::stod(items[i], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != items[i].size() || !std::isfinite(v) || v < 0 || v > 1e9)
      throw UsageError("--mm-per-unit: '" + items[i] + "' is not a length in mm (0: automatic)");
    out[i] = v;
  }
  return out;
}

}  // namespace

void add_translucency_options(CLI::App* cmd, TranslucencyArguments* a) {
  cmd->add_flag("--translucency", a->enabled,
                "Real-time approximations of subsurface scattering (Lambert with R_total, normal "
                "blurring, mesh-space diffusion, depth-map translucency) against the dipole bake, "
                "and the bake's time against vertex count");
  cmd->add_option("--subsurface", a->preset,
                  "--translucency: the material preset (marble, skin1, ...)")
      ->capture_default_str();
  cmd->add_option("--more-scenes", a->more_scenes,
                  "--translucency: further scenes measured the same way, e.g. bunny.obj");
  cmd->add_option("--mm-per-unit", a->mm_per_unit,
                  "--translucency: millimetres per scene unit, one per scene in order (0 or "
                  "absent: the subsurface bake's automatic scale)");
  cmd->add_option("--opaque", a->opaque,
                  "--translucency: primitives or materials kept Lambert with their albedo, e.g. "
                  "ground (default: none; every other one is translucent)");
}

void refuse_translucency_options(const CLI::App& cmd) {
  for (const char* option : kTranslucencyOnly)
    if (cmd.count(option) > 0) throw UsageError(std::string(option) + " needs --translucency");
}

void check_translucency_mode(const TranslucencyArguments& a, const std::string& scene,
                             const std::string& environment, const std::string& other) {
  if (!other.empty()) throw UsageError(other + " does not apply to --translucency");
  if (scene.empty() || environment.empty())
    throw UsageError("--translucency takes a SCENE and an ENV");
  if (!subsurface::find_subsurface_preset(a.preset).ok())
    throw UsageError("--subsurface: unknown preset '" + a.preset + "'");
  for (const std::string& s : all_scenes(a, scene))
    if (s.empty()) throw UsageError("--more-scenes: an empty scene path");
  parse_mm_per_unit(a, all_scenes(a, scene).size());
}

CommandFiles translucency_files(const TranslucencyArguments& a, const std::string& scene,
                                const std::string& environment, const std::string& output) {
  CommandFiles files;
  for (const std::string& s : all_scenes(a, scene)) files.add_scene(s);
  files.add_environment(environment);
  files.add_output_directory("-o", output);
  for (const std::string& name : prt::report::translucency_report_file_names(all_scenes(a, scene)))
    files.add_output("-o", (std::filesystem::path(output) / name).string());
  return files;
}

void run_translucency_mode(const TranslucencyArguments& a, const std::string& scene,
                           const std::string& environment, const std::string& output,
                           const std::string& layout, uint64_t seed, bool quick, bool quiet,
                           uint64_t memory_limit) {
  prt::report::TranslucencyReportOptions o;
  const std::vector<std::string> scenes = all_scenes(a, scene);
  const std::vector<double> mm = parse_mm_per_unit(a, scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) o.scenes.push_back({scenes[i], mm[i]});
  o.environment_path = environment;
  o.layout = parse_layout_option(layout);
  o.output_dir = output;
  o.preset = a.preset;
  if (!a.opaque.empty()) o.opaque = split(a.opaque);
  o.seed = seed;
  o.quick = quick;
  if (quick) o.order = 3, o.samples = 64;
  o.memory_limit = memory_limit;
  ProgressReporter progress(quiet);
  o.log = [&progress](const std::string& line) { progress.message(line); };
  const prt::report::TranslucencyReportResult r = prt::report::run_translucency_report(o);
  for (const std::string& f : r.files_written) std::printf("wrote %s\n", f.c_str());
}

}  // namespace prt::cli
