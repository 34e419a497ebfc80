// report/ssao_report_outputs.h — the files of `prt report --ssao` (docs/SSAO.md): the error
// figures of every screen-space estimate against the ray-traced truth (ssao_comparison.h) as
// CSV, JSON and a Markdown summary, and one picture per camera of the values and their
// differences. Every file is written atomically; errors throw std::runtime_error "PATH: problem".
#pragma once

#include <string>
#include <vector>

#include "report/ssao_comparison.h"

namespace prt::report {

struct SsaoReportSettings {
  std::string scene;
  double radius = 0;  // the screen-space radius R (scene units)
  int samples = 0, slices = 0, steps = 0, truth_rays = 0, bake_samples = 0;
  bake::ObscuranceOptions obscurance;  // distance > 0: obscurance was measured too
  RegionRule rule;
  double distance_lo = 0, distance_hi = 0;  // the bins' range
};

// One estimate (e.g. "gtao") against one truth ("ao", "obscurance") on one camera, or "all".
struct SsaoResult {
  std::string camera, estimate, truth;
  RegionErrors errors;
};

// A camera's picture, three images across: truth AO | classic SSAO | GTAO; then baked AO (the
// file's per-vertex values) | SSAO − AO | GTAO − AO; then, when the truth has obscurance, the
// obscurance | SSAO − obscurance | GTAO − obscurance. Differences: red where the estimate is
// brighter than the truth, blue where darker, full colour at ±0.5. Grey values are AO itself, no
// tone mapping.
void write_ssao_picture(const std::string& path, const AoCapture& capture, const PixelTruth& truth);

// ssao_errors.csv, ssao_errors.json and summary.md in `dir`; returns the paths written.
std::vector<std::string> write_ssao_tables(const std::string& dir,
                                           const std::vector<SsaoResult>& results,
                                           const SsaoReportSettings& settings);

// The file names write_ssao_tables writes.
std::vector<std::string> ssao_table_names();

}  // namespace prt::report
