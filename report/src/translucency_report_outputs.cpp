// The files of `prt report --translucency` (see report/translucency_report.h).
#include "translucency_report_outputs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bake/subsurface_approx/subsurface_approximations.h"
#include "report/plot_svg.h"

namespace prt::report {
namespace {

const char* const kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                               "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};

std::string fmt(double v, const char* f = "%.6g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

void write_csvs(const std::filesystem::path& dir, const TranslucencyReportResult& r,
                std::vector<std::string>& written) {
  std::ostringstream e;
  e << "scene,part,lighting,approximation,vertices,relative_rms\n";
  for (const TranslucencyErrorRow& x : r.errors)
    e << x.scene << ',' << x.part << ',' << x.lighting << ',' << x.approximation << ','
      << x.vertices << ',' << fmt(x.relative_rms) << '\n';
  write_text_file((dir / "translucency_errors.csv").string(), e.str());
  written.push_back((dir / "translucency_errors.csv").string());
  std::ostringstream t;
  t << "vertices,seconds_hierarchical,seconds_reference,seconds_mesh_diffusion,"
       "hierarchical_vs_reference_relative_rms\n";
  for (const TranslucencyTimingRow& x : r.timing)
    t << x.vertices << ',' << fmt(x.seconds_hierarchical) << ','
      << (x.seconds_reference < 0 ? "" : fmt(x.seconds_reference)) << ','
      << fmt(x.seconds_mesh_diffusion) << ','
      << (x.reference_relative_rms < 0 ? "" : fmt(x.reference_relative_rms)) << '\n';
  write_text_file((dir / "translucency_timing.csv").string(), t.str());
  written.push_back((dir / "translucency_timing.csv").string());
}

void write_json(const std::filesystem::path& dir, const TranslucencyReportOptions& o,
                glm::dvec3 dominant, const TranslucencyReportResult& r,
                std::vector<std::string>& written) {
  nlohmann::ordered_json j;
  j["sh_convention"] =
      "real orthonormal SH, no Condon-Shortley phase, polar axis +z, k = l(l+1)+m, scene frame +Y "
      "up";
  j["preset"] = o.preset;
  j["order"] = o.order;
  j["samples"] = o.samples;
  j["seed"] = o.seed;
  j["environment"] = std::filesystem::path(o.environment_path).filename().string();
  j["dominant_direction"] = {dominant.x, dominant.y, dominant.z};
  for (const TranslucencyErrorRow& x : r.errors)
    j["errors"].push_back({{"scene", x.scene},
                           {"part", x.part},
                           {"lighting", x.lighting},
                           {"approximation", x.approximation},
                           {"vertices", x.vertices},
                           {"relative_rms", x.relative_rms}});
  for (const TranslucencyTimingRow& x : r.timing) j["timing_vertices"].push_back(x.vertices);
  write_text_file((dir / "translucency.json").string(), j.dump(2) + "\n");
  written.push_back((dir / "translucency.json").string());
}

void write_plot(const std::filesystem::path& dir, const std::string& name, const PlotSpec& spec,
                std::vector<std::string>& written) {
  const std::string svg = (dir / (name + ".svg")).string(), png = (dir / (name + ".png")).string();
  write_text_file(svg, render_svg(spec));
  written.push_back(svg);
  std::string why;
  if (convert_svg_to_png(svg, png, 1.5, &why)) written.push_back(png);
}

// Error per approximation (x = 1..4): markers only (the x axis is a list, not a quantity); one
// series per scene × lighting for the whole scene, and per translucent part under back light.
PlotSpec error_plot(const TranslucencyReportResult& r) {
  PlotSpec spec;
  spec.title = "Real-time approximations against the dipole bake";
  spec.x_label = "approximation: 1 lambert-rtotal, 2 normal-blur, 3 mesh-diffusion, 4 depth-map";
  spec.y_label = "relative RMS error of the exit radiance";
  spec.log_y = true;
  spec.legend = LegendCorner::OutsideRight;
  std::map<std::string, std::size_t> index;
  const Marker markers[] = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond,
                            Marker::Cross};
  for (const TranslucencyErrorRow& x : r.errors) {
    if (x.part != "all" && x.lighting != "back") continue;
    const std::string key = x.scene + (x.part == "all" ? "" : " " + x.part) + ", " + x.lighting;
    if (!index.count(key)) {
      index[key] = spec.series.size();
      PlotSeries s;
      s.label = key;
      s.color = kColors[spec.series.size() % 8];
      s.line = false;
      s.marker = markers[spec.series.size() % 5];
      s.marker_size = x.part == "all" ? 6.0 : 4.5;
      spec.series.push_back(s);
    }
    PlotSeries& s = spec.series[index[key]];
    int a = 1;
    for (bake::SubsurfaceApproximation k : bake::kAllApproximations) {
      if (x.approximation == bake::approximation_name(k)) break;
      ++a;
    }
    s.x.push_back(a);
    s.y.push_back(std::max(x.relative_rms, 1e-6));
  }
  return spec;
}

PlotSpec timing_plot(const TranslucencyReportResult& r) {
  PlotSpec spec;
  spec.title = "Subsurface bake time against vertex count (lone spheres)";
  spec.x_label = "vertices";
  spec.y_label = "seconds";
  spec.log_x = spec.log_y = true;
  spec.legend = LegendCorner::TopLeft;
  PlotSeries h, ref, md, nlogn, n2;
  h.label = "dipole, hierarchical";
  ref.label = "dipole, O(n^2) reference";
  md.label = "mesh-space diffusion";
  nlogn.label = "c n log n (through the largest hierarchical)";
  n2.label = "c n^2 (through the largest reference)";
  h.color = kColors[0];
  ref.color = kColors[1];
  md.color = kColors[2];
  nlogn.color = n2.color = "#999999";
  nlogn.dashed = n2.dashed = true;
  nlogn.marker = n2.marker = Marker::None;
  for (const TranslucencyTimingRow& x : r.timing) {
    h.x.push_back(double(x.vertices));
    h.y.push_back(x.seconds_hierarchical);
    md.x.push_back(double(x.vertices));
    md.y.push_back(x.seconds_mesh_diffusion);
    if (x.seconds_reference > 0) {
      ref.x.push_back(double(x.vertices));
      ref.y.push_back(x.seconds_reference);
    }
  }
  if (!h.x.empty()) {
    const double n = h.x.back(), c = h.y.back() / (n * std::log(n));
    for (double v : h.x) nlogn.x.push_back(v), nlogn.y.push_back(c * v * std::log(v));
  }
  if (!ref.x.empty()) {
    const double n = ref.x.back(), c = ref.y.back() / (n * n);
    for (double v : h.x) n2.x.push_back(v), n2.y.push_back(c * v * v);
  }
  spec.series = {h, ref, md, nlogn, n2};
  return spec;
}

void write_summary(const std::filesystem::path& dir, const TranslucencyReportOptions& o,
                   glm::dvec3 dominant, const TranslucencyReportResult& r,
                   std::vector<std::string>& written) {
  std::ostringstream s;
  s << "# Translucency: real-time approximations against the dipole bake\n\n"
    << "Preset `" << o.preset << "`, SH order " << o.order << ", " << o.samples
    << " samples per vertex, seed " << o.seed << "; environment `"
    << std::filesystem::path(o.environment_path).filename().string()
    << "`, its dominant direction (" << fmt(dominant.x, "%.3f") << ", " << fmt(dominant.y, "%.3f")
    << ", " << fmt(dominant.z, "%.3f")
    << ") turned to 20° above −Z (back light) or +Z (front light).\n"
    << "Relative RMS error of the exit radiance over the translucent vertices, against the dipole "
       "bake:\n\n| scene | part | light | lambert-rtotal | normal-blur | mesh-diffusion | "
       "depth-map "
       "|\n|---|---|---|---|---|---|---|\n";
  std::map<std::string, std::vector<const TranslucencyErrorRow*>> rows;
  std::vector<std::string> order;
  for (const TranslucencyErrorRow& x : r.errors) {
    const std::string key = x.scene + " | " + x.part + " | " + x.lighting;
    if (!rows.count(key)) order.push_back(key);
    rows[key].push_back(&x);
  }
  for (const std::string& key : order) {
    s << "| " << key;
    for (const TranslucencyErrorRow* x : rows[key])
      s << " | " << fmt(100 * x->relative_rms, "%.1f") << "%";
    s << " |\n";
  }
  s << "\n![errors](translucency_errors.svg)\n\nBake time against vertex count (lone marble "
       "spheres, r = 10 mm):\n\n| vertices | hierarchical s | reference s | mesh diffusion s | "
       "hierarchical vs reference |\n|---|---|---|---|---|\n";
  for (const TranslucencyTimingRow& x : r.timing)
    s << "| " << x.vertices << " | " << fmt(x.seconds_hierarchical, "%.3f") << " | "
      << (x.seconds_reference < 0 ? "—" : fmt(x.seconds_reference, "%.3f")) << " | "
      << fmt(x.seconds_mesh_diffusion, "%.3f") << " | "
      << (x.reference_relative_rms < 0 ? "—" : fmt(100 * x.reference_relative_rms, "%.2f") + "%")
      << " |\n";
  s << "\n![timing](translucency_timing.svg)\n";
  write_text_file((dir / "translucency_summary.md").string(), s.str());
  written.push_back((dir / "translucency_summary.md").string());
}

}  // namespace

void write_translucency_outputs(const TranslucencyReportOptions& o, glm::dvec3 dominant,
                                TranslucencyReportResult& r) {
  const std::filesystem::path dir(o.output_dir);
  std::filesystem::create_directories(dir);
  write_csvs(dir, r, r.files_written);
  write_json(dir, o, dominant, r, r.files_written);
  write_plot(dir, "translucency_errors", error_plot(r), r.files_written);
  write_plot(dir, "translucency_timing", timing_plot(r), r.files_written);
  write_summary(dir, o, dominant, r, r.files_written);
}

std::vector<std::string> translucency_report_file_names(const std::vector<std::string>& scenes) {
  std::vector<std::string> out{"translucency_errors.csv", "translucency_errors.png",
                               "translucency_errors.svg", "translucency_timing.csv",
                               "translucency_timing.svg", "translucency_timing.png",
                               "translucency.json",       "translucency_summary.md"};
  for (const std::string& s : scenes) {
    out.push_back(translucency_transfer_name(s, "dipole"));
    for (bake::SubsurfaceApproximation a : bake::kAllApproximations)
      out.push_back(translucency_transfer_name(s, bake::approximation_name(a)));
  }
  return out;
}

std::string translucency_transfer_name(const std::string& scene_path, const std::string& kind) {
  return std::filesystem::path(scene_path).stem().string() + "." + kind + ".prt";
}

}  // namespace prt::report
