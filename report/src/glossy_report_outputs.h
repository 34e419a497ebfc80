// report/src/glossy_report_outputs.h — internal to `prt report --glossy`: its log line format and
// the files it writes (report/glossy_report.h).
#pragma once

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "report/glossy_report.h"

namespace prt::report::detail {

// "[glossy report   12.3s] line" to the options' log (nothing when unset).
struct GlossyLog {
  const std::function<void(const std::string&)>& sink;
  std::chrono::steady_clock::time_point t_start;
  void operator()(const std::string& line) const {
    if (!sink) return;
    char stamp[48];
    std::snprintf(
        stamp, sizeof stamp, "[glossy report %6.1fs] ",
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
    sink(stamp + line);
  }
};

// results.csv, pareto.svg/png, error_vs_bake_time.svg/png and summary.md in options.output_dir,
// each written atomically; the paths written are appended to *written. Throws
// std::runtime_error "PATH: problem".
void write_glossy_outputs(const GlossyReportOptions& options, const GlossyReportResult& result,
                          std::vector<std::string>* written);

}  // namespace prt::report::detail
