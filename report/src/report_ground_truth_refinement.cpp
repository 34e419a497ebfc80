// report/src/report_ground_truth_refinement.cpp — the ground truth of `prt report`: a first
// estimate before the sweep, refined after it until its error is below a fifth of the smallest
// error measured (or its budget runs out).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "report/report_metrics.h"
#include "report_state.h"

namespace prt::report::detail {

namespace {

// The smallest error measured (settings and projection errors).
double smallest_error(const ReportResult& result) {
  double e = INFINITY;
  for (const ReportMeasurement& m : result.measurements)
    if (m.failure.empty() && m.relative_rms > 0) e = std::min(e, m.relative_rms);
  for (double p : result.projection_error) e = std::min(e, p);
  return e;
}

}  // namespace

// The ground truth's first estimate, before the sweep.
void estimate_ground_truth(ReportState& st) {
  st.refine_within_budget(st.opt.quick ? 0.03 : 0.01);
  st.truth = st.gt.result();
  st.log("ground truth: " + std::to_string(st.truth.samples_per_vertex) +
         " samples/vertex, relative RMS SE " + percent(st.truth.relative_rms_se) + ", " +
         seconds_text(st.truth.seconds));
}

// Is the ground truth good enough for the smallest error measured? Refines it if needed and
// scores the settings and the projection error again.
void refine_ground_truth(ReportState& st) {
  ReportResult& result = st.result;
  st.e_min = smallest_error(result);
  if (st.truth.relative_rms_se > st.e_min / 5.0) {
    st.log("refining the ground truth toward SE " + percent(st.e_min / 5.0) +
           " (1/5 of the smallest error)");
    st.refine_within_budget(st.e_min / 5.0);
    st.truth = st.gt.result();
    for (std::size_t i = 0; i < result.measurements.size(); ++i) {
      ReportMeasurement& m = result.measurements[i];
      if (!m.failure.empty()) continue;
      score_against_truth(m, st.radiance[i], st.truth.radiance);
    }
    compute_projection_error(st);
    st.e_min = smallest_error(result);
  }
}

// The image errors against a rendering of the final ground truth, and the ground truth's
// figures in the result.
void record_ground_truth(ReportState& st) {
  ReportResult& result = st.result;
  const report::GroundTruthResult& truth = st.truth;
  const std::vector<float> truth_f(truth.radiance.begin(), truth.radiance.end());
  const std::vector<float> truth_image = st.in.render_radiance(truth_f);
  for (std::size_t i = 0; i < result.measurements.size(); ++i)
    if (result.measurements[i].failure.empty())
      result.measurements[i].image_relative_rms =
          relative_rms_image_error(st.images[i], truth_image, st.in.mask);
  result.ground_truth_samples = truth.samples_per_vertex;
  result.ground_truth_relative_se = truth.relative_rms_se;
  result.ground_truth_seconds = truth.seconds;
  result.ground_truth_mrays = truth.mrays_per_second();
  result.ground_truth_adequate = truth.relative_rms_se <= st.e_min / 5.0;
  st.log("ground truth: " + std::to_string(truth.samples_per_vertex) + " samples/vertex, SE " +
         percent(truth.relative_rms_se) + " vs smallest error " + percent(st.e_min) +
         (result.ground_truth_adequate ? " (adequate)" : " (NOT below 1/5 of it)"));
}

// Every setting's (bake time, error); failed ones never count.
void collect_costs(ReportState& st) {
  for (const ReportMeasurement& m : st.result.measurements) {
    st.cost.push_back(m.failure.empty() ? m.bake_seconds : INFINITY);
    st.error.push_back(m.failure.empty() ? m.relative_rms : INFINITY);
  }
}

}  // namespace prt::report::detail
