// report/src/radiosity_report.cpp — the sweep of `prt report --radiosity`
// (report/radiosity_report.h); the files it writes: radiosity_report_outputs.cpp.
#include "report/radiosity_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <tuple>

#include "radiosity/materials.h"
#include "radiosity/patches.h"
#include "radiosity_report_outputs.h"
#include "report/emitter_ground_truth.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace prt::report {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Log {
  const RadiosityReportOptions& o;
  Clock::time_point start;
  void operator()(const std::string& line) const {
    if (!o.log) return;
    char stamp[48];
    std::snprintf(stamp, sizeof stamp, "[report %6.1fs] ", since(start));
    o.log(stamp + line);
  }
};

bool emits(const radiosity::Patch& p) {
  return p.emission.x + p.emission.y + p.emission.z > 0;
}

// The scene with the command line's emission and albedo, checked; throws when nothing emits.
scene::Scene load_lit_scene(const RadiosityReportOptions& o) {
  scene::Scene s = scene::load_scene(o.scene_path);
  scene::apply_emission(s, o.emission);
  scene::apply_albedo(s, o.albedo);
  radiosity::check_materials(s);
  bool any = false;
  for (const scene::ScenePrimitive& p : s.primitives)
    any = any || (p.triangle_count > 0 && p.emission != glm::vec3(0.f));
  if (!any)
    throw std::runtime_error(o.scene_path +
                             ": nothing emits light (give --emission MATERIAL=r,g,b, a glTF "
                             "emissiveFactor or an OBJ Ke)");
  return s;
}

// The systematic sample of K non-emitting patches (see header).
std::vector<uint32_t> evaluation_patches(const std::vector<radiosity::Patch>& patches, int k) {
  std::vector<uint32_t> candidates;
  for (std::size_t t = 0; t < patches.size(); ++t)
    if (!emits(patches[t]) && patches[t].area > 0) candidates.push_back(static_cast<uint32_t>(t));
  if (static_cast<std::size_t>(k) >= candidates.size()) return candidates;
  std::vector<uint32_t> chosen;
  const double n = static_cast<double>(candidates.size());
  for (int i = 0; i < k; ++i)
    chosen.push_back(candidates[static_cast<std::size_t>((i + 0.5) * n / k)]);
  return chosen;
}

// Area-weighted relative RMS over `subset` (RGB norm).
double relative_rms(const std::vector<radiosity::Patch>& patches,
                    const std::vector<uint32_t>& subset, const std::vector<glm::dvec3>& radiance,
                    const std::vector<glm::dvec3>& truth) {
  double e2 = 0, t2 = 0;
  for (uint32_t p : subset) {
    const glm::dvec3 d = radiance[p] - truth[p];
    e2 += patches[p].area * glm::dot(d, d);
    t2 += patches[p].area * glm::dot(truth[p], truth[p]);
  }
  return t2 > 0 ? std::sqrt(e2 / t2) : 0.0;
}

struct Level {  // one patch count: its scene, patches and ground truth
  scene::Scene scene;
  std::vector<radiosity::Patch> patches;
  std::vector<uint32_t> subset;
  EmitterGroundTruthResult truth;
  double max_edge = 0;
};

struct Sweep {
  const RadiosityReportOptions& o;
  const Log& log;
  int patches_k, samples;
  RadiosityReportResult& result;
  std::vector<glm::dvec3> best_finest;  // the most accurate radiance of the finest level
  double best_finest_error = INFINITY;

