// report/plot_svg.h — small self-contained SVG line/scatter plots for the report: axes with
// linear or logarithmic scales (decade ticks labelled 10^k with minor ticks at 2..9), axis
// labels, a title, a legend, markers, lines (solid or dashed), and conversion to PNG with
// rsvg-convert (Debian package librsvg2-bin) when it is installed.
// Coordinates: data space → pixel space by x_px = left + (T(x) − T(x0))/(T(x1) − T(x0))·width,
// T = log10 for log axes (non-positive values are dropped from log plots), y up.
// Point labels are drawn after all markers and placed greedily, in series order, at the first of
// above-right, below-right, above-left, below-left of their marker whose text box (estimated
// from the character count) stays inside the plot and covers no label placed before and no
// marker; failing that, the first that covers no label; failing that, the label is left out
// (overlapping text would be unreadable; the caller's table has the point).
#pragma once

#include <string>
#include <vector>

namespace prt::report {

enum class Marker { None, Circle, Square, Triangle, Diamond, Cross };

struct PlotSeries {
  std::string label;  // legend text; empty: not in the legend
  std::vector<double> x, y;
  std::string color = "#1f77b4";
  bool line = true;
  bool dashed = false;
  double line_width = 2.0;
  Marker marker = Marker::Circle;
  double marker_size = 4.5;
  std::vector<std::string> point_labels;  // optional text next to each point
};

// Where the legend box sits: a corner inside the plot area; Auto = the first corner (top right,
// top left, bottom right, bottom left) whose box covers no marker, line or point label, or, when
// every corner covers something, OutsideRight; OutsideRight = right of the plot area, the
// document widened by the legend's width.
enum class LegendCorner { TopRight, TopLeft, BottomRight, BottomLeft, Auto, OutsideRight };

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  int width = 860, height = 560;
  std::vector<PlotSeries> series;
  // Horizontal reference lines (y value, label), drawn dotted.
  std::vector<std::pair<double, std::string>> reference_lines;
  bool y_as_percent = false;  // tick labels ×100 with a % sign
  LegendCorner legend = LegendCorner::TopRight;
};

// Axis range covering the data (log: whole decades around the data; linear: nice round numbers).
void choose_axis_range(const std::vector<double>& values, bool log_scale, double* lo, double* hi);

// Tick positions: log axes → 10^k in [lo, hi] (major); linear → about `target` round steps.
std::vector<double> major_ticks(double lo, double hi, bool log_scale, int target = 6);
// Minor ticks of a log axis: m·10^k, m = 2..9, inside [lo, hi]; none for linear.
std::vector<double> minor_ticks(double lo, double hi, bool log_scale);

// Formats a tick value: "10^k"-style for log axes ("0.01", "1", "100" for |k| ≤ 3, else "1e-5"),
// shortest round form for linear axes; percent when asked ("1%", "0.1%").
std::string format_tick(double value, bool log_scale, bool percent);

// The whole plot as an SVG document.
std::string render_svg(const PlotSpec& spec);

// Writes `text` to `path` atomically (PATH.tmp-<pid>, then rename). Throws std::runtime_error
// "PATH: problem".
void write_text_file(const std::string& path, const std::string& text);

// Converts an SVG file to PNG with rsvg-convert (at `zoom`× its size). Returns false and says why
// (rsvg-convert missing or failing) without throwing; the PNG is written atomically.
bool convert_svg_to_png(const std::string& svg_path, const std::string& png_path, double zoom,
                        std::string* why);

}  // namespace prt::report
