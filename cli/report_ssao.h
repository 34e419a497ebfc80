// cli/report_ssao.h — the `--ssao` mode of `prt report`: screen-space AO against ray-traced AO
// (docs/SSAO.md). `prt report --ssao SCENE -o DIR [--ao-distance D] [--ao-falloff F]
// [--ssao-radius R] [--ssao-samples N] [--ssao-slices N] [--ssao-steps N] [--ssao-rays N]
// [--ssao-size WxH] [--quick]`:
//   - bakes AO (DIR/ao.prt; with --ao-distance also obscurance, DIR/obscurance.prt);
//   - serves the scene with `prt view`'s server on loopback and renders its AO page
//     (web/ssao.html) in headless Chromium from several cameras (cli/ssao_browser.h);
//   - traces the truth per pixel and measures classic SSAO, GTAO and the baked per-vertex AO
//     against it (report/ssao_comparison.h), overall and where screen-space AO fails;
//   - writes ssao_errors.csv, ssao_errors.json, summary.md and ssao_CAMERA.png
//     (report/ssao_report_outputs.h).
// Its options are refused without --ssao; with it, ENV and the other modes' options are refused.
// Without Chromium, node or puppeteer-core it says which in one line and exits 1 before writing.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "output_safety.h"

namespace prt::cli {

struct SsaoReportArguments {
  bool enabled = false;
  std::optional<double> ao_distance, radius;
  std::string ao_falloff = "constant";
  int samples = 32, slices = 4, steps = 8, rays = 256;
  std::string size = "480x270";
};

void add_ssao_report_options(CLI::App* report, SsaoReportArguments* arguments);

// Throws UsageError naming the first --ssao option given without --ssao.
void refuse_ssao_options(const CLI::App& report);

// Checks the mode (UsageError): SCENE given, `other` ("" or the first other mode's argument the
// caller saw) refused, values in range.
void check_ssao_mode(const SsaoReportArguments& arguments, const std::string& scene,
                     const std::string& other);

CommandFiles ssao_report_files(const SsaoReportArguments& arguments, const std::string& scene,
                               const std::string& output, bool quick);

void run_ssao_mode(const SsaoReportArguments& arguments, const std::string& scene,
                   const std::string& output, bool quick, bool quiet);

}  // namespace prt::cli