  void add_row(const Level& lv, RadiosityReportRow row, const radiosity::Solution& sol,
               bool finest) {
    row.max_edge = lv.max_edge;
    row.patches = lv.patches.size();
    row.total_seconds = row.form_factor_seconds + row.solve_seconds;
    row.iterations = sol.iterations;
    row.converged = sol.converged;
    row.relative_rms = relative_rms(lv.patches, lv.subset, sol.display_radiance, lv.truth.radiance);
    const double s = lv.truth.relative_rms_se;
    row.relative_rms_corrected =
        std::sqrt(std::max(0.0, row.relative_rms * row.relative_rms - s * s));
    char resolve[48] = "";  // progressive rows have no re-solve (resolve_seconds < 0)
    if (row.resolve_seconds >= 0)
      std::snprintf(resolve, sizeof resolve, " (re-solve %.2f s)", row.resolve_seconds);
    char line[256];
    std::snprintf(line, sizeof line, "%s + %s, %zu patches: %.2f s%s, error %.2f%%",
                  method_name(row.method).c_str(), solver_name(row.solver).c_str(), row.patches,
                  row.total_seconds, resolve, 100 * row.relative_rms);
    log(line);
    if (finest && row.relative_rms < best_finest_error)
      best_finest_error = row.relative_rms, best_finest = sol.display_radiance;
    result.rows.push_back(row);
  }

  // The matrix solvers on one form-factor matrix, each timed, then re-solved with new emission.
  void matrix_solvers(const Level& lv, const radiosity::FormFactorOptions& fo, bool finest) {
    const scene::RayCaster caster(lv.scene);
    Clock::time_point t = Clock::now();
    const radiosity::FormFactorMatrix f = radiosity::compute_form_factors(lv.patches, caster, fo);
    const double ff_seconds = since(t);
    std::vector<radiosity::Patch> relit = lv.patches;
    for (radiosity::Patch& p : relit) p.emission *= kResolveScale;
    for (radiosity::SolverKind kind : o.solvers) {
      if (kind == radiosity::SolverKind::Progressive) continue;
      radiosity::SolveOptions so;
      so.solver = kind, so.tolerance = o.tolerance;
      RadiosityReportRow row;
      row.method = fo.method, row.solver = kind, row.form_factor_seconds = ff_seconds;
      t = Clock::now();
      const radiosity::Solution sol = radiosity::solve_matrix(lv.patches, f, so);
      row.solve_seconds = since(t);
      t = Clock::now();
      const radiosity::Solution again = radiosity::solve_matrix(relit, f, so);
      row.resolve_seconds = since(t);
      add_row(lv, row, sol, finest);
    }
  }

  void progressive(const Level& lv, const radiosity::FormFactorOptions& fo, bool finest) {
    const scene::RayCaster caster(lv.scene);
    radiosity::SolveOptions so;
    so.solver = radiosity::SolverKind::Progressive, so.tolerance = o.tolerance;
    RadiosityReportRow row;
    row.method = fo.method, row.solver = so.solver;
    const Clock::time_point t = Clock::now();
    const radiosity::Solution sol = radiosity::solve_progressive(lv.patches, caster, fo, so);
    row.solve_seconds = since(t);
    add_row(lv, row, sol, finest);
  }

  void level(const scene::Scene& base, double max_edge, bool finest) {
    Level lv;
    lv.max_edge = max_edge;
    lv.scene = scene::subdivide_to_edge_length(base, max_edge);
    if (lv.scene.triangles.size() > radiosity::kMaxPatches)
      throw std::invalid_argument("--max-edges " + std::to_string(max_edge) + ": " +
                                  std::to_string(lv.scene.triangles.size()) + " patches (at most " +
                                  std::to_string(radiosity::kMaxPatches) + ")");
    lv.patches = radiosity::make_patches(lv.scene);
    lv.subset = evaluation_patches(lv.patches, patches_k);
    EmitterGroundTruthOptions go;
    go.samples = samples, go.seed = o.seed, go.patches = lv.subset;
    lv.truth = compute_emitter_ground_truth(lv.scene, go);
    char line[200];
    std::snprintf(line, sizeof line,
                  "max edge %g: %zu patches; ground truth on %zu of them, %d paths each: "
                  "relative SE %.2f%% in %.1f s",
                  max_edge, lv.patches.size(), lv.subset.size(), samples,
                  100 * lv.truth.relative_rms_se, lv.truth.seconds);
    log(line);
    result.ground_truth.push_back({max_edge, lv.patches.size(), lv.subset.size(), samples,
                                   lv.truth.relative_rms_se, lv.truth.seconds});
    for (radiosity::FormFactorMethod m : o.methods) {
      radiosity::FormFactorOptions fo;
      fo.method = m, fo.rays_per_patch = o.rays_per_patch, fo.seed = o.seed;
      fo.hemicube_resolution = o.hemicube_resolution;
      // As `prt radiosity` by default: Sobol' rows, emitters' rows by reciprocity.
      fo.emitter_rows = radiosity::EmitterRows::Reciprocal;
      const bool matrix = std::any_of(o.solvers.begin(), o.solvers.end(), [](auto k) {
        return k != radiosity::SolverKind::Progressive;
      });
      if (matrix) matrix_solvers(lv, fo, finest);
      if (std::count(o.solvers.begin(), o.solvers.end(), radiosity::SolverKind::Progressive))
        progressive(lv, fo, finest);
    }
    if (finest) surfaces(base, lv);
  }

