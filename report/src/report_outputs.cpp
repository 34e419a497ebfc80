// report/src/report_outputs.cpp — the files `prt report` writes: results.csv, results.json, and
// (through report_plots.cpp and report_summary.cpp) the plots and summary.md.

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/plot_svg.h"
#include "report_state.h"
#include "sh/basis.h"

namespace prt::report::detail {

namespace {

// Haar cube sizes measured, in sweep order.
std::vector<int> haar_cubes_swept(const ReportResult& result) {
  std::vector<int> cubes;
  for (const ReportMeasurement& m : result.measurements)
    if (is_haar(m.setting) && std::find(cubes.begin(), cubes.end(), m.setting.cube) == cubes.end())
      cubes.push_back(m.setting.cube);
  return cubes;
}

void write_results_csv(ReportState& st) {
  std::ostringstream csv;
  // basis sh: order and samples set, cube and terms empty; basis haar: the other way round
  // (terms = the lighting terms used, 6N² for all).
  csv << "axis,basis,order,samples,cube,terms,bounces,precision,bake_seconds,relight_seconds,"
         "file_bytes,relative_rms,p99_relative,max_relative,image_relative_rms,pareto,failure\n";
  for (const ReportMeasurement& m : st.result.measurements) {
    std::string failure = m.failure;
    std::replace(failure.begin(), failure.end(), ',', ';');
    const ReportSetting& s = m.setting;
    csv << m.axis << "," << basis_name(s) << ",";
    if (is_haar(s))
      csv << ",," << s.cube << "," << haar_terms_used(s) << ",";
    else
      csv << s.order << "," << s.samples << ",,,";
    csv << bounces_name(s.bounces) << "," << storage_name(s) << "," << m.bake_seconds << ","
        << m.relight_seconds << "," << m.file_bytes << "," << m.relative_rms << "," << m.p99 << ","
        << m.max << "," << m.image_relative_rms << "," << (m.on_pareto_front ? 1 : 0) << ","
        << failure << "\n";
  }
  write_output(st, "results.csv", csv.str());
}

nlohmann::json error_definitions_json(const relight::RenderOptions& ropt) {
  return {{"relative_rms", "sqrt(sum_p |B_p - B_gt,p|^2) / sqrt(sum_p |B_gt,p|^2), |.| RGB norm"},
          {"p99_relative/max_relative",
           "per-vertex |B_p - B_gt,p| / max(|B_gt,p|, 0.05 * RMS_p |B_gt,p|): 99th percentile "
           "(nearest rank) and maximum"},
          {"image_relative_rms",
           "relative RMS over the pixels that show the scene, " + std::to_string(ropt.width) + "x" +
               std::to_string(ropt.height) + " with 2x2 samples, same camera for both"},
          {"bake_seconds",
           "wall time of bake_transfer (SH) or bake_haar_transfer (Haar: one bake per cube size, "
           "shared by its K settings), all threads"},
          {"relight_seconds",
           "best of 5 wall times of shading every vertex (SH: all threads; Haar: "
           "HaarRelighter::shade on one thread, as prt relight)"}};
}

nlohmann::json measurement_json(const ReportMeasurement& m) {
  const ReportSetting& s = m.setting;
  const nlohmann::json none;  // null: the field does not apply to this basis
  return {{"axis", m.axis},
          {"basis", basis_name(s)},
          {"order", is_haar(s) ? none : nlohmann::json(s.order)},
          {"samples", is_haar(s) ? none : nlohmann::json(s.samples)},
          {"cube", is_haar(s) ? nlohmann::json(s.cube) : none},
          {"terms", is_haar(s) ? nlohmann::json(haar_terms_used(s)) : none},
          {"all_terms", is_haar(s) ? nlohmann::json(s.terms <= 0) : none},
          {"bounces", bounces_name(s.bounces)},
          {"precision", storage_name(s)},
          {"bake_seconds", m.bake_seconds},
          {"relight_seconds", m.relight_seconds},
          {"file_bytes", m.file_bytes},
          {"relative_rms", m.relative_rms},
          {"p99_relative", m.p99},
          {"max_relative", m.max},
          {"image_relative_rms", m.image_relative_rms},
          {"pareto", m.on_pareto_front},
          {"failure", m.failure}};
}

nlohmann::json auto_json(const ReportAuto& a) {
  return {{"tolerance", a.tolerance},
          {"order", a.order},
          {"channels", a.channels},
          {"kind", a.kind},
          {"haar_recommended", a.haar_recommended},
          {"predicted_error", a.predicted_error},
          {"predicted_error_scope", "excludes the mesh's interpolation of interreflected light"},
          {"bake_seconds", a.bake_seconds},
          {"file_bytes", a.file_bytes},
          {"relative_rms", a.relative_rms},
          {"p99_relative", a.p99},
          {"max_relative", a.max},
          {"cheapest_fixed_index", a.cheapest_fixed},
          {"failure", a.failure}};
}

void write_results_json(ReportState& st) {
  const ReportOptions& opt = st.opt;
  const ReportResult& result = st.result;
  const report::GroundTruthResult& truth = st.truth;
  nlohmann::json j;
  j["sh_basis"] = sh::kBasisConvention;
  j["scene"] = opt.scene_path;
  j["environment"] = opt.environment_path;
  j["environment_layout"] = st.in.layout_note;
  j["vertices"] = st.in.V;
  j["quick"] = opt.quick;
  j["base_setting"] = {{"order", st.base.order},
                       {"samples", st.base.samples},
                       {"bounces", bounces_name(st.base.bounces)},
                       {"precision", "f32"}};
  j["error_definitions"] = error_definitions_json(st.in.ropt);
  j["ground_truth"] = {{"samples_per_vertex", truth.samples_per_vertex},
                       {"relative_rms_standard_error", truth.relative_rms_se},
                       {"seconds", truth.seconds},
                       {"rays", truth.rays},
                       {"mrays_per_second", truth.mrays_per_second()},
                       {"max_bounces", st.gto.max_bounces},
                       {"adequate", result.ground_truth_adequate},
                       {"smallest_error_measured", st.e_min}};
  j["haar"] = {{"transfer", "interreflected, bounces as the base setting"},
               {"directions", "one per cube texel (6N^2 per vertex, texel centres)"},
               {"relative_threshold", kHaarThreshold},
               {"quantization_bits", static_cast<int>(kHaarQuantization)},
               {"lighting", "non-linear: the K largest area-weighted wavelet coefficients"},
               {"relight_seconds",
                "best of 5, HaarRelighter::shade on one thread (as prt "
                "relight); lighting selection not included"}};
  nlohmann::json rows = nlohmann::json::array();
  for (const ReportMeasurement& m : result.measurements) rows.push_back(measurement_json(m));
  j["results"] = rows;
  nlohmann::json autos = nlohmann::json::array();
  for (const ReportAuto& a : result.autos) autos.push_back(auto_json(a));
  j["auto"] = autos;
  j["split"] = {{"orders", result.orders},
                {"projection_error", result.projection_error},
                {"reference_samples", st.reference_samples},
                {"sampling_samples", result.split_samples},
                {"sampling_error", result.sampling_error}};
  write_output(st, "results.json", j.dump(2) + "\n");
}

}  // namespace

std::string output_path(const ReportState& st, const std::string& name) {
  return (std::filesystem::path(st.opt.output_dir) / name).string();
}

// Writes a file of the output directory atomically and lists it in the result.
void write_output(ReportState& st, const std::string& name, const std::string& text) {
  write_text_file(output_path(st, name), text);
  st.result.files_written.push_back(output_path(st, name));
}

// The error levels marked on the plots and tabulated in the summary.
std::vector<std::pair<double, std::string>> error_thresholds() {
  return {{0.01, "1%"}, {0.05, "5%"}, {0.10, "10%"}};
}

// A Haar cube's measured (not failed) rows, by ascending K.
std::vector<std::size_t> haar_rows_by_terms(const ReportResult& result, int cube) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < result.measurements.size(); ++i) {
    const ReportMeasurement& m = result.measurements[i];
    if (is_haar(m.setting) && m.setting.cube == cube && m.failure.empty()) rows.push_back(i);
  }
  std::sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) {
    return haar_terms_used(result.measurements[a].setting) <
           haar_terms_used(result.measurements[b].setting);
  });
  return rows;
}

// Writes STEM.svg and, through rsvg-convert, STEM.png (else notes why not).

// results.csv, results.json, the plots (SVG, and PNG when rsvg-convert is there), summary.md.
void write_outputs(ReportState& st) {
  write_results_csv(st);
  write_results_json(st);
  const std::vector<int> haar_cubes = haar_cubes_swept(st.result);
  write_pareto_plot(st, haar_cubes);
  write_error_vs_order_plot(st);
  if (!haar_cubes.empty()) write_haar_terms_plot(st, haar_cubes);
  write_summary(st, haar_cubes);
}

}  // namespace prt::report::detail
