// report/report.h — `prt report`: error against run time for the PRT settings, measured against
// the independent Monte Carlo ground truth of report/ground_truth.h.
//
// Conventions: SH basis of sh/basis.h (real orthonormal, no Condon–Shortley phase,
// k = l(l+1)+m); glTF frame (+Y up); radiance in the map's units; errors as defined in
// report/report_metrics.h (RGB-norm relative RMS over vertices, p99 and max of the floored
// per-vertex relative error, relative RMS over the scene's pixels of a rendering).
//
// Sweep design: one axis at a time around a base setting (order 6, 1024 samples per vertex,
// interreflected with bounces solved to convergence, f32 storage; --quick: 256 samples), plus a
// small (order × samples) grid for the Pareto plot. Axes are rows of a table (ReportAxis) of
// settings (ReportSetting), so a new axis is one more entry.
// Haar axis ("haar"): all-frequency transfer (bake/haar_baker.h, as `prt bake --basis haar`:
// interreflected with the base setting's bounces, one direction per cube texel, per-vertex
// threshold 1e-3, 16-bit quantisation) on cube sizes N (quick {8}; full {8, 16}) × K
// non-linear lighting terms (relight/haar_relight.h, as `prt relight --terms K`; K values at or
// above 6N² collapse into "all"). One bake per N is shared by its K settings. Haar has no sample
// count (its directions are the 6N² texel centres) and no SH order: those fields are 0 and are
// printed empty. The bake cost grows about as N⁴ (the interreflection solve runs on all 6N²
// wavelet columns, and each of the 6N² texel rays adds a gather entry), so quick keeps N = 8 and
// N = 32 is opt-in (ReportOptions::haar_cubes, `prt report --haar-cubes 8,16,32`); costs on the
// demo scene: docs/BENCHMARKS.md, "Report and ground truth".
// Projection vs sampling error: a reference bake at the largest order and sample count
// (converged transfer) truncated to order n gives the projection error of order n (against the
// ground truth); the order-n bake at N samples against that truncated reference gives the
// sampling error.
// The ground truth is refined (sample doubling) until its relative RMS standard error is at most
// 1/5 of the smallest error measured, within a time budget, and the summary says what it reached.
// `prt bake --auto` rows (ReportAuto): one per tolerance, after the sweep, measured against the
// final ground truth; results.json "auto" and a summary.md section.
// Outputs in the output directory: results.csv, results.json, pareto.svg/png,
// error_vs_order.svg/png, haar_error_vs_terms.svg/png (when the Haar axis is swept), summary.md
// (PNG through rsvg-convert; without it only SVG). All files are written atomically. Errors
// throw std::runtime_error "PATH: problem".
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bake/progress.h"
#include "prt/formats/transfer_data.h"
#include "sh/env_map.h"

namespace prt::report {

enum class ReportBasis { Sh, Haar };

struct ReportSetting {
  ReportBasis basis = ReportBasis::Sh;
  int order = 6;       // SH order n (n² coefficients); 0 for Haar
  int samples = 1024;  // SH rays per vertex; 0 for Haar (one direction per cube texel)
  int bounces = -1;    // −1: solved to convergence; 0: shadowed (direct) only
  prt::Precision precision = prt::Precision::F32;  // SH storage (Haar files are 16-bit)
  int cube = 0;                                    // Haar cube size N; 0 for SH
  int64_t terms = 0;  // Haar lighting terms K (non-linear); 0 = all 6N²; 0 for SH
};

struct ReportAxis {
  std::string name;  // "order", "samples", "bounces", "precision", "grid", "haar"
  std::vector<ReportSetting> settings;
};

// --quick caps the ground truth's refinement budget at this many seconds.
inline constexpr double kQuickGroundTruthBudgetSeconds = 15.0;

struct ReportOptions {
  std::string scene_path, environment_path, output_dir;
  std::optional<sh::EnvLayout> layout;
  bool quick = false;
  uint64_t seed = 1;
  int image_width = 320, image_height = 180;
  double ground_truth_budget_seconds = 110;  // refinement stops before exceeding this
  // Haar cube sizes to sweep: nullopt = the default of the mode (quick {8}, full {8, 16});
  // an empty list leaves the Haar axis out.
  std::optional<std::vector<int>> haar_cubes;
  // Progress (the library prints nothing): one line per step to `log` when it is set, and the
  // ground truth's sample passes to `progress` when it is not null.
  std::function<void(const std::string&)> log;
  bake::ProgressSink* progress = nullptr;
  // Tolerances of the `prt bake --auto` rows (bake/adaptive/adaptive_baker.h): nullopt = the
  // default of the mode (quick {0.05}; full {0.01, 0.05, 0.1}); an empty list leaves them out.
  std::optional<std::vector<double>> auto_tolerances;
  uint64_t memory_limit = 0;  // every bake's memory_limit (prt/core/memory_budget.h); 0: none
};

// `prt bake --auto --env` at one tolerance, baked as the CLI does it (the map projected at
// order 32 is the lighting it adapts to) and measured like the settings: its own prediction
// against the error measured with the same ground truth, and the fixed setting of the sweep
// that reaches that error fastest.
struct ReportAuto {
  double tolerance = 0;
  int order = 0;  // the SH order it chose
  uint32_t channels = 0;
  std::string kind;               // the transfer it stored
  bool haar_recommended = false;  // no SH order meets the tolerance
  double predicted_error = 0;     // excludes the mesh's interpolation of interreflected light
  double bake_seconds = 0;        // wall time of bake_transfer_auto: analysis, pilot and bake
  uint64_t file_bytes = 0;
  double relative_rms = 0, p99 = 0, max = 0;
  long cheapest_fixed = -1;  // index into measurements with relative_rms ≤ this one's, fastest
                             // bake; −1 when no setting reaches it
  std::string failure;
};

struct ReportMeasurement {
  std::string axis;  // axes this setting belongs to, joined with '+'
  ReportSetting setting;
  double bake_seconds = 0, relight_seconds = 0;
  uint64_t file_bytes = 0;
  double relative_rms = 0, p99 = 0, max = 0, image_relative_rms = 0;
  bool on_pareto_front = false;
  std::string failure;  // non-empty when the setting could not be measured (e.g. f16 overflow)
};

struct ReportResult {
  std::vector<ReportMeasurement> measurements;
  std::vector<int> orders;               // of the projection/sampling split
  std::vector<double> projection_error;  // per order
  std::vector<int> split_samples;
  std::vector<std::vector<double>> sampling_error;  // [samples index][order index]
  int ground_truth_samples = 0;
  double ground_truth_relative_se = 0, ground_truth_seconds = 0, ground_truth_mrays = 0;
  bool ground_truth_adequate = false;  // SE ≤ smallest error / 5
  std::vector<ReportAuto> autos;
  std::vector<std::string> files_written;
};

// The base setting and the axes swept (quick or full). haar_cubes as in ReportOptions.
ReportSetting base_setting(bool quick);
std::vector<int> default_haar_cubes(bool quick);
std::vector<double> default_auto_tolerances(bool quick);
std::vector<int64_t> haar_terms(bool quick);  // K values (0 = all) before collapsing at 6N²
std::vector<ReportAxis> report_axes(bool quick,
                                    const std::optional<std::vector<int>>& haar_cubes = {});

// The names of every file run_report may write into the output directory (so a caller can
// check them before the run).
std::vector<std::string> report_file_names();

// Runs everything and writes the files. Throws std::runtime_error on failure.
ReportResult run_report(const ReportOptions& options);

}  // namespace prt::report
