// cli/report_translucency.h — the `--translucency` mode of `prt report`
// (report/translucency_report.h): `prt report --translucency SCENE ENV -o DIR [--quick]
// [--subsurface PRESET] [--more-scenes A,B] [--mm-per-unit LIST] [--opaque NAMES]
// [--seed S] [--layout L]`. Its options are refused by name without --translucency.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "output_safety.h"

namespace prt::cli {

struct TranslucencyArguments {
  bool enabled = false;
  std::string preset = "marble", more_scenes, mm_per_unit, opaque;
};

void add_translucency_options(CLI::App* report, TranslucencyArguments* arguments);
// Throws UsageError naming the first --translucency option given without --translucency.
void refuse_translucency_options(const CLI::App& report);
// Checks the mode's values (UsageError). `other` names another mode given ("" when none).
void check_translucency_mode(const TranslucencyArguments& a, const std::string& scene,
                             const std::string& environment, const std::string& other);
// Every file read and written.
CommandFiles translucency_files(const TranslucencyArguments& a, const std::string& scene,
                                const std::string& environment, const std::string& output);
void run_translucency_mode(const TranslucencyArguments& a, const std::string& scene,
                           const std::string& environment, const std::string& output,
                           const std::string& layout, uint64_t seed, bool quick, bool quiet,
                           uint64_t memory_limit);

}  // namespace prt::cli
