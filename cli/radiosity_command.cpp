// `prt radiosity SCENE -o OUT [...]`: light a scene by its own emitters (diffuse radiosity,
// radiosity/scene_solve.h) and draw the solution (relight/radiosity_render.h).
//
// Every value and combination of the command line is checked before any file is read
// (check_request: UsageError, exit 2), the files by main (radiosity_files, output_safety.h);
// options that the run would ignore are refused by name (option_rules.h).
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <filesystem>
#include <stdexcept>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "option_rules.h"
#include "prt/core/memory_budget.h"
#include "radiosity/scene_solve.h"
#include "radiosity_shard.h"
#include "relight/auto_exposure.h"
#include "relight/radiosity_render.h"
#include "run_record.h"
#include "scene/material_assignment.h"
#include "shard_cli.h"

namespace prt::cli {
namespace {

struct RadiosityArguments {
  std::string scene, output, vertex_colors, csv, per_emitter;
  std::string form_factors = "auto";
  std::string solver = "auto";
  double link_epsilon = 3e-5;
  int link_rays = 0;  // 0: the solver picks (fine or coarse transfer)
  int link_passes = 4;
  std::vector<std::string> emission, albedo, moves;
  std::string form_factor_cache;
  std::optional<double> max_edge;
  std::optional<double> adaptive;
  std::size_t max_patches = 0;
  int adaptive_passes = 8;
  int adaptive_levels = 3;
  double tolerance = 1e-4;
  int rays = 1024;
  uint64_t seed = 1;
  int emitter_rays = 0;
  std::string ray_sampling = "sobol";
  std::string emitter_rows = "auto";
  int quadrature = 3;
  int hemicube = 64;
  std::size_t max_iterations = 100000;
  std::optional<double> exposure;
  std::string size = "960x540";
  int spp = 3;
  std::string camera = "auto";
  bool quiet = false;
  int threads = 0;    // --threads (0: every core)
  std::string shard;  // --shard I/N: form-factor rows into a part file (radiosity_shard.h)
  std::optional<bake::ShardSpec> shard_spec;
  uint64_t memory_limit = 0;  // --memory-limit (option_rules.h); 0: not given
};

void parse_size(const std::string& text, relight::RenderOptions* render) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
      w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError("--size " + text + ": expected WIDTHxHEIGHT, each side in 1..16384");
  render->width = w;
  render->height = h;
}

radiosity::SceneSolveRequest make_solve_request(const RadiosityArguments& a) {
  radiosity::SceneSolveRequest r;
  r.scene_path = a.scene;
  r.per_emitter_path = a.per_emitter;
  for (const std::string& e : a.emission)
    r.emission.push_back(scene::parse_material_colour("--emission", e));
  for (const std::string& e : a.albedo)
    r.albedo.push_back(scene::parse_material_colour("--albedo", e));
  r.max_edge = a.max_edge;
  r.form_factor_cache = a.form_factor_cache;
  for (const std::string& m : a.moves) r.moves.push_back(radiosity::parse_object_move(m));
  if (a.adaptive) {  // --adaptive T: patch refinement
    if (!(*a.adaptive > 0.0) || !std::isfinite(*a.adaptive))
      throw UsageError("--adaptive " + std::to_string(*a.adaptive) +
                       ": the threshold must be a finite positive number");
    if (a.adaptive_passes < 1 || a.adaptive_passes > 32)
      throw UsageError("--adaptive-passes: must be in 1..32");
    radiosity::PatchRefinementOptions o;
    o.threshold = *a.adaptive;
    o.max_patches = a.max_patches;
    o.max_passes = a.adaptive_passes;
    if (a.adaptive_levels < 1 || a.adaptive_levels > 16)
      throw UsageError("--adaptive-levels: must be in 1..16");
    o.max_levels = a.adaptive_levels;
    r.refinement = o;
  }
  if (a.form_factors == "auto") {
    r.choose_method = true;  // by the patch count (radiosity::choose_form_factors)
  } else if (a.form_factors == "analytic") {
    r.form_factors.method = radiosity::FormFactorMethod::Analytic;
  } else if (a.form_factors == "rays") {
    r.form_factors.method = radiosity::FormFactorMethod::Rays;
  } else if (a.form_factors == "hemicube") {
    r.form_factors.method = radiosity::FormFactorMethod::Hemicube;
  } else {
    throw UsageError("--form-factors " + a.form_factors + ": expected auto|analytic|rays|hemicube");
  }
  if (a.solver == "gauss-seidel" || a.solver == "auto" || a.solver == "hierarchical") {
    r.solve.solver = radiosity::SolverKind::GaussSeidel;
    r.hierarchical = a.solver == "hierarchical";
    r.choose_solver = a.solver == "auto";
  } else if (a.solver == "jacobi") {
    r.solve.solver = radiosity::SolverKind::Jacobi;
  } else if (a.solver == "progressive") {
    r.solve.solver = radiosity::SolverKind::Progressive;
  } else {
    throw UsageError("--solver " + a.solver +
                     ": expected auto|gauss-seidel|jacobi|progressive|hierarchical");
  }
  if (!(a.link_epsilon > 0.0 && a.link_epsilon < 1.0))
    throw UsageError("--link-epsilon: must be in (0, 1)");
  if (a.link_rays < 0 || a.link_rays > 256) throw UsageError("--link-rays: must be in 0..256");
  if (a.link_passes < 1 || a.link_passes > 16) throw UsageError("--link-passes: must be in 1..16");
  r.hierarchy.links.epsilon = a.link_epsilon;
  r.hierarchy.links.visibility_rays = a.link_rays;
  r.hierarchy.max_passes = a.link_passes;
  if (a.rays < 1 || a.rays > 1 << 24) throw UsageError("--rays: must be in 1..16777216");
  if (a.quadrature != 1 && a.quadrature != 3) throw UsageError("--quadrature: must be 1 or 3");
  if (a.hemicube < 2 || a.hemicube > 4096 || a.hemicube % 2 != 0)
    throw UsageError("--hemicube: must be even, 2..4096");
  r.form_factors.rays_per_patch = a.rays;
  r.form_factors.seed = a.seed;
  if (a.emitter_rays < 0 || a.emitter_rays > 1 << 24)
    throw UsageError("--emitter-rays: must be in 0..16777216");
  r.form_factors.emitter_rays_per_patch = a.emitter_rays;
  if (a.ray_sampling == "sobol") {
    r.form_factors.sampling = radiosity::RaySampling::Sobol;
  } else if (a.ray_sampling == "independent") {
    r.form_factors.sampling = radiosity::RaySampling::Independent;
  } else {
    throw UsageError("--ray-sampling " + a.ray_sampling + ": expected sobol|independent");
  }
  if (a.emitter_rows == "rays" || (a.emitter_rows == "auto" && a.emitter_rays > 0)) {
    r.form_factors.emitter_rows = radiosity::EmitterRows::Rays;
  } else if (a.emitter_rows == "reciprocal" || a.emitter_rows == "auto") {
    if (a.emitter_rays > 0)
      throw UsageError("--emitter-rays: not with --emitter-rows reciprocal (no emitter rays)");
    r.form_factors.emitter_rows = radiosity::EmitterRows::Reciprocal;
  } else {
    throw UsageError("--emitter-rows " + a.emitter_rows + ": expected auto|rays|reciprocal");
  }
  r.form_factors.hemicube_resolution = a.hemicube;
  r.form_factors.quadrature_points = a.quadrature;
  r.solve.tolerance = a.tolerance;
  r.solve.max_iterations = a.max_iterations;
  if (a.threads < 0) throw UsageError("--threads " + std::to_string(a.threads) + ": must be >= 0");
  r.memory_limit = memory_limit_or_default(a.memory_limit);
  return r;
}

relight::RadiosityRenderRequest make_render_request(const RadiosityArguments& a) {
  relight::RadiosityRenderRequest r;
  r.scene_path = a.scene;
  r.output_path = a.output;
  r.vertex_colors_path = a.vertex_colors;
  r.csv_path = a.csv;
  if (a.exposure) r.exposure_ev = float(*a.exposure);
  parse_size(a.size, &r.render);
  if (a.spp < 1 || a.spp > 16) throw UsageError("--spp: must be in 1..16 (N×N per pixel)");
  r.render.samples_per_axis = a.spp;
  r.camera = a.camera;
  return r;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Options that the run would ignore, refused by name (option_rules.h).
void check_applicable(const RadiosityArguments& a, const CLI::App& cmd) {
  const bool rays = a.form_factors == "rays";
  refuse_unless(cmd, rays,
                {"--rays", "--emitter-rays", "--ray-sampling", "--emitter-rows", "--seed"},
                "--form-factors rays");
  refuse_unless(cmd, a.form_factors == "hemicube", {"--hemicube"}, "--form-factors hemicube");
  const bool reciprocal_rows =
      rays && (a.emitter_rows == "reciprocal" || (a.emitter_rows == "auto" && a.emitter_rays == 0));
  refuse_unless(cmd, a.form_factors == "analytic" || reciprocal_rows, {"--quadrature"},
                "--form-factors analytic and the reciprocal emitter rows of --form-factors rays");
  refuse_unless(cmd, a.adaptive.has_value(),
                {"--max-patches", "--adaptive-passes", "--adaptive-levels"}, "--adaptive");
  refuse_unless(cmd, a.solver == "hierarchical" || a.solver == "auto",
                {"--link-epsilon", "--link-rays", "--link-passes"}, "--solver hierarchical|auto");
  if (a.solver == "hierarchical")
    for (const char* name : {"--form-factors", "--rays", "--emitter-rays", "--ray-sampling",
                             "--emitter-rows", "--seed", "--quadrature", "--hemicube"})
      if (cmd.count(name) > 0)
        throw UsageError(std::string(name) +
                         ": not with --solver hierarchical (it makes its own links)");
  refuse_unless(cmd, !a.output.empty(), {"--size", "--spp", "--camera", "--exposure"},
                "an image (-o IMAGE)");
  refuse_unless(cmd, lower_extension(a.output) == ".png", {"--exposure"},
                ".png output (.exr and .hdr are written linear)");
}

// Every value and combination of the command line, before any file is read. The solve's own
// request checks (radiosity::check_scene_solve) report a wrong option as invalid_argument: a
// UsageError here.
void check_request(RadiosityArguments& a, const CLI::App& cmd) {
  check_applicable(a, cmd);
  if (!a.shard.empty()) {  // form-factor rows only (radiosity_shard.h)
    check_radiosity_shard(cmd);
    if (a.form_factors == "hemicube")
      throw UsageError(
          "--form-factors hemicube: not with --shard (its rows are combined across the "
          "matrix); use analytic or rays");
    a.shard_spec = resolve_shard(a.shard, process_environment());
    try {
      radiosity::check_scene_solve(make_solve_request(a), {a.output});
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    return;
  }
  if (a.exposure) check_exposure(*a.exposure, cmd.get_option("--exposure")->as<std::string>());
  if (a.max_iterations < 1)
    throw UsageError("--max-iterations " + std::to_string(a.max_iterations) +
                     ": must be at least 1");
  if (!a.per_emitter.empty() && lower_extension(a.per_emitter) != ".prte")
    throw UsageError("--per-emitter " + a.per_emitter +
                     ": expected an emitter responses file (.prte)");
  try {
    const radiosity::SceneSolveRequest solve = make_solve_request(a);
    for (const scene::MaterialColour& c : solve.albedo)
      if (c.rgb[0] >= 1.f || c.rgb[1] >= 1.f || c.rgb[2] >= 1.f)
        throw UsageError("--albedo " + c.name + "=" + c.value +
                         ": every component must be below 1 (energy conservation)");
    const relight::RadiosityRenderRequest draw = make_render_request(a);
    if (draw.output_path.empty() && draw.vertex_colors_path.empty() && draw.csv_path.empty() &&
        solve.per_emitter_path.empty())
      throw UsageError("nothing to write: give -o IMAGE, --vertex-colors, --csv or --per-emitter");
    radiosity::check_scene_solve(solve, {draw.output_path, draw.vertex_colors_path, draw.csv_path});
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// What the run reads and writes; the form-factor cache is an input when it exists (reused) and
// an output when it does not (saved).
CommandFiles radiosity_files(const RadiosityArguments& a) {
  CommandFiles files;
  files.add_scene(a.scene);
  if (a.shard_spec) {
    files.add_output_file("-o", a.output, {".prtpart"}, "a part file (--shard)");
    files.add_run_record(a.output);
    return files;
  }
  std::error_code ec;
  if (!a.form_factor_cache.empty() && std::filesystem::exists(a.form_factor_cache, ec))
    files.add_input("form-factor cache", a.form_factor_cache);
  else
    files.add_output_file("--form-factor-cache", a.form_factor_cache);
  files.add_output_file("-o", a.output, {".exr", ".hdr", ".png"}, "an image");
  files.add_output_file("--vertex-colors", a.vertex_colors, {".glb"}, "a binary glTF");
  files.add_output_file("--csv", a.csv, {".csv"});
  files.add_output_file("--per-emitter", a.per_emitter, {".prte"}, "emitter responses");
  for (const std::string* main_output : {&a.per_emitter, &a.output, &a.csv, &a.vertex_colors})
    if (!main_output->empty()) {
      files.add_run_record(*main_output);
      break;
    }
  return files;
}

struct RadiosityRun {
  radiosity::SceneSolution solution;
  relight::RadiosityRenderSummary render;
  relight::CameraChoice camera;
};

// Solves (the camera resolved on the patch scene before the solve, so that a bad one fails
// first), then draws the solution. A request that is wrong for this scene (a name it does not
// have, a move far outside it, an edge length that makes too many patches) is the command
// line's fault: UsageError.
RadiosityRun solve_and_render(const RadiosityArguments& args) {
  const radiosity::SceneSolveRequest solve = make_solve_request(args);
  const relight::RadiosityRenderRequest draw = make_render_request(args);
  RadiosityRun run;
  try {
    run.solution = radiosity::solve_scene(solve, [&](const scene::Scene& patch_scene) {
      if (!draw.output_path.empty()) run.camera = relight::radiosity_camera(draw, patch_scene);
    });
  } catch (const radiosity::RequestError& e) {
    throw UsageError(e.what());
  }
  run.render = relight::render_radiosity(draw, run.solution.scene, run.solution.vertex_radiance,
                                         run.camera.camera);
  return run;
}

// An unconverged solve and a stale cache recomputed are warnings on stderr, which --quiet does
// not silence.
void print_warnings(const RadiosityArguments& args, const radiosity::SceneSolution& s) {
  if (!s.cache_notice.empty())
    std::fprintf(stderr, "prt radiosity: warning: %s\n", s.cache_notice.c_str());
  if (!s.solution.converged)
    std::fprintf(stderr,
                 "prt radiosity: %s: warning: the solve stopped after %zu %s with %.3g of the "
                 "emitted power unshot (--tolerance %g): raise --max-iterations to converge\n",
                 args.scene.c_str(), s.solution.iterations,
                 args.solver == "progressive" ? "shots" : "sweeps", s.solution.relative_unshot,
                 args.tolerance);
  for (const radiosity::EmitterSolveReport& r : s.emitter_reports)
    if (!r.converged)
      std::fprintf(stderr,
                   "prt radiosity: %s: warning: the response of emitter %s stopped after %zu "
                   "sweeps with %.3g unshot: raise --max-iterations to converge\n",
                   args.scene.c_str(), r.name.c_str(), r.iterations, r.relative_unshot);
}

// The phases for the run record (run_record.h); "render" only when an image was rendered.
void record_phases(const RadiosityArguments& args, const RadiosityRun& result) {
  const radiosity::SceneSolution& s = result.solution;
  RunRecord& record = run_record();
  record.phase("form factors", s.form_factor_seconds);
  if (s.cache != radiosity::SceneSolution::Cache::None)
    record.phase("form-factor cache", s.cache_seconds);
  if (s.update_seconds > 0) record.phase("form-factor update", s.update_seconds);
  record.phase("solve", s.solve_seconds);
  if (!s.emitter_reports.empty()) record.phase("per-emitter solves", s.per_emitter_seconds);
  if (!args.output.empty()) record.phase("render", result.render.render_seconds);
}

// The hierarchical solve's statistics: nodes, links (form factors) per pass, rays, times.
void print_hierarchy(const radiosity::HierarchicalStats& h) {
  std::printf(
      "hierarchical: %zu patches, %zu nodes (%zu planar, %zu clusters); %zu links (%zu exact "
      "patch-patch), %s; %zu rays; epsilon %.3g; hierarchy %.2f s, links %.2f s, solve %.2f s\n",
      h.patches, h.nodes, h.planar_nodes, h.clusters, h.links, h.exact_links,
      prt::format_memory_size(h.link_bytes).c_str(), h.rays, h.epsilon_absolute,
      h.hierarchy_seconds, h.link_seconds, h.solve_seconds);
  for (std::size_t k = 0; k < h.passes.size(); ++k) {
    const radiosity::HierarchicalPass& p = h.passes[k];
    std::printf(
        "hierarchical pass %zu: %zu links, %zu refined, %zu rays, %zu iterations; links "
        "%.2f s, solve %.2f s\n",
        k + 1, p.links, p.refined, p.rays, p.iterations, p.link_seconds, p.solve_seconds);
  }
  std::printf("hierarchical memory: %s charged at the peak\n",
              prt::format_memory_size(h.budget_peak).c_str());
}

void run(const RadiosityArguments& args) {
  std::optional<tbb::global_control> thread_limit;
  if (args.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(args.threads));
  run_record().threads = resolved_threads(args.threads);
  if (args.shard_spec)
    return run_radiosity_shard(make_solve_request(args), *args.shard_spec, args.output, args.quiet);
  const RadiosityRun result = solve_and_render(args);
  record_phases(args, result);
  print_warnings(args, result.solution);
  if (args.quiet) return;
  const radiosity::SceneSolution& s = result.solution;
  const radiosity::Solution& solution = s.solution;
  for (std::size_t k = 0; k < s.refinement_passes.size(); ++k) {
    const radiosity::RefinementPass& p = s.refinement_passes[k];
    std::printf(
        "adaptive pass %zu: %zu patches, %zu over the threshold (and splittable), %zu split\n",
        k + 1, p.patches, p.marked, p.refined);
  }
  const radiosity::EnergyAccount& e = solution.energy;
  const double emitted = e.emitted.x + e.emitted.y + e.emitted.z;
  const auto share = [&](const glm::dvec3& v) { return (v.x + v.y + v.z) / emitted; };
  std::printf(
      "%zu patches, %zu vertices; form factors %.2f s, solve %.2f s (%zu %s%s), "
      "render %.2f s\n",
      s.patches, s.scene.vertex_count(), s.form_factor_seconds, s.solve_seconds,
      solution.iterations, args.solver == "progressive" ? "shots" : "sweeps",
      solution.converged ? "" : ", NOT converged: raise --max-iterations",
      result.render.render_seconds);
  if (!s.solver_choice.empty()) std::printf("%s\n", s.solver_choice.c_str());
  if (s.hierarchical) print_hierarchy(*s.hierarchical);
  if (!s.form_factor_choice.empty()) std::printf("%s\n", s.form_factor_choice.c_str());
  if (!s.cache_message.empty())
    std::printf("%s\n", s.cache_message.c_str());
  else if (s.cache == radiosity::SceneSolution::Cache::Loaded)
    std::printf("form factors loaded from %s (%.2f s)\n", args.form_factor_cache.c_str(),
                s.cache_seconds);
  else if (s.cache == radiosity::SceneSolution::Cache::Saved)
    std::printf("form factors saved to %s (%.2f s)\n", args.form_factor_cache.c_str(),
                s.cache_seconds);
  if (!args.moves.empty() && s.cache != radiosity::SceneSolution::Cache::None)
    std::printf("moved %zu patches: recomputed %zu rows and %zu entries (%.2f s)\n",
                s.update.moved_patches, s.update.rows_recomputed, s.update.entries_recomputed,
                s.update_seconds);
  std::printf(
      "unshot power %.3g of emitted; absorbed %.6f, escaped %.6f; balance error %.2g; "
      "%s\n",
      solution.relative_unshot, share(e.absorbed), share(e.escaped), e.balance_error(),
      relight::describe_exposure(result.render.exposure_ev, result.render.exposure_auto).c_str());
  if (!args.output.empty()) std::printf("%s\n", relight::describe_camera(result.camera).c_str());
  if (!s.emitter_reports.empty()) {
    std::printf("per-emitter responses: %zu emitter%s solved in %.2f s on the same form factors:",
                s.emitter_reports.size(), s.emitter_reports.size() == 1 ? "" : "s",
                s.per_emitter_seconds);
    for (const radiosity::EmitterSolveReport& r : s.emitter_reports)
      std::printf(" %s (%zu sweeps, unshot %.2g%s)", r.name.c_str(), r.iterations,
                  r.relative_unshot, r.converged ? "" : ", NOT converged");
    std::printf("\n");
  }
  std::printf("wrote:");
  for (const std::string& file : s.files_written) std::printf(" %s", file.c_str());
  for (const std::string& file : result.render.files_written) std::printf(" %s", file.c_str());
  std::printf("\n");
}

Command register_radiosity(CLI::App& app) {
  auto args = std::make_shared<RadiosityArguments>();
  CLI::App* cmd = app.add_subcommand(
      "radiosity", "Light a scene by its own emitters (diffuse radiosity) and render it");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj)")->required();
  cmd->add_option("-o,--output", args->output,
                  "Image to write: .exr/.hdr linear, .png tone mapped");
  cmd->add_option("--vertex-colors", args->vertex_colors,
                  "Also write a .glb with COLOR_0 = exit radiance (linear)");
  cmd->add_option("--csv", args->csv, "Also write index,x,y,z,r,g,b per vertex");
  cmd->add_option("--per-emitter", args->per_emitter,
                  "Also write OUT.prte: each emitting material's response to unit white "
                  "emission, for prt relight --emitter NAME=r,g,b");
  cmd->add_option("--emission", args->emission,
                  "NAME=r,g,b: emitted radiance of a material, a primitive (glTF mesh, OBJ "
                  "object) or * for all (repeatable)");
  cmd->add_option("--albedo", args->albedo,
                  "NAME=r,g,b: albedo of a material, a primitive (glTF mesh, OBJ object) or * for "
                  "all, each below 1 (repeatable)");
  cmd->add_option(
      "--form-factor-cache", args->form_factor_cache,
      "Form factors of the scene as loaded: saved here when absent, reused when "
      "present (refused if made for another scene or other options; recomputed and saved over "
      "if made by an earlier algorithm); with the hierarchical solver its links (reused for "
      "other emission or albedo, refined where needed)");
  cmd->add_option("--move", args->moves,
                  "OBJECT=dx,dy,dz: translate an object before solving; with a cache only the "
                  "form factors the move can change are recomputed (repeatable)");
  cmd->add_option("--max-edge", args->max_edge,
                  "Subdivide into patches with edges at most this long (scene units)");
  cmd->add_option("--adaptive", args->adaptive,
                  "THRESHOLD: refine patches whose radiance differs from a neighbour's by more "
                  "than THRESHOLD x the brightest non-emitting radiance (start: --max-edge)");
  cmd->add_option("--max-patches", args->max_patches,
                  "Patch budget for --adaptive (default: 4x the starting patches)");
  cmd->add_option("--adaptive-passes", args->adaptive_passes,
                  "Refinement passes at most for --adaptive")
      ->capture_default_str();
  cmd->add_option("--adaptive-levels", args->adaptive_levels,
                  "For --adaptive: split a starting patch into at most 4^N (edges / 2^N)")
      ->capture_default_str();
  cmd->add_option("--form-factors", args->form_factors,
                  "auto|analytic|rays|hemicube; auto: analytic up to 1500 patches, above that "
                  "rays (1024 per patch); the choice is printed")
      ->capture_default_str();
  cmd->add_option("--hemicube", args->hemicube,
                  "Cells across the hemicube's top face for --form-factors hemicube")
      ->capture_default_str();
  cmd->add_option("--solver", args->solver,
                  "auto|gauss-seidel|jacobi|progressive|hierarchical; auto: gauss-seidel up to "
                  "16384 patches (dense form factors), hierarchical above")
      ->capture_default_str();
  cmd->add_option("--link-epsilon", args->link_epsilon,
                  "Hierarchical: refine a link when its estimated error exceeds this fraction of "
                  "the largest emitted radiance")
      ->capture_default_str();
  cmd->add_option("--link-rays", args->link_rays,
                  "Hierarchical: visibility rays per link between clusters or surfaces; 0: 12 "
                  "with the fine transfer (up to 100,000 patches), 4 above")
      ->capture_default_str();
  cmd->add_option("--link-passes", args->link_passes,
                  "Hierarchical: refinement passes at most (each followed by a solve)")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "Stop when the unshot power is this fraction of the emitted power")
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations, "Sweeps (progressive: shots) at most")
      ->capture_default_str();
  cmd->add_option("--rays", args->rays, "Rays per patch for --form-factors rays")
      ->capture_default_str();
  cmd->add_option("--emitter-rays", args->emitter_rays,
                  "Rays per emitting patch for --form-factors rays (0: as --rays); direct light "
                  "is estimated from these")
      ->capture_default_str();
  cmd->add_option("--ray-sampling", args->ray_sampling,
                  "sobol|independent: the rays' samples (point on the patch, direction) of "
                  "--form-factors rays: a digitally shifted Sobol' set per patch (stratified) or "
                  "independent random samples")
      ->capture_default_str();
  cmd->add_option("--emitter-rows", args->emitter_rows,
                  "auto|rays|reciprocal: emitting patches' rows for --form-factors rays, by "
                  "their own rays or by reciprocity from every receiver's analytic form factor "
                  "(--quadrature points, one shadow ray each); auto: rays when --emitter-rays is "
                  "given, else reciprocal")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed of --form-factors rays")
      ->capture_default_str();
  cmd->add_option(
         "--quadrature", args->quadrature,
         "Analytic form factors: points per sending patch (1 or 3), one visibility ray each")
      ->capture_default_str();
  cmd->add_option("--exposure", args->exposure,
                  "Exposure in EV for PNG output (default: automatic)");
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--spp", args->spp, "N: N×N stratified samples per pixel")->capture_default_str();
  cmd->add_option("--camera", args->camera, "auto | NAME | ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all)")->capture_default_str();
  add_memory_limit_option(*cmd, &args->memory_limit);
  cmd->add_flag("--quiet", args->quiet, "Print nothing on success");
  cmd->add_option("--shard", args->shard,
                  "Compute the form-factor rows of shard I/N (auto, auto/N: from Slurm or "
                  "Kubernetes) into -o PART.prtpart for prt merge (docs/FARM.md)");
  return {cmd, [args, cmd] { check_request(*args, *cmd); },
          [args] { return radiosity_files(*args); }, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(35, register_radiosity);

}  // namespace prt::cli
