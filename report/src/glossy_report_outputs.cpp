// report/src/glossy_report_outputs.cpp — results.csv, the two plots and summary.md of
// `prt report --glossy` (glossy_report_outputs.h).
#include "glossy_report_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include "report/plot_svg.h"

namespace prt::report::detail {
namespace {

std::string path_in(const GlossyReportOptions& o, const std::string& name) {
  return (std::filesystem::path(o.output_dir) / name).string();
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string percent(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g%%", 100 * v);
  return buf;
}

std::string setting_label(const GlossyReportRow& r) {
  char buf[64];
  if (r.clusters > 0)
    std::snprintf(buf, sizeof buf, "%ux%u", r.clusters, r.vectors);
  else
    std::snprintf(buf, sizeof buf, "n%d N%d b%d", r.order, r.samples, r.bounces);
  return buf;
}

std::string results_csv(const GlossyReportResult& result) {
  std::ostringstream csv;
  csv << "axis,order,samples,bounces,clusters,vectors,channels,bytes,bake_seconds,"
         "compress_seconds,relighter_seconds,shade_seconds,relative_rms,"
         "relative_rms_non_grazing,cpca_matrix_error,pareto_storage,pareto_bake_time";
  for (const std::string& name : result.primitive_names) csv << ",error_" << name;
  csv << '\n';
  for (const GlossyReportRow& r : result.rows) {
    csv << r.axis << ',' << r.order << ',' << r.samples << ',' << r.bounces << ',' << r.clusters
        << ',' << r.vectors << ',' << r.channels << ',' << r.bytes << ','
        << fixed(r.bake_seconds, 3) << ',' << fixed(r.compress_seconds, 3) << ','
        << fixed(r.relighter_seconds, 3) << ',' << fixed(r.shade_seconds, 5) << ','
        << fixed(r.relative_rms, 6) << ',' << fixed(r.relative_rms_non_grazing, 6) << ','
        << fixed(r.cpca_matrix_error, 6) << ',' << (r.front_storage ? 1 : 0) << ','
        << (r.front_bake_time ? 1 : 0);
    for (double e : r.primitive_rms) csv << ',' << fixed(e, 6);
    csv << '\n';
  }
  return csv.str();
}

const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd"};

// One series per axis (a shared row in each of its axes), x from `cost`.
PlotSpec error_plot(const GlossyReportResult& result,
                    const std::function<double(const GlossyReportRow&)>& cost) {
  PlotSpec spec;
  spec.log_x = spec.log_y = true;
  spec.y_as_percent = true;
  spec.y_label = "relative RMS error of exit radiance";
  spec.legend = LegendCorner::OutsideRight;
  const char* const axes[] = {"order", "samples", "bounces", "cpca"};
  const Marker markers[] = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond};
  for (int a = 0; a < 4; ++a) {
    PlotSeries s;
    s.label = a == 3 ? "CPCA of the base bake (clusters x vectors)"
                     : std::string(axes[a]) + " varied (n order, N samples, b bounces)";
    s.color = kPalette[a];
    s.marker = markers[a];
    std::vector<const GlossyReportRow*> rows;
    for (const GlossyReportRow& r : result.rows)
      if (("+" + r.axis + "+").find(std::string("+") + axes[a] + "+") != std::string::npos)
        rows.push_back(&r);
    std::sort(rows.begin(), rows.end(),
              [&cost](const GlossyReportRow* x, const GlossyReportRow* y) {
                return cost(*x) < cost(*y);
              });
    for (const GlossyReportRow* r : rows) {
      s.x.push_back(cost(*r));
      s.y.push_back(r->relative_rms);
      s.point_labels.push_back(setting_label(*r));
    }
    if (!s.x.empty()) spec.series.push_back(s);
  }
  spec.reference_lines = {{result.ground_truth_relative_se, "ground-truth noise"}};
  return spec;
}

void write_plot(const GlossyReportOptions& o, const PlotSpec& spec, const std::string& stem,
                std::vector<std::string>* written) {
  write_text_file(path_in(o, stem + ".svg"), render_svg(spec));
  written->push_back(path_in(o, stem + ".svg"));
  std::string why;
  if (convert_svg_to_png(path_in(o, stem + ".svg"), path_in(o, stem + ".png"), 1.5, &why))
    written->push_back(path_in(o, stem + ".png"));
}

// The materials the bakes and the ground truth used: the overrides as given, then each
// primitive's (scene::describe_materials).
std::string materials_md(const GlossyReportOptions& o, const GlossyReportResult& result) {
  std::ostringstream md;
  md << "## Materials\n\n";
  if (o.material_overrides.empty())
    md << "The scene's own (no `--material`).";
  else {
    md << "The scene's, with `--material` overrides (in order, a later one wins):";
    for (const scene::MaterialOverride& m : o.material_overrides) md << " `" << m.text << "`";
    md << ".";
  }
  md << " Bakes and ground truth use the same BRDF per primitive:\n\n";
  for (const std::string& line : result.materials) md << "- " << line << "\n";
  md << "\n";
  return md.str();
}

std::string summary_md(const GlossyReportOptions& o, const GlossyReportResult& result) {
  std::ostringstream md;
  md << "# prt report --glossy: glossy PRT error against cost\n\n"
     << "Scene `" << o.scene_path << "`, environment `" << o.environment_path << "`, "
     << (o.quick ? "quick" : "full") << " sweep, seed " << o.seed << ". Generated by `prt report "
     << "--glossy" << (o.quick ? " --quick" : "");
  for (const scene::MaterialOverride& m : o.material_overrides)
    md << " --material '" << m.text << "'";
  md << "`.\n\n"
     << materials_md(o, result) << "## Ground truth\n\n"
     << "Path tracing with each surface's BRDF (report/glossy_ground_truth.h: environment "
        "importance sampling and BRDF sampling combined by the balance heuristic, interreflection "
        "up to 64 bounces with Russian roulette) toward ";
  for (std::size_t i = 0; i < result.eyes.size(); ++i)
    md << (i ? ", " : "") << "(" << fixed(result.eyes[i][0], 2) << ", "
       << fixed(result.eyes[i][1], 2) << ", " << fixed(result.eyes[i][2], 2) << ")";
  md << ": " << result.vertices_per_eye << " vertices per eye (an equal share of each "
     << "primitive's vertices facing the eye), up to " << result.ground_truth_samples
     << " samples per vertex, relative RMS standard error **"
     << percent(result.ground_truth_relative_se) << "** (the noise floor of every error below; "
     << "they add in quadrature), " << fixed(result.ground_truth_seconds, 1) << " s.\n\n"
     << "## Settings\n\nError: relative RMS of the exit radiance (RGB) over those vertices and "
        "eyes. Storage: the transfer matrices only (f32; CPCA: its payload). Bake: wall time, all "
        "threads; CPCA rows add the compression. Shade: one pass over every vertex, one thread. "
        "Non-grazing: the error without views within ~6° of the tangent plane (n·ω_o < 0.1). "
        "P: on the Pareto front of error against storage (s) or against bake time (t). The error "
        "over each primitive's vertices alone is in results.csv.\n\n"
     << "| axis | setting | channels | storage | bake | compress | relighter | shade | error | "
        "non-grazing | CPCA matrix error | P "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const GlossyReportRow& r : result.rows)
    md << "| " << r.axis << " | "
       << (r.clusters ? "CPCA " + std::to_string(r.clusters) + " clusters x " +
                            std::to_string(r.vectors) + " vectors"
                      : "order " + std::to_string(r.order) + ", " + std::to_string(r.samples) +
                            " samples, " + std::to_string(r.bounces) + " bounce(s)")
       << " | " << r.channels << " | " << fixed(double(r.bytes) / 1e6, 2) << " MB | "
       << fixed(r.bake_seconds, 1) << " s | "
       << (r.clusters ? fixed(r.compress_seconds, 1) + " s" : "") << " | "
       << fixed(r.relighter_seconds, 2) << " s | " << fixed(r.shade_seconds * 1e3, 1) << " ms | **"
       << percent(r.relative_rms) << "** | " << percent(r.relative_rms_non_grazing) << " | "
       << (r.clusters ? percent(r.cpca_matrix_error) : "") << " | " << (r.front_storage ? "s" : "")
       << (r.front_bake_time ? "t" : "") << " |\n";
  md << "\n![error against storage](pareto.svg)\n\n![error against bake time]"
        "(error_vs_bake_time.svg)\n";
  return md.str();
}

}  // namespace

void write_glossy_outputs(const GlossyReportOptions& o, const GlossyReportResult& result,
                          std::vector<std::string>* written) {
  write_text_file(path_in(o, "results.csv"), results_csv(result));
  written->push_back(path_in(o, "results.csv"));
  PlotSpec storage = error_plot(result, [](const GlossyReportRow& r) { return double(r.bytes); });
  storage.title = "Glossy PRT: error against storage of the transfer";
  storage.x_label = "transfer storage (bytes)";
  write_plot(o, storage, "pareto", written);
  PlotSpec bake = error_plot(
      result, [](const GlossyReportRow& r) { return r.bake_seconds + r.compress_seconds; });
  bake.title = "Glossy PRT: error against bake time";
  bake.x_label = "bake (+ CPCA) wall time (s)";
  write_plot(o, bake, "error_vs_bake_time", written);
  write_text_file(path_in(o, "summary.md"), summary_md(o, result));
  written->push_back(path_in(o, "summary.md"));
}

}  // namespace prt::report::detail