  void surfaces(const scene::Scene& base, const Level& lv);
};

// The surface key of a patch: its primitive and its plane's normal (rounded to 1e-3).
using SurfaceKey = std::tuple<std::size_t, long, long, long>;
std::vector<SurfaceKey> surface_keys(const scene::Scene& s,
                                     const std::vector<radiosity::Patch>& patches) {
  std::vector<SurfaceKey> keys(patches.size());
  for (std::size_t p = 0; p < s.primitives.size(); ++p)
    for (uint32_t k = 0; k < s.primitives[p].triangle_count; ++k) {
      const std::size_t t = s.primitives[p].first_triangle + k;
      if (t >= patches.size()) continue;
      const glm::dvec3 n = patches[t].normal * 1000.0;
      keys[t] = {p, std::lround(n.x), std::lround(n.y), std::lround(n.z)};
    }
  return keys;
}

void Sweep::surfaces(const scene::Scene& base, const Level& lv) {
  const std::vector<radiosity::Patch> coarse = radiosity::make_patches(base);
  const std::vector<SurfaceKey> coarse_keys = surface_keys(base, coarse);
  const std::vector<SurfaceKey> fine_keys = surface_keys(lv.scene, lv.patches);
  EmitterGroundTruthOptions go;
  go.samples = result.surface_samples, go.seed = o.seed;
  const EmitterGroundTruthResult truth = compute_emitter_ground_truth(base, go);
  const scene::RayCaster caster(base);
  std::map<SurfaceKey, std::size_t> index;
  std::vector<std::vector<radiosity::Patch>> members;
  for (std::size_t t = 0; t < coarse.size(); ++t) {
    if (!(coarse[t].area > 0)) continue;
    auto [it, fresh] = index.emplace(coarse_keys[t], result.surfaces.size());
    if (fresh) {
      RadiositySurface s;
      s.primitive = base.primitives[std::get<0>(coarse_keys[t])].name;
      s.normal = coarse[t].normal;
      result.surfaces.push_back(s);
      members.emplace_back();
    }
    RadiositySurface& s = result.surfaces[it->second];
    s.area += coarse[t].area;
    s.truth += coarse[t].area * truth.radiance[t];
    s.truth_se +=
        coarse[t].area * coarse[t].area * truth.standard_error[t] * truth.standard_error[t];
    members[it->second].push_back(coarse[t]);
  }
  std::vector<double> fine_area(result.surfaces.size(), 0.0);
  for (std::size_t t = 0; t < lv.patches.size(); ++t) {
    const auto it = index.find(fine_keys[t]);
    if (it == index.end()) continue;
    result.surfaces[it->second].radiosity += lv.patches[t].area * best_finest[t];
    fine_area[it->second] += lv.patches[t].area;
  }
  for (std::size_t i = 0; i < result.surfaces.size(); ++i) {
    RadiositySurface& s = result.surfaces[i];
    s.truth /= s.area;
    s.truth_se = glm::sqrt(s.truth_se) / s.area;
    if (fine_area[i] > 0) s.radiosity /= fine_area[i];
    s.escape = radiosity::escape_fraction(members[i], caster, 4096, o.seed);
  }
  result.surfaces_max_edge = lv.max_edge;
  for (uint32_t t : lv.subset)
    result.patches.push_back({t, lv.patches[t].centroid, lv.patches[t].normal, lv.patches[t].area,
                              lv.truth.radiance[t], lv.truth.standard_error[t], best_finest[t]});
  log("surfaces: " + std::to_string(result.surfaces.size()) + " integrated whole, " +
      std::to_string(result.surface_samples) + " paths per triangle");
}

