// report/src/report_state.h (private to prt_report) — what the phases of run_report() share.
//
// run_report() (report.cpp) loads the inputs and a first ground truth (ReportState), measures
// every setting of the sweep (report_sweep.cpp), splits the error into projection and sampling,
// refines the ground truth if the smallest error needs it and scores everything again
// (report_ground_truth_refinement.cpp), bakes `prt bake --auto` at each tolerance, and writes
// the outputs (report_outputs.cpp, report_plots.cpp, report_summary.cpp). Conventions and
// error definitions: report/report.h.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "bake/progress.h"
#include "bake/transfer_baker.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/camera.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "report/ground_truth.h"
#include "report/report.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::report::detail {

using Clock = std::chrono::steady_clock;
// Haar compression of the report's bakes: the defaults of `prt bake --basis haar`.
constexpr double kHaarThreshold = 1e-3;
constexpr prt::HaarQuantization kHaarQuantization = prt::HaarQuantization::Bits16;

// Seconds since t.
double since(Clock::time_point t);

// ---- names of settings (report_settings.cpp) ----
std::string precision_name(prt::Precision p);
std::string bounces_name(int bounces);  // "converged" for −1
bool is_haar(const ReportSetting& s);
std::string basis_name(const ReportSetting& s);    // "sh" or "haar"
std::string storage_name(const ReportSetting& s);  // f32/f16 for SH, the quantisation for Haar
int64_t haar_coefficient_count(int cube);          // 6N²
int64_t haar_terms_used(const ReportSetting& s);   // the lighting terms a Haar setting uses
std::string terms_text(const ReportSetting& s);    // "200" or "all 384"
std::string describe(const ReportSetting& s);      // one line for the log and the summary
std::string short_label(const ReportSetting& s);   // a plot label
bool same(const ReportSetting& a, const ReportSetting& b);
std::string percent(double x);
std::string seconds_text(double s);

// Step lines for ReportOptions::log (when set), stamped with the seconds since the start.
struct ReportLog {
  const std::function<void(const std::string&)>& sink;
  Clock::time_point t_start;
  void operator()(const std::string& line) const {
    if (!sink) return;
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "[report %6.1fs] ", since(t_start));
    sink(stamp + line);
  }
};

// The scene, the map and the renderer every phase measures with.
struct ReportInputs {
  // Loads the scene and the map, logs them, and finds the pixels the scene covers.
  ReportInputs(const ReportOptions& opt, const ReportLog& log);

  // Renders per-vertex RGB radiance with the report's camera: RGB floats per pixel.
  std::vector<float> render_radiance(const std::vector<float>& b) const {
    return relight::render(scene, caster, b, nullptr, relight::kIdentityRotation, camera, ropt).rgb;
  }

  scene::Scene scene;
  std::string layout_note;
  const sh::EnvMap env;
  scene::RayCaster caster;
  const std::size_t V;
  relight::RenderOptions ropt;
  relight::Camera camera;
  std::vector<uint8_t> mask;  // pixels fully covered by the scene
};
// and per-measurement results, and the result being filled.
struct ReportState {
  // Loads the inputs and sets up the ground-truth integrator (no samples yet: see
  // estimate_ground_truth).
  ReportState(const ReportOptions& options, Clock::time_point start);

  // Adds ground-truth samples (doubling) until its standard error reaches `target`, the
  // sample cap or the time budget.
  void refine_within_budget(double target) { gt.refine(target, progress, budget); }
  // The map projected to `order` (projected once per order).
  const prt::ShLighting& lighting_for(int order) {
    auto it = lighting.find(order);
    if (it == lighting.end())
      it = lighting.emplace(order, relight::project_lighting(in.env, order, {})).first;
    return it->second;
  }
  // The interreflected SH bake of a setting; shared between settings that differ only in
  // precision.
  const bake::BakeResult& bake_for(const ReportSetting& s) {
    const auto key = std::make_tuple(s.order, s.samples, s.bounces);
    auto it = bakes.find(key);
    if (it == bakes.end()) {
      bake::BakeOptions bo;
      bo.kind = prt::TransferKind::Interreflected;
      bo.order = s.order, bo.samples = s.samples, bo.bounces = s.bounces, bo.seed = opt.seed;
      bo.memory_limit = opt.memory_limit;
      it = bakes.emplace(key, bake::bake_transfer(in.scene, bo)).first;
    }
    return it->second;
  }

