// report/src/radiosity_report_outputs.h (private to prt_report) — the Pareto front and the files
// of `prt report --radiosity` (report/radiosity_report.h).
#pragma once

#include "report/radiosity_report.h"

namespace prt::report {

// Marks the rows no other row beats in both total seconds and error.
void mark_radiosity_pareto_front(RadiosityReportResult& result);

// radiosity_results.csv, radiosity_results.json, radiosity_pareto.svg/png and
// radiosity_summary.md in options.output_dir, each written atomically.
void write_radiosity_outputs(const RadiosityReportOptions& options, RadiosityReportResult& result);

}  // namespace prt::report
