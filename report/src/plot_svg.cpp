// report/src/plot_svg.cpp — see plot_svg.h.
#include "report/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "prt/core/atomic_file.h"

namespace prt::report {
namespace {

std::string escape_xml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

struct Axis {
  double lo, hi, px0, px1;
  bool log;
  double map(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    return px0 + t * (px1 - px0);
  }
  bool inside(double v) const { return (!log || v > 0) && std::isfinite(v); }
};

std::string marker_svg(Marker m, double x, double y, double r, const std::string& color) {
  std::ostringstream o;
  switch (m) {
    case Marker::None:
      break;
    case Marker::Circle:
      o << "<circle cx='" << number(x) << "' cy='" << number(y) << "' r='" << number(r)
        << "' fill='" << color << "' stroke='white' stroke-width='0.8'/>";
      break;
    case Marker::Square:
      o << "<rect x='" << number(x - r) << "' y='" << number(y - r) << "' width='" << number(2 * r)
        << "' height='" << number(2 * r) << "' fill='" << color
        << "' stroke='white' stroke-width='0.8'/>";
      break;
    case Marker::Triangle:
      o << "<polygon points='" << number(x) << "," << number(y - 1.2 * r) << " "
        << number(x - 1.1 * r) << "," << number(y + 0.8 * r) << " " << number(x + 1.1 * r) << ","
        << number(y + 0.8 * r) << "' fill='" << color << "' stroke='white' stroke-width='0.8'/>";
      break;
    case Marker::Diamond:
      o << "<polygon points='" << number(x) << "," << number(y - 1.3 * r) << " "
        << number(x + 1.3 * r) << "," << number(y) << " " << number(x) << "," << number(y + 1.3 * r)
        << " " << number(x - 1.3 * r) << "," << number(y) << "' fill='" << color
        << "' stroke='white' stroke-width='0.8'/>";
      break;
    case Marker::Cross:
      o << "<path d='M" << number(x - r) << "," << number(y - r) << " L" << number(x + r) << ","
        << number(y + r) << " M" << number(x - r) << "," << number(y + r) << " L" << number(x + r)
        << "," << number(y - r) << "' stroke='" << color << "' stroke-width='2'/>";
      break;
  }
  return o.str();
}

}  // namespace

void choose_axis_range(const std::vector<double>& values, bool log_scale, double* lo, double* hi) {
  double a = INFINITY, b = -INFINITY;
  for (double v : values)
    if (std::isfinite(v) && (!log_scale || v > 0)) a = std::min(a, v), b = std::max(b, v);
  if (!(a <= b)) {
    *lo = log_scale ? 0.1 : 0.0;
    *hi = log_scale ? 10.0 : 1.0;
    return;
  }
  if (log_scale) {
    *lo = std::pow(10.0, std::floor(std::log10(a) + 1e-9));
    *hi = std::pow(10.0, std::ceil(std::log10(b) - 1e-9));
    if (*hi <= *lo) *hi = *lo * 10.0;
    return;
  }
  if (a == b) a -= 0.5, b += 0.5;
  const std::vector<double> ticks = major_ticks(a, b, false, 6);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : (b - a);
  *lo = std::floor(a / step + 1e-9) * step;
  *hi = std::ceil(b / step - 1e-9) * step;
}

std::vector<double> major_ticks(double lo, double hi, bool log_scale, int target) {
  std::vector<double> t;
  if (!(hi > lo)) return t;
  if (log_scale) {
    if (!(lo > 0)) return t;
    for (int k = static_cast<int>(std::floor(std::log10(lo) - 1e-9));
         k <= static_cast<int>(std::ceil(std::log10(hi) + 1e-9)); ++k) {
      const double v = std::pow(10.0, k);
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
    }
    return t;
  }
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
  return t;
}

std::vector<double> minor_ticks(double lo, double hi, bool log_scale) {
  std::vector<double> t;
  if (!log_scale || !(lo > 0) || !(hi > lo)) return t;
  for (int k = static_cast<int>(std::floor(std::log10(lo)));
       k <= static_cast<int>(std::ceil(std::log10(hi))); ++k)
    for (int m = 2; m <= 9; ++m) {
      const double v = m * std::pow(10.0, k);
      if (v > lo && v < hi) t.push_back(v);
    }
  return t;
}

std::string format_tick(double value, bool log_scale, bool percent) {
  const double v = percent ? value * 100.0 : value;
  char buf[32];
  if (log_scale) {
    const int k = static_cast<int>(std::lround(std::log10(std::fabs(v))));
    if (k >= -4 && k <= 4)
      std::snprintf(buf, sizeof buf, "%.*f", k < 0 ? -k : 0, v);
    else
      std::snprintf(buf, sizeof buf, "1e%d", k);
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return std::string(buf) + (percent ? "%" : "");
}

namespace {

// An axis-aligned box in pixels.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& b) const { return x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1; }
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// True when the segment (ax, ay)–(bx, by) meets the box (Liang–Barsky clipping).
bool segment_meets(const Box& b, double ax, double ay, double bx, double by) {
  double t0 = 0, t1 = 1;
  const double dx = bx - ax, dy = by - ay;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {ax - b.x0, b.x1 - ax, ay - b.y0, b.y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

// Text box of a 10-px label (DejaVu Sans averages ≈ 6 px per character at that size).
constexpr double kLabelCharWidth = 6.0, kLabelHeight = 10.0;

// The plot area in pixels and the axes mapping data onto it.
struct PlotFrame {
  double W, H;                      // the plot's size (the document may grow for the legend)
  double left, right, top, bottom;  // the plot area
  Axis ax, ay;
};

// The plot area and axis ranges that hold every point and reference line of `spec`.
PlotFrame plot_frame(const PlotSpec& spec) {
  PlotFrame f;
  f.W = spec.width, f.H = spec.height;
  f.left = 86, f.right = f.W - 24, f.top = 48, f.bottom = f.H - 64;
  std::vector<double> xs, ys;
  for (const PlotSeries& s : spec.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  for (const auto& r : spec.reference_lines) ys.push_back(r.first);
  choose_axis_range(xs, spec.log_x, &f.ax.lo, &f.ax.hi);
  choose_axis_range(ys, spec.log_y, &f.ay.lo, &f.ay.hi);
  f.ax.px0 = f.left, f.ax.px1 = f.right, f.ax.log = spec.log_x;
  f.ay.px0 = f.bottom, f.ay.px1 = f.top, f.ay.log = spec.log_y;
  return f;
}

// Title, grid lines and ticks, the plot's border and the axis labels.
void draw_frame(std::ostream& o, const PlotSpec& spec, const PlotFrame& f) {
  const double left = f.left, right = f.right, top = f.top, bottom = f.bottom;
  const Axis &ax = f.ax, &ay = f.ay;
  o << "<text x='" << number(f.W / 2) << "' y='28' text-anchor='middle' font-size='17' "
    << "font-weight='bold'>" << escape_xml(spec.title) << "</text>\n";
  // Grid and ticks.
  for (double v : minor_ticks(ax.lo, ax.hi, ax.log))
    o << "<line x1='" << number(ax.map(v)) << "' y1='" << top << "' x2='" << number(ax.map(v))
      << "' y2='" << bottom << "' stroke='#eeeeee'/>\n";
  for (double v : minor_ticks(ay.lo, ay.hi, ay.log))
    o << "<line x1='" << left << "' y1='" << number(ay.map(v)) << "' x2='" << right << "' y2='"
      << number(ay.map(v)) << "' stroke='#eeeeee'/>\n";
  for (double v : major_ticks(ax.lo, ax.hi, ax.log)) {
    const double x = ax.map(v);
    o << "<line x1='" << number(x) << "' y1='" << top << "' x2='" << number(x) << "' y2='" << bottom
      << "' stroke='#d0d0d0'/>\n"
      << "<text x='" << number(x) << "' y='" << bottom + 20 << "' text-anchor='middle' "
      << "font-size='13'>" << format_tick(v, ax.log, false) << "</text>\n";
  }
  for (double v : major_ticks(ay.lo, ay.hi, ay.log)) {
    const double y = ay.map(v);
    o << "<line x1='" << left << "' y1='" << number(y) << "' x2='" << right << "' y2='" << number(y)
      << "' stroke='#d0d0d0'/>\n"
      << "<text x='" << left - 8 << "' y='" << number(y + 4) << "' text-anchor='end' "
      << "font-size='13'>" << format_tick(v, ay.log, spec.y_as_percent) << "</text>\n";
  }
  o << "<rect x='" << left << "' y='" << top << "' width='" << right - left << "' height='"
    << bottom - top << "' fill='none' stroke='#333333'/>\n";
  o << "<text x='" << number((left + right) / 2) << "' y='" << f.H - 18
    << "' text-anchor='middle' font-size='14'>" << escape_xml(spec.x_label) << "</text>\n";
  o << "<text transform='translate(20," << number((top + bottom) / 2)
    << ") rotate(-90)' text-anchor='middle' font-size='14'>" << escape_xml(spec.y_label)
    << "</text>\n";
}

void draw_reference_lines(std::ostream& o, const PlotSpec& spec, const PlotFrame& f) {
  for (const auto& r : spec.reference_lines) {
    if (!f.ay.inside(r.first) || r.first < f.ay.lo || r.first > f.ay.hi) continue;
    const double y = f.ay.map(r.first);
    o << "<line x1='" << f.left << "' y1='" << number(y) << "' x2='" << f.right << "' y2='"
      << number(y) << "' stroke='#888888' stroke-dasharray='2,4' stroke-width='1.2'/>\n"
      << "<text x='" << f.right - 4 << "' y='" << number(y - 4) << "' text-anchor='end' "
      << "font-size='11' fill='#666666'>" << escape_xml(r.second) << "</text>\n";
  }
}

// A point label waiting for its place (placed once every marker is drawn).
struct PendingLabel {
  double x, y;
  std::string text;
};

// What drawing the series leaves for the labels and the legend to avoid.
struct DrawnSeries {
  std::vector<std::vector<std::pair<double, double>>> drawn;  // pixel points per polyline
  std::vector<PendingLabel> pending;
};

// Lines and markers of every series.
DrawnSeries draw_series(std::ostream& o, const PlotSpec& spec, const PlotFrame& f) {
  DrawnSeries d;
  for (const PlotSeries& s : spec.series) {
    std::vector<std::pair<double, double>> pts;
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (f.ax.inside(s.x[i]) && f.ay.inside(s.y[i])) {
        pts.emplace_back(f.ax.map(s.x[i]), f.ay.map(s.y[i]));
        labels.push_back(i < s.point_labels.size() ? s.point_labels[i] : std::string());
      }
    if (s.line && pts.size() > 1) {
      o << "<polyline fill='none' stroke='" << s.color << "' stroke-width='" << s.line_width << "'"
        << (s.dashed ? " stroke-dasharray='7,5'" : "") << " points='";
      for (const auto& p : pts) o << number(p.first) << "," << number(p.second) << " ";
      o << "'/>\n";
    }
    for (std::size_t i = 0; i < pts.size(); ++i) {
      o << marker_svg(s.marker, pts[i].first, pts[i].second, s.marker_size, s.color) << "\n";
      if (!labels[i].empty()) d.pending.push_back({pts[i].first, pts[i].second, labels[i]});
    }
    if (s.line)
      d.drawn.push_back(pts);
    else  // markers only: the points, but no segments between them
      for (const auto& pt : pts) d.drawn.push_back({pt});
  }
  return d;
}

// Point labels, after every marker is known (placement: see the header). Returns the boxes of
// the labels placed.
std::vector<Box> draw_point_labels(std::ostream& o, const DrawnSeries& d, const PlotFrame& f) {
  std::vector<Box> label_boxes;
  for (const PendingLabel& l : d.pending) {
    const double px = l.x, py = l.y;
    const double w = kLabelCharWidth * static_cast<double>(l.text.size());
    const Box candidates[4] = {{px + 7, py - 6 - kLabelHeight, px + 7 + w, py - 4},
                               {px + 7, py + 4, px + 7 + w, py + 6 + kLabelHeight},
                               {px - 7 - w, py - 6 - kLabelHeight, px - 7, py - 4},
                               {px - 7 - w, py + 4, px - 7, py + 6 + kLabelHeight}};
    // First choice: clear of labels and markers; second: clear of labels; else no label.
    int pick = -1;
    for (int pass = 0; pass < 2 && pick < 0; ++pass)
      for (int c = 0; c < 4 && pick < 0; ++c) {
        const Box& b = candidates[c];
        bool free = b.x0 >= f.left && b.x1 <= f.right && b.y0 >= f.top && b.y1 <= f.bottom;
        for (const Box& placed : label_boxes) free = free && !b.overlaps(placed);
        const Box grown{b.x0 - 3, b.y0 - 3, b.x1 + 3, b.y1 + 3};  // marker radius
        if (pass == 0)
          for (const auto& series_pts : d.drawn)
            for (const auto& [x, y] : series_pts) free = free && !grown.contains(x, y);
        if (free) pick = c;
      }
    if (pick < 0) continue;
    const Box& b = candidates[pick];
    label_boxes.push_back(b);
    o << "<text x='" << number(pick < 2 ? b.x0 : b.x1) << "' y='" << number(b.y1 - 2) << "'"
      << (pick < 2 ? "" : " text-anchor='end'") << " font-size='10' fill='#444444'>"
      << escape_xml(l.text) << "</text>\n";
  }
  return label_boxes;
}

// The legend's box: in the corner the spec asks for, or (Auto) the first corner that covers no
// point, segment or label, else outside on the right (*outside).
Box legend_box(const PlotSpec& spec, const PlotFrame& f, double lw, double lh, const DrawnSeries& d,
               const std::vector<Box>& label_boxes, bool* outside) {
  const auto corner_box = [&](LegendCorner c) {
    const bool at_left = c == LegendCorner::BottomLeft || c == LegendCorner::TopLeft;
    const bool at_bottom = c == LegendCorner::BottomLeft || c == LegendCorner::BottomRight;
    const double x0 = at_left ? f.left + 8 : f.right - lw - 8;
    const double y0 = at_bottom ? f.bottom - lh - 8 : f.top + 8;
    return Box{x0, y0, x0 + lw, y0 + lh};
  };
  const auto covers_nothing = [&](const Box& b) {
    for (const auto& pts : d.drawn) {
      for (const auto& [x, y] : pts)
        if (Box{b.x0 - 5, b.y0 - 5, b.x1 + 5, b.y1 + 5}.contains(x, y)) return false;
      for (std::size_t i = 1; i < pts.size(); ++i)
        if (segment_meets(b, pts[i - 1].first, pts[i - 1].second, pts[i].first, pts[i].second))
          return false;
    }
    for (const Box& l : label_boxes)
      if (b.overlaps(l)) return false;
    return true;
  };
  LegendCorner where = spec.legend;
  if (where == LegendCorner::Auto) {
    where = LegendCorner::OutsideRight;
    for (LegendCorner c : {LegendCorner::TopRight, LegendCorner::TopLeft, LegendCorner::BottomRight,
                           LegendCorner::BottomLeft})
      if (covers_nothing(corner_box(c))) {
        where = c;
        break;
      }
  }
  *outside = where == LegendCorner::OutsideRight;
  if (*outside) return Box{f.right + 16, f.top, f.right + 16 + lw, f.top + lh};
  return corner_box(where);
}

// The legend (when any series has a label). Returns the document's width: the plot's, or wider
// when the legend stands outside on the right.
double draw_legend(std::ostream& o, const PlotSpec& spec, const PlotFrame& f, const DrawnSeries& d,
                   const std::vector<Box>& label_boxes) {
  int entries = 0;
  std::size_t longest = 0;
  for (const PlotSeries& s : spec.series)
    if (!s.label.empty()) ++entries, longest = std::max(longest, s.label.size());
  if (entries == 0) return f.W;
  const double lw = 46 + 6.6 * static_cast<double>(longest), lh = 8 + 19.0 * entries;
  bool outside = false;
  const Box box = legend_box(spec, f, lw, lh, d, label_boxes, &outside);
  const double lx = box.x0, ly = box.y0;
  o << "<rect x='" << number(lx) << "' y='" << number(ly) << "' width='" << number(lw)
    << "' height='" << number(lh) << "' fill='white' fill-opacity='0.9' stroke='#999999'/>\n";
  int row = 0;
  for (const PlotSeries& s : spec.series) {
    if (s.label.empty()) continue;
    const double y = ly + 14 + 19.0 * row++;
    if (s.line)
      o << "<line x1='" << number(lx + 6) << "' y1='" << number(y) << "' x2='" << number(lx + 34)
        << "' y2='" << number(y) << "' stroke='" << s.color << "' stroke-width='" << s.line_width
        << "'" << (s.dashed ? " stroke-dasharray='7,5'" : "") << "/>\n";
    o << marker_svg(s.marker, lx + 20, y, s.marker_size, s.color) << "\n";
    o << "<text x='" << number(lx + 40) << "' y='" << number(y + 4) << "' font-size='12'>"
      << escape_xml(s.label) << "</text>\n";
  }
  return outside ? std::ceil(box.x1 + 12) : f.W;
}

}  // namespace

std::string render_svg(const PlotSpec& spec) {
  const PlotFrame frame = plot_frame(spec);
  std::ostringstream o;  // everything after the document header
  draw_frame(o, spec, frame);
  draw_reference_lines(o, spec, frame);
  o << "<g>\n";
  const DrawnSeries drawn = draw_series(o, spec, frame);
  const std::vector<Box> label_boxes = draw_point_labels(o, drawn, frame);
  o << "</g>\n";
  const double document_width = draw_legend(o, spec, frame, drawn, label_boxes);
  std::ostringstream doc;
  doc << "<?xml version='1.0' encoding='UTF-8'?>\n"
      << "<svg xmlns='http://www.w3.org/2000/svg' width='" << document_width << "' height='"
      << spec.height << "' viewBox='0 0 " << document_width << " " << spec.height
      << "' font-family='DejaVu Sans, Helvetica, Arial, sans-serif'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << o.str() << "</svg>\n";
  return doc.str();
}

void write_text_file(const std::string& path, const std::string& text) {
  const prt::Status written = prt::replace_file_atomically(path, [&](const std::string& temporary) {
    std::ofstream f(temporary, std::ios::binary);
    if (!f) return prt::Status::Error(path + ": cannot open for writing");
    f << text;
    f.flush();
    return f ? prt::Status::Ok() : prt::Status::Error(path + ": write failed");
  });
  if (!written.ok()) throw std::runtime_error(written.message());
}

bool convert_svg_to_png(const std::string& svg_path, const std::string& png_path, double zoom,
                        std::string* why) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) {
    if (why) *why = "rsvg-convert not found (install librsvg2-bin)";
    return false;
  }
  const std::string quote = "'";
  auto quoted = [&](const std::string& s) {
    std::string q = quote;
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + quote;
  };
  char zoom_text[32];
  std::snprintf(zoom_text, sizeof zoom_text, "%.3f", zoom);
  const prt::Status written =
      prt::replace_file_atomically(png_path, [&](const std::string& temporary) {
        const std::string cmd = "rsvg-convert --zoom=" + std::string(zoom_text) + " -o " +
                                quoted(temporary) + " " + quoted(svg_path) + " 2>/dev/null";
        if (std::system(cmd.c_str()) != 0)
          return prt::Status::Error(svg_path + ": rsvg-convert failed");
        return prt::Status::Ok();
      });
  if (!written.ok() && why) *why = written.message();
  return written.ok();
}

}  // namespace prt::report
