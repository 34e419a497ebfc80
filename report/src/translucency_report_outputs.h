// The files of `prt report --translucency` (report/translucency_report.h).
#pragma once

#include <glm/glm.hpp>

#include "report/translucency_report.h"

namespace prt::report {

// Writes the CSVs, JSON, plots and summary into options.output_dir; appends their paths to
// result.files_written. `dominant`: the environment's dominant direction before rotation.
void write_translucency_outputs(const TranslucencyReportOptions& options, glm::dvec3 dominant,
                                TranslucencyReportResult& result);

}  // namespace prt::report
