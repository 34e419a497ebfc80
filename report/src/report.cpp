// report/src/report.cpp — `prt report` (see report.h): run_report() runs the phases of
// report_state.h in order.
#include "report/report.h"

#include <string>
#include <utility>
#include <vector>

#include "report_state.h"

namespace prt::report {

using namespace detail;

std::vector<std::string> report_file_names() {
  std::vector<std::string> names = {"results.csv", "results.json", "summary.md"};
  for (const char* stem : {"pareto", "error_vs_order", "haar_error_vs_terms"})
    for (const char* extension : {".svg", ".png"}) names.push_back(std::string(stem) + extension);
  return names;
}

ReportResult run_report(const ReportOptions& opt) {
  const auto t_start = Clock::now();
  check_haar_cubes(opt);
  ReportState st(opt, t_start);  // loads and checks the inputs before anything is written
  create_output_dir(opt);
  // Phase 1: the sweep, against a first estimate of the ground truth.
  estimate_ground_truth(st);
  run_sweep(st);
  // Phase 2: projection vs sampling error.
  split_projection_and_sampling(st);
  // Phase 3: the ground truth's refinement, then every setting's cost and error.
  refine_ground_truth(st);
  record_ground_truth(st);
  collect_costs(st);
  // Phase 4: `prt bake --auto` at each tolerance, and the Pareto front.
  measure_auto_bakes(st);
  mark_pareto_front(st);
  // Phase 5: the outputs.
  write_outputs(st);
  st.log("done in " + seconds_text(since(t_start)) + "; wrote " +
         std::to_string(st.result.files_written.size()) + " files to " + opt.output_dir);
  return std::move(st.result);
}

}  // namespace prt::report