void check_options(const RadiosityReportOptions& o) {
  for (double e : o.max_edges)
    if (!(e > 0) || !std::isfinite(e))
      throw std::invalid_argument("--max-edges: " + std::to_string(e) +
                                  " is not a finite positive length");
  if (o.ground_truth_patches < 0 || o.ground_truth_samples < 0 || o.surface_samples < 0)
    throw std::invalid_argument("ground-truth patches and samples must be positive");
  if (o.methods.empty() || o.solvers.empty())
    throw std::invalid_argument("at least one form-factor method and one solver are needed");
  if (!(o.tolerance > 0 && o.tolerance < 1))
    throw std::invalid_argument("--tolerance: must be in (0, 1)");
}

}  // namespace

std::vector<double> default_max_edges(bool quick) {
  if (quick) return {200, 100};
  return {200, 100, 70, 50};
}

std::string method_name(radiosity::FormFactorMethod m) {
  switch (m) {
    case radiosity::FormFactorMethod::Analytic:
      return "analytic";
    case radiosity::FormFactorMethod::Rays:
      return "rays";
    case radiosity::FormFactorMethod::Hemicube:
      return "hemicube";
  }
  return "?";
}

std::string solver_name(radiosity::SolverKind s) {
  switch (s) {
    case radiosity::SolverKind::GaussSeidel:
      return "gauss-seidel";
    case radiosity::SolverKind::Jacobi:
      return "jacobi";
    case radiosity::SolverKind::Progressive:
      return "progressive";
  }
  return "?";
}

std::vector<std::string> radiosity_report_file_names() {
  return {"radiosity_results.csv", "radiosity_results.json", "radiosity_pareto.svg",
          "radiosity_pareto.png",  "radiosity_patches.csv",  "radiosity_summary.md"};
}

RadiosityReportResult run_radiosity_report(const RadiosityReportOptions& o) {
  const Clock::time_point start = Clock::now();
  check_options(o);
  const Log log{o, start};
  const scene::Scene base = load_lit_scene(o);
  std::vector<double> edges = o.max_edges.empty() ? default_max_edges(o.quick) : o.max_edges;
  std::sort(edges.begin(), edges.end(), std::greater<double>());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  RadiosityReportResult result;
  result.surface_samples = o.surface_samples > 0 ? o.surface_samples : (o.quick ? 16384 : 65536);
  const int k = o.ground_truth_patches > 0 ? o.ground_truth_patches : (o.quick ? 512 : 1024);
  const int samples = o.ground_truth_samples > 0 ? o.ground_truth_samples : (o.quick ? 1024 : 4096);
  std::error_code ec;
  std::filesystem::create_directories(o.output_dir, ec);
  if (ec) throw std::runtime_error(o.output_dir + ": cannot create directory: " + ec.message());
  Sweep sweep{o, log, k, samples, result, {}, INFINITY};
  for (std::size_t i = 0; i < edges.size(); ++i) sweep.level(base, edges[i], i + 1 == edges.size());
  mark_radiosity_pareto_front(result);
  result.seconds = since(start);
  write_radiosity_outputs(o, result);
  return result;
}

}  // namespace prt::report
