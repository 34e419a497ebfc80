// report/src/sun_study_report.cpp — run_sun_study(): the sweep over materials and orders, and
// its CSV, SVG/PNG and summary.md outputs (report/sun_study.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "prt/glossy/brdf_projection.h"
#include "report/plot_svg.h"
#include "report/sun_study.h"

namespace prt::report {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
const char* const kPalette[] = {"#7f7f7f", "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};

struct MaterialOutcome {
  SunStudyMaterial material;
  int runtime_order = 0;
  std::vector<OrderError> sphere, normal;      // normal: isotropic only
  std::vector<std::vector<OrderError>> views;  // the sphere's errors per view
  DecayFit sphere_fit, normal_fit_low;         // normal_fit_low: fitted on orders ≤ runtime_order
  double seconds = 0;
};

// Budgets: (label, bytes per value, bytes).
struct Budget {
  std::string label;
  int bytes_per_value;
  double bytes;
  int order = 0;
};

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

double rms_at(const std::vector<OrderError>& e, int order) {
  for (const OrderError& x : e)
    if (x.order == order) return x.rms;
  return -1;
}

// "n (direct)" or "≈ n (fit)" or "> limit".
std::string needed_text(const std::vector<OrderError>& e, const DecayFit& fit, double target) {
  const int direct = direct_needed_order(e, target);
  if (direct > 0) return std::to_string(direct);
  const int predicted = fit.order_for(target);
  if (predicted > 0) return fmt("≈%.0f (fit)", predicted);
  return "not predictable";
}

MaterialOutcome study_material(const SunStudyMaterial& m, const SunStudyOptions& o,
                               const SunSphereSetup& setup) {
  const auto t0 = std::chrono::steady_clock::now();
  MaterialOutcome r;
  r.material = m;
  const bool iso = m.material.isotropic();
  r.runtime_order = iso ? (o.quick ? 12 : kMaxBrdfProjectionOrder) : (o.quick ? 6 : 12);
  r.sphere =
      sphere_errors(m.material, setup, r.runtime_order, sun_study_projection_options(), &r.views);
  r.sphere_fit = fit_decay(r.sphere);
  if (iso) {
    Result<std::shared_ptr<const brdf::Brdf>> f = brdf::make_brdf(m.material);
    if (!f) throw std::runtime_error("sun study: " + f.status().message());
    r.normal = normal_incidence_errors(**f, setup.half_angle, o.quick ? 256 : 512);
    std::vector<OrderError> low(r.normal.begin(), r.normal.begin() + r.runtime_order);
    r.normal_fit_low = fit_decay(low);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void write_csvs(const std::filesystem::path& dir, const std::vector<MaterialOutcome>& all,
                const SunSphereSetup& setup, const SunStudyOptions& o,
                std::vector<std::string>* written) {
  std::ostringstream e;
  e << "material,description,path,order,rel_rms,rel_peak\n";
  for (const MaterialOutcome& r : all) {
    std::ostringstream quoted;
    quoted << '"' << brdf::describe(r.material.material) << '"';
    const std::string d = quoted.str();
    for (const OrderError& x : r.sphere)
      e << r.material.name << "," << d << ",sphere," << x.order << "," << x.rms << "," << x.peak
        << "\n";
    for (const OrderError& x : r.normal)
      e << r.material.name << "," << d << ",normal_incidence," << x.order << "," << x.rms << ","
        << x.peak << "\n";
    for (std::size_t k = 0; k < r.views.size(); ++k)
      for (const OrderError& x : r.views[k])
        e << r.material.name << "," << d << ",sphere_" << setup.view_names[k] << "," << x.order
          << "," << x.rms << "," << x.peak << "\n";
  }
  write_text_file((dir / "sun_errors.csv").string(), e.str());
  written->push_back((dir / "sun_errors.csv").string());
  std::ostringstream m;
  m << "order,bytes_per_vertex_f32,bytes_per_vertex_f16,gib_f32,gib_f16,vertices\n";
  for (int n = 1; n <= 32; ++n)
    m << n << "," << transfer_matrix_bytes(n, 4) << "," << transfer_matrix_bytes(n, 2) << ","
      << o.vertices * transfer_matrix_bytes(n, 4) / kGiB << ","
      << o.vertices * transfer_matrix_bytes(n, 2) / kGiB << "," << o.vertices << "\n";
  write_text_file((dir / "sun_memory.csv").string(), m.str());
  written->push_back((dir / "sun_memory.csv").string());
}

// Vertical dashed line at each budget's largest order, as a series.
void add_budget_lines(PlotSpec* spec, const std::vector<Budget>& budgets, double y0, double y1) {
  const char* colours[] = {"#444444", "#999999"};
  int k = 0;
  for (const Budget& b : budgets) {
    PlotSeries s;
    s.label = b.label + ": n ≤ " + std::to_string(b.order);
    s.x = {double(b.order), double(b.order)};
    s.y = {y0, y1};
    s.color = colours[(k++) % 2];
    s.dashed = true;
    s.marker = Marker::None;
    s.line_width = 1.5;
    spec->series.push_back(s);
  }
}

void write_plot(const std::filesystem::path& dir, const std::string& stem, PlotSpec spec,
                std::vector<std::string>* written) {
  const std::string svg = (dir / (stem + ".svg")).string();
  write_text_file(svg, render_svg(spec));
  written->push_back(svg);
  std::string why;
  const std::string png = (dir / (stem + ".png")).string();
  if (convert_svg_to_png(svg, png, 1.5, &why)) written->push_back(png);
}

void write_plots(const std::filesystem::path& dir, const std::vector<MaterialOutcome>& all,
                 const std::vector<Budget>& budgets, const SunStudyOptions& o,
                 std::vector<std::string>* written) {
  PlotSpec a;
  a.title = "Sun (0.53°) + sky: relative RMS error of glossy exit radiance, prt's runtime path";
  a.x_label = "SH order n (lighting n² coefficients; transfer matrix n² × n²)";
  a.y_label = "relative RMS error";
  a.log_y = true;
  a.y_as_percent = true;
  a.legend = LegendCorner::OutsideRight;
  for (double t : o.targets) a.reference_lines.push_back({t, fmt("%g%%", 100 * t)});
  PlotSpec b = a;
  b.title = "Normal incidence (view along the normal), sun only: the exact zonal series";
  b.x_label = "SH order n";
  b.log_x = true;
  std::size_t k = 0;
  for (const MaterialOutcome& r : all) {
    PlotSeries s;
    s.label = r.material.name;
    s.color = kPalette[k++ % (sizeof kPalette / sizeof *kPalette)];
    s.marker_size = 3;
    for (const OrderError& x : r.sphere) s.x.push_back(x.order), s.y.push_back(x.rms);
    a.series.push_back(s);
    if (r.normal.empty()) continue;
    s.x.clear(), s.y.clear();
    s.marker = Marker::None;
    for (const OrderError& x : r.normal) s.x.push_back(x.order), s.y.push_back(x.rms);
    b.series.push_back(s);
  }
  auto smallest = [](const PlotSpec& spec) {
    double lo = 1.0;
    for (const PlotSeries& s : spec.series)
      for (double y : s.y)
        if (y > 0) lo = std::min(lo, y);
    return lo;
  };
  add_budget_lines(&a, budgets, smallest(a), 1.0);
  add_budget_lines(&b, budgets, smallest(b), 1.0);
  write_plot(dir, "sun_error_vs_order", a, written);
  write_plot(dir, "sun_normal_incidence", b, written);
}

void write_summary(const std::filesystem::path& dir, const std::vector<MaterialOutcome>& all,
                   const std::vector<Budget>& budgets, const SunStudyOptions& o,
                   const SunSphereSetup& setup, std::vector<std::string>* written) {
  std::ostringstream s;
  s << "# Where SH fails: a sun on glossy surfaces\n\n";
  s << "Sun: a disc of " << kSunAngularDiameterDegrees << "° (solid angle "
    << fmt("%.3g", disc_solid_angle(setup.half_angle)) << " sr), irradiance 1 on a plane facing "
    << "it; a uniform sky of irradiance " << o.sky_fraction << " on a plane. Sphere: the sun at "
    << setup.suns.size() << " Fibonacci directions over the sphere of the surface's local frame "
    << "(every orientation of the surface), seen from " << setup.views.size()
    << " views (θo 0°, 30°, 60°, 80°; φo 0° and 90°). Runtime path: BrdfProjection (kAuto; "
    << "isotropic table at 5° steps with the views on its nodes, 32 nodes per panel) × the "
    << "lighting's SH in the local frame. Normal incidence: view along the normal, sun only, the "
    << "exact zonal series (isotropic materials). Relative RMS over the configurations and RGB. "
    << "Mode: " << (o.quick ? "quick" : "full") << ".\n\n";
  s << "## Memory of a per-vertex n² × n² transfer matrix, " << o.vertices << " vertices\n\n";
  s << "| budget | largest order |\n|---|---|\n";
  for (const Budget& b : budgets) s << "| " << b.label << " | " << b.order << " |\n";
  s << "\n## Order needed and error at the orders that fit\n\n";
  s << "Needed order: direct (the smallest order from which every computed order is within the "
       "target) or, beyond the computed range, extrapolated by a fit of the error's decay over "
       "the second half of the computed orders.\n\n";
  s << "| material | sphere: orders computed |";
  for (double t : o.targets) s << " sphere: n for " << 100 * t << "% |";
  for (double t : o.targets)
    s << " normal incidence: n for " << 100 * t << "% (fit from n ≤ runtime) |";
  for (const Budget& b : budgets) s << " sphere error at n = " << b.order << " |";
  s << " time (s) |\n|---|---|";
  for (std::size_t i = 0; i < 2 * o.targets.size() + budgets.size() + 1; ++i) s << "---|";
  s << "\n";
  for (const MaterialOutcome& r : all) {
    s << "| " << r.material.name << " | 1.." << r.runtime_order << " |";
    for (double t : o.targets) s << " " << needed_text(r.sphere, r.sphere_fit, t) << " |";
    for (double t : o.targets) {
      if (r.normal.empty()) {
        s << " – |";
        continue;
      }
      const int d = direct_needed_order(r.normal, t), f = r.normal_fit_low.order_for(t);
      s << " " << (d > 0 ? std::to_string(d) : fmt(">%.0f", r.normal.back().order)) << " ("
        << (f > 0 ? std::to_string(f) : "–") << ") |";
    }
    for (const Budget& b : budgets) {
      const double e = rms_at(r.sphere, b.order);
      s << " " << (e >= 0 ? fmt("%.3g%%", 100 * e) : "not computed") << " |";
    }
    s << " " << fmt("%.1f", r.seconds) << " |\n";
  }
  s << "\n## Sphere error per view at n = 10 and at the largest computed order\n\n| material |";
  for (const std::string& v : setup.view_names) s << " " << v << " |";
  s << "\n|---|";
  for (std::size_t i = 0; i < setup.view_names.size(); ++i) s << "---|";
  s << "\n";
  for (const MaterialOutcome& r : all) {
    s << "| " << r.material.name << " |";
    for (const std::vector<OrderError>& v : r.views) {
      const double e10 = rms_at(v, 10);
      s << " " << (e10 >= 0 ? fmt("%.3g%%", 100 * e10) : std::string("–")) << " / "
        << fmt("%.3g%%", 100 * v.back().rms) << " (n " << v.back().order << ") |";
    }
    s << "\n";
  }
  s << "\nMaterials:\n\n";
  for (const MaterialOutcome& r : all)
    s << "- " << r.material.name << ": " << brdf::describe(r.material.material) << "\n";
  s << "\nFiles: sun_errors.csv (every order), sun_memory.csv, sun_error_vs_order.svg, "
       "sun_normal_incidence.svg.\n";
  write_text_file((dir / "summary.md").string(), s.str());
  written->push_back((dir / "summary.md").string());
}

}  // namespace

std::vector<std::string> sun_study_file_names() {
  return {"sun_errors.csv",          "sun_memory.csv",         "summary.md",
          "sun_error_vs_order.svg",  "sun_error_vs_order.png", "sun_normal_incidence.svg",
          "sun_normal_incidence.png"};
}

SunStudyResult run_sun_study(const SunStudyOptions& o) {
  const std::vector<SunStudyMaterial> materials = sun_study_materials(o.ggx_alphas);
  const SunSphereSetup setup = default_sun_setup(o.sky_fraction, o.quick ? 4000 : 20000);
  std::vector<Budget> budgets = {
      {fmt("%g GiB/object f32", o.object_budget_gib), 4, o.object_budget_gib * kGiB},
      {fmt("%g GiB/object f16", o.object_budget_gib), 2, o.object_budget_gib * kGiB},
      {fmt("%g GiB f32", o.machine_budget_gib), 4, o.machine_budget_gib * kGiB},
      {fmt("%g GiB f16", o.machine_budget_gib), 2, o.machine_budget_gib * kGiB}};
  for (Budget& b : budgets) b.order = largest_fitting_order(o.vertices, b.bytes_per_value, b.bytes);
  std::vector<MaterialOutcome> all;
  for (const SunStudyMaterial& m : materials) {
    all.push_back(study_material(m, o, setup));
    if (o.log)
      o.log(m.name + ": order " + std::to_string(all.back().runtime_order) + " rms " +
            fmt("%.3g", all.back().sphere.back().rms) + " (" + fmt("%.1f", all.back().seconds) +
            " s)");
  }
  const std::filesystem::path dir(o.output_dir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(o.output_dir + ": cannot create the folder: " + ec.message());
  SunStudyResult result;
  write_csvs(dir, all, setup, o, &result.files_written);
  write_plots(dir, all, budgets, o, &result.files_written);
  write_summary(dir, all, budgets, o, setup, &result.files_written);
  return result;
}

}  // namespace prt::report
