// cli/glossy_report_cli.h — the glossy mode of `prt report` (report/glossy_report.h), kept apart
// so report_command.cpp changes by a few lines only:
//   prt report --glossy SCENE ENV -o DIR [--quick] [--seed S] [--quiet] [--material M ...]
// SCENE's materials (ScenePrimitive::brdf, Lambert elsewhere), after the `--material`
// overrides of `prt bake` (cli/material_option.h: same syntax, same one-line errors), are
// baked, compressed and relit toward the scene camera's eye and compared with the glossy ground
// truth, which uses the same overridden materials.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace prt::cli {

struct GlossyReportRequest {
  std::string scene, environment, output;
  bool quick = false, quiet = false, stability = false, radiosity = false;
  uint64_t seed = 1;
  std::vector<std::string> materials;  // --material values as given
  uint64_t memory_limit = 0;           // GlossyReportOptions::memory_limit
};

// Refuses what does not apply to --glossy, by name (`cmd` counts the options), and a
// --material value that does not parse. Throws UsageError.
void check_glossy_report_options(const GlossyReportRequest& request, const CLI::App& cmd);

// Runs the report and prints the files written. Throws std::runtime_error / BakeError.
void run_glossy_report_command(const GlossyReportRequest& request);

}  // namespace prt::cli
