// report/src/report_plots.cpp — the SVG (and PNG) plots of `prt report`: error against bake time
// with its Pareto front, error against SH order, and Haar error against kept terms.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "report/plot_svg.h"
#include "report_state.h"

namespace prt::report::detail {

namespace {

const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
// Haar series (one per cube size), apart from the SH grid's first five palette colours.
const char* const kHaarPalette[] = {"#8c564b", "#e377c2", "#17becf", "#bcbd22"};

void write_plot(ReportState& st, const PlotSpec& spec, const std::string& stem) {
  write_output(st, stem + ".svg", render_svg(spec));
  std::string why;
  if (convert_svg_to_png(output_path(st, stem + ".svg"), output_path(st, stem + ".png"), 1.5, &why))
    st.result.files_written.push_back(output_path(st, stem + ".png"));
  else
    st.png_notes.push_back(why);
}

// Pareto plot: the SH grid, one line per order through its sample counts.
std::vector<PlotSeries> grid_series(const ReportResult& result) {
  std::vector<int> grid_orders;
  for (const ReportMeasurement& m : result.measurements)
    if (m.axis.find("grid") != std::string::npos &&
        std::find(grid_orders.begin(), grid_orders.end(), m.setting.order) == grid_orders.end())
      grid_orders.push_back(m.setting.order);
  std::sort(grid_orders.begin(), grid_orders.end());
  std::vector<PlotSeries> series;
  for (std::size_t g = 0; g < grid_orders.size(); ++g) {
    PlotSeries s;
    s.label = "SH order " + std::to_string(grid_orders[g]) + ", samples varied";
    s.color = kPalette[g % 10];
    s.line_width = 1.5;
    std::vector<std::pair<int, std::size_t>> pts;
    for (std::size_t i = 0; i < result.measurements.size(); ++i) {
      const ReportMeasurement& m = result.measurements[i];
      if (m.axis.find("grid") != std::string::npos && m.setting.order == grid_orders[g] &&
          m.failure.empty())
        pts.emplace_back(m.setting.samples, i);
    }
    std::sort(pts.begin(), pts.end());
    for (const auto& [n, i] : pts) {
      s.x.push_back(result.measurements[i].bake_seconds);
      s.y.push_back(result.measurements[i].relative_rms);
    }
    series.push_back(s);
  }
  return series;
}

// Pareto plot: the SH settings off the grid, as markers.
PlotSeries other_axes_series(const ReportResult& result) {
  PlotSeries other;
  other.label = "SH, other axes (bounces, order, samples, f16)";
  other.color = "#555555";
  other.line = false;
  other.marker = Marker::Diamond;
  other.marker_size = 3.5;
  for (const ReportMeasurement& m : result.measurements)
    if (!is_haar(m.setting) && m.axis.find("grid") == std::string::npos && m.failure.empty()) {
      other.x.push_back(m.bake_seconds);
      other.y.push_back(m.relative_rms);
    }
  return other;
}

// Pareto plot: one Haar series per cube size; its K settings share the bake, so they stand in
// a column.
std::vector<PlotSeries> haar_bake_series(const ReportResult& result,
                                         const std::vector<int>& cubes) {
  std::vector<PlotSeries> series;
  for (std::size_t c = 0; c < cubes.size(); ++c) {
    PlotSeries h;
    h.label = "Haar cube " + std::to_string(cubes[c]) + ", K varied (column)";
    h.color = kHaarPalette[c % 4];
    h.marker = Marker::Square;
    h.marker_size = 5;
    h.line_width = 1.5;
    for (std::size_t i : haar_rows_by_terms(result, cubes[c])) {
      h.x.push_back(result.measurements[i].bake_seconds);
      h.y.push_back(result.measurements[i].relative_rms);
    }
    series.push_back(h);
  }
  return series;
}

// Pareto plot: `prt bake --auto` at each tolerance (not part of the front, which is over the
// sweep).
PlotSeries auto_series(const ReportResult& result) {
  PlotSeries au;
  au.label = "prt bake --auto, by tolerance";
  au.color = "#000000";
  au.line = false;
  au.marker = Marker::Triangle;
  au.marker_size = 6;
  for (const ReportAuto& a : result.autos)
    if (a.failure.empty()) {
      char label[32];
      std::snprintf(label, sizeof label, "auto %g%%", 100.0 * a.tolerance);
      au.x.push_back(a.bake_seconds);
      au.y.push_back(a.relative_rms);
      au.point_labels.push_back(label);
    }
  return au;
}

// Pareto plot: the front itself, by bake time, each point labelled with its setting.
PlotSeries pareto_front_series(const ReportResult& result) {
  PlotSeries f;
  f.label = "Pareto front";
  f.color = "#d62728";
  f.dashed = true;
  f.marker = Marker::Circle;
  f.marker_size = 6.5;
  f.line_width = 2.0;
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < result.measurements.size(); ++i)
    if (result.measurements[i].on_pareto_front) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return result.measurements[a].bake_seconds < result.measurements[b].bake_seconds;
  });
  for (std::size_t i : idx) {
    f.x.push_back(result.measurements[i].bake_seconds);
    f.y.push_back(result.measurements[i].relative_rms);
    f.point_labels.push_back(short_label(result.measurements[i].setting));
  }
  return f;
}

}  // namespace

