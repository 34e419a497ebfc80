// cli/report_sun_study.h — the `--sun-study` mode of `prt report` (report/sun_study.h):
// `prt report --sun-study -o DIR [--quick] [--roughness LIST] [--sky F] [--vertices N]
// [--object-budget GIB] [--machine-budget GIB]`. Its options are refused by name without
// --sun-study; with it, the SCENE/ENV arguments and the other modes' options are refused.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "output_safety.h"

namespace prt::cli {

struct SunStudyArguments {
  bool enabled = false;
  std::string roughness;  // GGX α list; empty: 0.05,0.1,0.2,0.4
  double sky = 0.15, vertices = 50000, object_budget = 1, machine_budget = 24;
};

// Registers --sun-study and its options on `report`.
void add_sun_study_options(CLI::App* report, SunStudyArguments* arguments);

// Throws UsageError naming the first --sun-study option given without --sun-study.
void refuse_sun_study_options(const CLI::App& report);

// Checks the mode's options (UsageError, before anything is written). `given` names any
// positional argument or other mode's option the caller saw ("" when none): it is refused.
void check_sun_study_mode(const SunStudyArguments& arguments, const std::string& given);

// The output folder and every file the study writes there.
CommandFiles sun_study_files(const std::string& output);

// Runs the study (its options and files checked) and prints the files written.
void run_sun_study_mode(const SunStudyArguments& arguments, const std::string& output, bool quick,
                        bool quiet);

}  // namespace prt::cli
