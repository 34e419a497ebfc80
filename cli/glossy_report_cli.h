// cli/glossy_report_cli.h — the glossy mode of `prt report` (report/glossy_report.h), kept apart
// so report_command.cpp changes by a few lines only:
//   prt report --glossy SCENE ENV -o DIR [--quick] [--seed S] [--quiet]
// SCENE's materials (ScenePrimitive::brdf, Lambert elsewhere) are baked, compressed and relit
// toward the scene camera's eye and compared with the glossy ground truth.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace prt::cli {

struct GlossyReportRequest {
  std::string scene, environment, output;
  bool quick = false, quiet = false, stability = false, radiosity = false;
  uint64_t seed = 1;
};

// Refuses what does not apply to --glossy, by name (`cmd` counts the options). Throws
// UsageError.
void check_glossy_report_options(const GlossyReportRequest& request, const CLI::App& cmd);

// Runs the report and prints the files written. Throws std::runtime_error / BakeError.
void run_glossy_report_command(const GlossyReportRequest& request);

}  // namespace prt::cli