  const ReportOptions& opt;
  const ReportLog log;
  const ReportSetting base;
  ReportInputs in;

  // Ground truth: a first estimate before the sweep, refined after it if the errors demand it.
  const GroundTruthOptions gto;
  GroundTruthIntegrator gt;
  bake::ProgressSink* const progress;  // the caller's, may be null
  const double budget;                 // seconds
  GroundTruthResult truth;

  // The sweep.
  std::map<int, prt::ShLighting> lighting;                      // per order
  std::map<std::tuple<int, int, int>, bake::BakeResult> bakes;  // (order, samples, bounces)
  std::vector<std::vector<float>> radiance;                     // per measurement
  std::vector<std::vector<float>> images;                       // per measurement
  // The converged reference of the projection/sampling split: the largest order and sample
  // count (quick: the samples axis' largest bake at the base order, reused).
  const int reference_order;
  const int reference_samples;
  std::vector<std::vector<double>> reference_b;  // per order of the split

  double e_min = INFINITY;             // the smallest error measured
  std::vector<double> cost, error;     // per measurement; failed ones are infinite
  std::vector<std::string> png_notes;  // why a plot has no PNG
  ReportResult result;
};

// ---- the phases, in run_report's order ----
// Throws for a --haar-cubes size that is not a power of two in [8, 128].
void check_haar_cubes(const ReportOptions& opt);
// Creates the output directory; throws "DIR: cannot create directory: why".
void create_output_dir(const ReportOptions& opt);
// The ground truth's first estimate, before the sweep (report_ground_truth_refinement.cpp).
void estimate_ground_truth(ReportState& st);
// Measures every setting of the sweep: bake, file size, relight time and error against the
// current ground truth; keeps each one's radiance and rendering (report_sweep.cpp).
void run_sweep(ReportState& st);
// Projection error per order and sampling error per (order, samples) (report_sweep.cpp).
void split_projection_and_sampling(ReportState& st);
// Refines the ground truth if it is not below a fifth of the smallest error and scores again.
void refine_ground_truth(ReportState& st);
// The image errors against a rendering of the final ground truth, and its figures.
void record_ground_truth(ReportState& st);
// Every setting's (bake time, error); failed ones never count.
void collect_costs(ReportState& st);
// `prt bake --auto` at each tolerance, against the same ground truth (report_sweep.cpp).
void measure_auto_bakes(ReportState& st);
// Marks the Pareto front over (bake time, error).
void mark_pareto_front(ReportState& st);
// Writes results.csv, results.json, the plots and summary.md (report_outputs.cpp).
void write_outputs(ReportState& st);

// ---- shared between phases ----
// Sets a measurement's relative RMS, p99 and max errors against per-vertex `truth`.
void score_against_truth(ReportMeasurement& m, const std::vector<float>& b,
                         const std::vector<double>& truth);
// Each order's truncated reference against the ground truth.
void compute_projection_error(ReportState& st);
// A file in the output directory.
std::string output_path(const ReportState& st, const std::string& name);
// Writes a file of the output directory atomically and lists it in the result.
void write_output(ReportState& st, const std::string& name, const std::string& text);
// The error levels marked on the plots and tabulated in the summary.
std::vector<std::pair<double, std::string>> error_thresholds();
// A Haar cube's measured (not failed) rows, by ascending K.
std::vector<std::size_t> haar_rows_by_terms(const ReportResult& result, int cube);
// The plots (report_plots.cpp).
void write_pareto_plot(ReportState& st, const std::vector<int>& haar_cubes);
void write_error_vs_order_plot(ReportState& st);
void write_haar_terms_plot(ReportState& st, const std::vector<int>& haar_cubes);
// summary.md (report_summary.cpp).
void write_summary(ReportState& st, const std::vector<int>& haar_cubes);

}  // namespace prt::report::detail
