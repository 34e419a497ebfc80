// report/src/radiosity_report_outputs.cpp — the files of `prt report --radiosity`: the results
// table (CSV, JSON), the error-against-seconds Pareto plot and the summary.
#include "radiosity_report_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "report/plot_svg.h"

namespace prt::report {
namespace {

std::string path_in(const RadiosityReportOptions& o, const std::string& name) {
  return (std::filesystem::path(o.output_dir) / name).string();
}

void write(const RadiosityReportOptions& o, RadiosityReportResult& r, const std::string& name,
           const std::string& text) {
  write_text_file(path_in(o, name), text);
  r.files_written.push_back(path_in(o, name));
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

std::string pct(double x) {
  return fixed(100 * x, 2) + "%";
}

std::string rgb_text(const glm::dvec3& c, int digits) {
  return fixed(c.x, digits) + ", " + fixed(c.y, digits) + ", " + fixed(c.z, digits);
}

void write_csv(const RadiosityReportOptions& o, RadiosityReportResult& r) {
  std::ostringstream csv;
  csv << "max_edge,patches,method,solver,form_factor_seconds,solve_seconds,total_seconds,"
         "resolve_seconds,iterations,converged,relative_rms,relative_rms_corrected,pareto\n";
  csv.precision(6);
  for (const RadiosityReportRow& w : r.rows)
    csv << w.max_edge << ',' << w.patches << ',' << method_name(w.method) << ','
        << solver_name(w.solver) << ',' << w.form_factor_seconds << ',' << w.solve_seconds << ','
        << w.total_seconds << ','
        << (w.resolve_seconds >= 0 ? std::to_string(w.resolve_seconds) : "") << ',' << w.iterations
        << ',' << (w.converged ? 1 : 0) << ',' << w.relative_rms << ',' << w.relative_rms_corrected
        << ',' << (w.on_pareto_front ? 1 : 0) << '\n';
  write(o, r, "radiosity_results.csv", csv.str());
}

void write_patches_csv(const RadiosityReportOptions& o, RadiosityReportResult& r) {
  std::ostringstream csv;
  csv << "patch,x,y,z,nx,ny,nz,area,truth_r,truth_g,truth_b,se_r,se_g,se_b,radiosity_r,"
         "radiosity_g,radiosity_b\n";
  csv.precision(7);
  for (const RadiosityPatchRow& p : r.patches) {
    csv << p.patch;
    for (const glm::dvec3* v : {&p.centroid, &p.normal})
      csv << ',' << v->x << ',' << v->y << ',' << v->z;
    csv << ',' << p.area;
    for (const glm::dvec3* v : {&p.truth, &p.truth_se, &p.radiosity})
      csv << ',' << v->x << ',' << v->y << ',' << v->z;
    csv << '\n';
  }
  write(o, r, "radiosity_patches.csv", csv.str());
}

void write_json(const RadiosityReportOptions& o, RadiosityReportResult& r) {
  nlohmann::json j;
  j["scene"] = o.scene_path;
  j["tolerance"] = o.tolerance;
  j["rays_per_patch"] = o.rays_per_patch;
  j["hemicube_resolution"] = o.hemicube_resolution;
  j["resolve_emission_scale"] = {kResolveScale.x, kResolveScale.y, kResolveScale.z};
  j["error"] =
      "area-weighted relative RMS (RGB norm) over the ground truth's non-emitting patches; "
      "corrected = sqrt(max(0, e^2 - s^2)), s the ground truth's relative RMS standard error";
  for (const RadiosityGroundTruthLevel& g : r.ground_truth)
    j["ground_truth"].push_back({{"max_edge", g.max_edge},
                                 {"patches", g.patches},
                                 {"evaluated_patches", g.evaluated},
                                 {"samples_per_patch", g.samples},
                                 {"relative_se", g.relative_se},
                                 {"seconds", g.seconds}});
  for (const RadiosityReportRow& w : r.rows)
    j["rows"].push_back(
        {{"max_edge", w.max_edge},
         {"patches", w.patches},
         {"method", method_name(w.method)},
         {"solver", solver_name(w.solver)},
         {"form_factor_seconds", w.form_factor_seconds},
         {"solve_seconds", w.solve_seconds},
         {"total_seconds", w.total_seconds},
         {"resolve_seconds",
          w.resolve_seconds >= 0 ? nlohmann::json(w.resolve_seconds) : nlohmann::json()},
         {"iterations", w.iterations},
         {"converged", w.converged},
         {"relative_rms", w.relative_rms},
         {"relative_rms_corrected", w.relative_rms_corrected},
         {"pareto", w.on_pareto_front}});
  for (const RadiositySurface& s : r.surfaces)
    j["surfaces"].push_back({{"primitive", s.primitive},
                             {"normal", {s.normal.x, s.normal.y, s.normal.z}},
                             {"area", s.area},
                             {"truth", {s.truth.x, s.truth.y, s.truth.z}},
                             {"truth_se", {s.truth_se.x, s.truth_se.y, s.truth_se.z}},
                             {"radiosity", {s.radiosity.x, s.radiosity.y, s.radiosity.z}},
                             {"escape_fraction", s.escape}});
  j["surfaces_max_edge"] = r.surfaces_max_edge;
  j["surface_samples_per_triangle"] = r.surface_samples;
  j["seconds"] = r.seconds;
  write(o, r, "radiosity_results.json", j.dump(2) + "\n");
}

const char* color_of(radiosity::FormFactorMethod m) {
  switch (m) {
    case radiosity::FormFactorMethod::Analytic:
      return "#1f77b4";
    case radiosity::FormFactorMethod::Rays:
      return "#ff7f0e";
    default:
      return "#2ca02c";
  }
}

Marker marker_of(radiosity::SolverKind s) {
  switch (s) {
    case radiosity::SolverKind::GaussSeidel:
      return Marker::Circle;
    case radiosity::SolverKind::Jacobi:
      return Marker::Square;
    default:
      return Marker::Triangle;
  }
}

// One series per (method, solver) through its patch counts, and the Pareto front.
std::string pareto_svg(const RadiosityReportOptions& o, const RadiosityReportResult& r) {
  PlotSpec spec;
  spec.title = "Radiosity: error against cost (" +
               std::filesystem::path(o.scene_path).filename().string() + ")";
  spec.x_label = "total seconds (form factors + solve)";
  spec.y_label = "relative RMS error vs path-traced patch averages";
  spec.log_x = spec.log_y = true;
  spec.y_as_percent = true;
  spec.legend = LegendCorner::OutsideRight;
  spec.reference_lines = {{0.02, "2%"}};
  for (radiosity::FormFactorMethod m : o.methods)
    for (radiosity::SolverKind k : o.solvers) {
      PlotSeries s;
      s.label = method_name(m) + " + " + solver_name(k);
      s.color = color_of(m);
      s.marker = marker_of(k);
      s.dashed = k == radiosity::SolverKind::Jacobi;
      s.line_width = 1.5;
      for (const RadiosityReportRow& w : r.rows)
        if (w.method == m && w.solver == k) {
          s.x.push_back(w.total_seconds);
          s.y.push_back(w.relative_rms);
          s.point_labels.push_back(
              k == radiosity::SolverKind::GaussSeidel ? std::to_string(w.patches) : std::string());
        }
      spec.series.push_back(s);
    }
  PlotSeries front;
  front.label = "Pareto front";
  front.color = "#000000";
  front.marker = Marker::None;
  front.dashed = true;
  front.line_width = 1.0;
  std::vector<std::pair<double, double>> pts;
  for (const RadiosityReportRow& w : r.rows)
    if (w.on_pareto_front) pts.emplace_back(w.total_seconds, w.relative_rms);
  std::sort(pts.begin(), pts.end());
  for (const auto& [x, y] : pts) front.x.push_back(x), front.y.push_back(y);
  spec.series.push_back(front);
  return render_svg(spec);
}

void write_summary(const RadiosityReportOptions& o, RadiosityReportResult& r,
                   const std::string& png_note);

}  // namespace

void mark_radiosity_pareto_front(RadiosityReportResult& result) {
  for (RadiosityReportRow& a : result.rows) {
    a.on_pareto_front = true;
    for (const RadiosityReportRow& b : result.rows)
      if (&a != &b && b.total_seconds <= a.total_seconds && b.relative_rms <= a.relative_rms &&
          (b.total_seconds < a.total_seconds || b.relative_rms < a.relative_rms))
        a.on_pareto_front = false;
  }
}

void write_radiosity_outputs(const RadiosityReportOptions& o, RadiosityReportResult& r) {
  write_csv(o, r);
  write_patches_csv(o, r);
  write_json(o, r);
  write(o, r, "radiosity_pareto.svg", pareto_svg(o, r));
  std::string why;
  if (convert_svg_to_png(path_in(o, "radiosity_pareto.svg"), path_in(o, "radiosity_pareto.png"),
                         1.5, &why))
    r.files_written.push_back(path_in(o, "radiosity_pareto.png"));
  write_summary(o, r, why);
}

namespace {

void summary_ground_truth(std::ostringstream& md, const RadiosityReportResult& r) {
  md << "## Ground truth\n\nPath-traced patch averages (report/emitter_ground_truth.h: next-event "
        "estimation on the emitters by power, MIS with cosine sampling, Russian roulette with a "
        "256-bounce cap) on a systematic sample of the non-emitting patches of each patch count. "
        "Its noise adds to the measured error in quadrature; `corrected` removes it.\n\n"
        "| max edge | patches | evaluated | paths per patch | relative SE | seconds |\n"
        "|---|---|---|---|---|---|\n";
  for (const RadiosityGroundTruthLevel& g : r.ground_truth)
    md << "| " << g.max_edge << " | " << g.patches << " | " << g.evaluated << " | " << g.samples
       << " | " << pct(g.relative_se) << " | " << fixed(g.seconds, 1) << " |\n";
}

void summary_rows(std::ostringstream& md, const RadiosityReportResult& r) {
  md << "\n## Solutions\n\n| max edge | patches | form factors | solver | FF s | solve s | "
        "total s | re-solve s | steps | error | corrected | Pareto |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const RadiosityReportRow& w : r.rows)
    md << "| " << w.max_edge << " | " << w.patches << " | " << method_name(w.method) << " | "
       << solver_name(w.solver) << " | " << fixed(w.form_factor_seconds, 2) << " | "
       << fixed(w.solve_seconds, 2) << " | " << fixed(w.total_seconds, 2) << " | "
       << (w.resolve_seconds >= 0 ? fixed(w.resolve_seconds, 3) : "—") << " | " << w.iterations
       << (w.converged ? "" : " (not converged)") << " | " << pct(w.relative_rms) << " | "
       << pct(w.relative_rms_corrected) << " | " << (w.on_pareto_front ? "yes" : "") << " |\n";
  const auto best = std::min_element(
      r.rows.begin(), r.rows.end(),
      [](const auto& a, const auto& b) { return a.relative_rms < b.relative_rms; });
  if (best != r.rows.end())
    md << "\nMost accurate: " << method_name(best->method) << " + " << solver_name(best->solver)
       << " at " << best->patches << " patches (max edge " << best->max_edge
       << "): " << pct(best->relative_rms) << " (" << pct(best->relative_rms_corrected)
       << " without the ground truth's noise) in " << fixed(best->total_seconds, 1) << " s.\n";
  const RadiosityReportRow* cheapest = nullptr;
  for (const RadiosityReportRow& w : r.rows)
    if (w.relative_rms <= 0.02 && (!cheapest || w.total_seconds < cheapest->total_seconds))
      cheapest = &w;
  if (cheapest)
    md << "Cheapest within 2%: " << method_name(cheapest->method) << " + "
       << solver_name(cheapest->solver) << " at " << cheapest->patches << " patches, "
       << fixed(cheapest->total_seconds, 2) << " s.\n";
  else
    md << "No setting is within 2% of the ground truth with its noise included.\n";
  const RadiosityReportRow* corrected = nullptr;
  for (const RadiosityReportRow& w : r.rows)
    if (w.relative_rms_corrected <= 0.02 &&
        (!corrected || w.total_seconds < corrected->total_seconds))
      corrected = &w;
  if (corrected)
    md << "Cheapest within 2% without the ground truth's noise: " << method_name(corrected->method)
       << " + " << solver_name(corrected->solver) << " at " << corrected->patches << " patches, "
       << fixed(corrected->total_seconds, 2) << " s.\n";
  md << "\nRe-solve: the emitters' emission scaled by (" << kResolveScale.x << ", "
     << kResolveScale.y << ", " << kResolveScale.z
     << ") per channel and the matrix solver run again on the same form factors; compare its "
        "seconds with the total (progressive keeps its rows inside the solver: no re-solve).\n";
}

void summary_surfaces(std::ostringstream& md, const RadiosityReportResult& r) {
  if (r.surfaces.empty()) return;
  md << "\n## Surfaces\n\nEach surface (the scene's triangles grouped by primitive and plane) "
        "integrated whole by the ground truth ("
     << r.surface_samples
     << " paths per triangle) against the area-weighted mean of its patches in the most "
        "accurate solution at max edge "
     << r.surfaces_max_edge
     << "; escape = the fraction of cosine rays from it that leave the scene.\n\n"
        "| surface | normal | area | ground truth (RGB) | SE (RGB) | radiosity (RGB) | "
        "difference | escape |\n|---|---|---|---|---|---|---|---|\n";
  for (const RadiositySurface& s : r.surfaces) {
    const double t = glm::length(s.truth);
    const std::string diff = t > 0 ? pct(glm::length(s.radiosity - s.truth) / t) : "—";
    md << "| " << s.primitive << " | " << rgb_text(s.normal, 2) << " | " << fixed(s.area, 0)
       << " | " << rgb_text(s.truth, 4) << " | " << rgb_text(s.truth_se, 4) << " | "
       << rgb_text(s.radiosity, 4) << " | " << diff << " | " << pct(s.escape) << " |\n";
  }
}

void write_summary(const RadiosityReportOptions& o, RadiosityReportResult& r,
                   const std::string& png_note) {
  std::ostringstream md;
  md << "# Radiosity against a path-traced ground truth\n\nScene: `" << o.scene_path
     << "`. Tolerance " << o.tolerance << " (relative unshot power), rays " << o.rays_per_patch
     << " per patch, hemicube " << o.hemicube_resolution << ". Total " << fixed(r.seconds, 1)
     << " s.\n\n![error against cost](radiosity_pareto.svg)\n\n";
  summary_ground_truth(md, r);
  summary_rows(md, r);
  summary_surfaces(md, r);
  if (!png_note.empty()) md << "\n- PNG not written: " << png_note << "\n";
  write(o, r, "radiosity_summary.md", md.str());
}

}  // namespace

}  // namespace prt::report
