// cli/report_sun_study.cpp — argument mapping of `prt report --sun-study` (report_sun_study.h).
#include "report_sun_study.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "command_registry.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "report/sun_study.h"

namespace prt::cli {
namespace {

const char* const kSunStudyOnly[] = {"--roughness", "--sky", "--vertices", "--object-budget",
                                     "--machine-budget"};

// "0.05,0.1": every item a whole number in [0.001, 1] (the microfacet model's range).
std::vector<double> parse_roughness(const std::string& text) {
  if (text.empty()) return {0.05, 0.1, 0.2, 0.4};
  if (text.back() == ',') throw UsageError("--roughness: '" + text + "' ends with a comma");
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    double alpha = 0;
    try {
      alpha = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !(alpha >= 0.001) || !(alpha <= 1.0))
      throw UsageError("--roughness: '" + item + "' is not a GGX alpha in [0.001, 1]");
    out.push_back(alpha);
  }
  return out;
}

void check_positive(const char* option, double value, double low, double high) {
  if (!std::isfinite(value) || !(value >= low) || !(value <= high)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: must be in [%g, %g]", option, low, high);
    throw UsageError(buf);
  }
}

}  // namespace

void add_sun_study_options(CLI::App* cmd, SunStudyArguments* a) {
  cmd->add_flag("--sun-study", a->enabled,
                "Where SH fails: glossy exit radiance under a 0.53-degree sun against its exact "
                "value, error against SH order and transfer memory; no SCENE or ENV");
  cmd->add_option("--roughness", a->roughness,
                  "--sun-study: GGX alphas of the metal lobes, e.g. 0.05,0.1 (default: "
                  "0.05,0.1,0.2,0.4)");
  cmd->add_option("--sky", a->sky,
                  "--sun-study: irradiance of the uniform sky on a plane (the sun's is 1)")
      ->capture_default_str();
  cmd->add_option("--vertices", a->vertices, "--sun-study: vertices of the object for the memory")
      ->capture_default_str();
  cmd->add_option("--object-budget", a->object_budget,
                  "--sun-study: memory budget per object in GiB")
      ->capture_default_str();
  cmd->add_option("--machine-budget", a->machine_budget,
                  "--sun-study: memory of the machine in GiB")
      ->capture_default_str();
}

void refuse_sun_study_options(const CLI::App& cmd) {
  for (const char* option : kSunStudyOnly)
    if (cmd.count(option) > 0) throw UsageError(std::string(option) + " needs --sun-study");
}

void check_sun_study_mode(const SunStudyArguments& a, const std::string& given) {
  if (!given.empty()) throw UsageError(given + " does not apply to --sun-study");
  parse_roughness(a.roughness);
  check_positive("--sky", a.sky, 0.0, 100.0);
  check_positive("--vertices", a.vertices, 1.0, 1e10);
  check_positive("--object-budget", a.object_budget, 1e-6, 1e6);
  check_positive("--machine-budget", a.machine_budget, 1e-6, 1e6);
}

CommandFiles sun_study_files(const std::string& output) {
  CommandFiles files;
  files.add_output_directory("-o", output);
  for (const std::string& name : prt::report::sun_study_file_names())
    files.add_output("-o", (std::filesystem::path(output) / name).string());
  return files;
}

void run_sun_study_mode(const SunStudyArguments& a, const std::string& output, bool quick,
                        bool quiet) {
  prt::report::SunStudyOptions o;
  o.output_dir = output;
  o.quick = quick;
  o.ggx_alphas = parse_roughness(a.roughness);
  o.sky_fraction = a.sky;
  o.vertices = a.vertices;
  o.object_budget_gib = a.object_budget;
  o.machine_budget_gib = a.machine_budget;
  ProgressReporter progress(quiet);
  o.log = [&progress](const std::string& line) { progress.message(line); };
  const prt::report::SunStudyResult r = prt::report::run_sun_study(o);
  for (const std::string& f : r.files_written) std::printf("wrote %s\n", f.c_str());
}

}  // namespace prt::cli