void write_pareto_plot(ReportState& st, const std::vector<int>& haar_cubes) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against bake time (" + std::string(st.opt.quick ? "quick" : "full") + " sweep)";
  p.x_label = "bake time, seconds (wall, all threads; log)";
  p.y_label = "relative RMS error of exit radiance vs ground truth (log)";
  p.log_x = p.log_y = true;
  p.y_as_percent = true;
  p.legend = LegendCorner::Auto;  // a free corner, else beside the plot
  for (const auto& t : error_thresholds()) p.reference_lines.push_back(t);
  p.series = grid_series(result);
  p.series.push_back(other_axes_series(result));
  for (const PlotSeries& h : haar_bake_series(result, haar_cubes)) p.series.push_back(h);
  const PlotSeries au = auto_series(result);
  if (!au.x.empty()) p.series.push_back(au);
  // Front drawn first so the other markers stay visible on top of its big circles.
  p.series.insert(p.series.begin(), pareto_front_series(result));
  write_plot(st, p, "pareto");
}

void write_error_vs_order_plot(ReportState& st) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against SH order: projection vs sampling";
  p.legend = LegendCorner::BottomRight;  // the sampling curves rise into the top right
  p.x_label = "SH order n (n^2 coefficients per channel)";
  p.y_label = "relative RMS error (log)";
  p.log_y = true;
  p.y_as_percent = true;
  PlotSeries proj;
  proj.label = "projection: order-n converged transfer (" + std::to_string(st.reference_samples) +
               " spp) vs ground truth";
  proj.color = "#000000";
  proj.line_width = 3;
  proj.marker = Marker::Square;
  for (std::size_t j = 0; j < result.orders.size(); ++j) {
    proj.x.push_back(result.orders[j]);
    proj.y.push_back(result.projection_error[j]);
  }
  p.series.push_back(proj);
  for (std::size_t si = 0; si < result.split_samples.size(); ++si) {
    PlotSeries s;
    s.label =
        "sampling: " + std::to_string(result.split_samples[si]) + " spp vs converged order-n bake";
    s.color = kPalette[si < 3 ? si : si + 1];  // index 3 (red) is the total's
    s.dashed = true;
    s.marker = Marker::Triangle;
    for (std::size_t j = 0; j < result.orders.size(); ++j)
      if (std::isfinite(result.sampling_error[si][j])) {
        s.x.push_back(result.orders[j]);
        s.y.push_back(result.sampling_error[si][j]);
      }
    p.series.push_back(s);
  }
  PlotSeries total_s;
  total_s.label =
      "total: base setting (" + std::to_string(st.base.samples) + " spp) vs ground truth";
  total_s.color = "#d62728";
  total_s.marker = Marker::Circle;
  for (const ReportMeasurement& m : result.measurements)
    if (m.axis.find("order") != std::string::npos && m.failure.empty()) {
      total_s.x.push_back(m.setting.order);
      total_s.y.push_back(m.relative_rms);
    }
  p.series.push_back(total_s);
  p.reference_lines.push_back({st.truth.relative_rms_se, "ground-truth standard error"});
  write_plot(st, p, "error_vs_order");
}

void write_haar_terms_plot(ReportState& st, const std::vector<int>& haar_cubes) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against lighting terms: Haar (non-linear) and SH";
  p.x_label = "lighting terms per colour channel (Haar: K kept; SH: n^2; log)";
  p.y_label = "relative RMS error of exit radiance vs ground truth (log)";
  p.log_x = p.log_y = true;
  p.y_as_percent = true;
  p.legend = LegendCorner::Auto;  // errors fall to the right: usually bottom left is free
  for (std::size_t c = 0; c < haar_cubes.size(); ++c) {
    PlotSeries h;
    const int cube = haar_cubes[c];
    h.label = "Haar cube " + std::to_string(cube) +
              " (6N^2 = " + std::to_string(haar_coefficient_count(cube)) + "), interreflected";
    h.color = kHaarPalette[c % 4];
    h.marker = Marker::Square;
    for (std::size_t i : haar_rows_by_terms(result, cube)) {
      h.x.push_back(static_cast<double>(haar_terms_used(result.measurements[i].setting)));
      h.y.push_back(result.measurements[i].relative_rms);
    }
    p.series.push_back(h);
  }
  PlotSeries sh_s;
  sh_s.label = "SH order n (order axis, " + std::to_string(st.base.samples) + " spp)";
  sh_s.color = "#1f77b4";
  sh_s.marker = Marker::Circle;
  sh_s.dashed = true;
  for (const ReportMeasurement& m : result.measurements)
    if (!is_haar(m.setting) && m.axis.find("order") != std::string::npos && m.failure.empty()) {
      sh_s.x.push_back(static_cast<double>(m.setting.order) * m.setting.order);
      sh_s.y.push_back(m.relative_rms);
    }
  p.series.push_back(sh_s);
  // The ground truth's SE gets its own line unless it sits on a threshold line (within 25%),
  // where the two labels would print over each other: then the threshold's label says both.
  bool se_shown = false;
  for (const auto& t : error_thresholds()) {
    const double ratio = st.truth.relative_rms_se / t.first;
    if (ratio > 0.8 && ratio < 1.25) {
      p.reference_lines.push_back({t.first, t.second + " ≈ ground-truth SE"});
      se_shown = true;
    } else {
      p.reference_lines.push_back(t);
    }
  }
  if (!se_shown) p.reference_lines.push_back({st.truth.relative_rms_se, "ground-truth SE"});
  write_plot(st, p, "haar_error_vs_terms");
}

}  // namespace prt::report::detail
