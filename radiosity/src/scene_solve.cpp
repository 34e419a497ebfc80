// radiosity/src/scene_solve.cpp — see radiosity/scene_solve.h.
#include "radiosity/scene_solve.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "form_factor_rows.h"
#include "prt/core/memory_budget.h"
#include "prt/emitters/emitter_responses.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/hidden_patches.h"
#include "radiosity/link_cache.h"
#include "radiosity/materials.h"
#include "radiosity/patches.h"
#include "scene/output_path.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace prt::radiosity {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The diagonal of the scene's bounding box (0 when it has no vertex).
std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

double scene_extent(const scene::Scene& scene) {
  if (scene.positions.empty()) return 0.0;
  glm::dvec3 lo(scene.positions.front()), hi(lo);
  for (const glm::vec3& p : scene.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  return glm::length(hi - lo);
}

void check_move_length(const ObjectMove& move, double extent) {
  const double length = glm::length(move.offset);
  if (length <= kMaxMoveInExtents * extent) return;
  char text[160];
  std::snprintf(text, sizeof text,
                ": moves %.3g scene units, more than %g × the scene's extent (%.3g)", length,
                kMaxMoveInExtents, extent);
  throw RequestError("--move " + move.object + text);
}

void apply_moves(scene::Scene& scene, const SceneSolveRequest& r) {
  const double extent = scene_extent(scene);
  for (const ObjectMove& move : r.moves) {
    check_move_length(move, extent);
    bool found = false;
    std::string names;
    for (const scene::ScenePrimitive& p : scene.primitives) {
      const std::string mesh = p.name.substr(0, p.name.find('/'));
      if (names.size() < 200) names += (names.empty() ? "" : ", ") + p.name;
      if (p.name != move.object && mesh != move.object) continue;
      found = true;
      for (uint32_t v = 0; v < p.vertex_count; ++v)
        scene.positions[p.first_vertex + v] += glm::vec3(move.offset);
    }
    if (!found)
      throw RequestError("--move " + move.object + ": no object of " + r.scene_path +
                         " has this name (objects: " + names + ")");
  }
}

// Loads the scene and applies and checks its materials; throws when nothing emits. With
// `moved`, the objects of the moves are translated before subdivision.
scene::Scene prepare_scene(const SceneSolveRequest& r, bool moved) {
  scene::Scene scene = scene::load_scene(r.scene_path);
  if (moved) apply_moves(scene, r);
  try {  // names the scene does not have
    scene::apply_emission(scene, r.emission);
    scene::apply_albedo(scene, r.albedo);
  } catch (const std::invalid_argument& e) {
    throw RequestError(e.what());
  }
  check_materials(scene);
  bool emits = false;
  for (const scene::ScenePrimitive& p : scene.primitives)
    emits = emits || (p.triangle_count > 0 && p.emission != glm::vec3(0.f));
  if (!emits)
    throw std::runtime_error(
        r.scene_path +
        ": nothing emits light (give a material glTF emissiveFactor or OBJ Ke, "
        "or --emission MATERIAL=r,g,b)");
  try {  // an edge length far too small for the scene
    if (r.max_edge) scene = scene::subdivide_to_edge_length(scene, *r.max_edge);
  } catch (const std::invalid_argument& e) {
    throw RequestError(e.what());
  }
  return scene;
}

// The form factors of `after`. With a cache: those of the scene as loaded (`before`), loaded
// when the cache exists and is of the current algorithms, else computed and saved (over a cache of
// an earlier revision, with a notice; one that cannot be replaced is left, with a notice), then
// brought up to date for the moves.
FormFactorMatrix form_factors(const SceneSolveRequest& r, const scene::Scene& before,
                              const std::vector<Patch>& after, const scene::RayCaster& caster,
                              SceneSolution* out) {
  Clock::time_point t = Clock::now();
  if (r.form_factor_cache.empty()) {
    FormFactorMatrix f = compute_form_factors(after, caster, r.form_factors);
    out->form_factor_seconds = since(t);
    return f;
  }
  const std::vector<Patch> unmoved = make_patches(before);
  if (unmoved.size() != after.size())
    throw std::runtime_error(r.scene_path + ": --move changed how the scene subdivides (" +
                             std::to_string(unmoved.size()) + " patches before, " +
                             std::to_string(after.size()) + " after); use it without a cache");
  const uint64_t key = form_factor_key(unmoved, r.form_factors);
  const bool present = std::filesystem::exists(r.form_factor_cache);
  const uint32_t revision = present ? form_factor_cache_revision(r.form_factor_cache) : 0;
  FormFactorMatrix f;
  if (present && revision >= kFormFactorRevision) {  // a later revision is refused by the load
    f = load_form_factors(r.form_factor_cache, key);
    out->cache_seconds = since(t);
    out->cache = SceneSolution::Cache::Loaded;
  } else {
    const std::string stale = present
                                  ? r.form_factor_cache + ": form factors of algorithm revision " +
                                        std::to_string(revision) + ", earlier than this prt's " +
                                        std::to_string(kFormFactorRevision) + ": recomputed"
                                  : std::string();
    if (r.moves.empty()) {
      f = compute_form_factors(after, caster, r.form_factors);
    } else {
      const scene::RayCaster unmoved_caster(before);
      f = compute_form_factors(unmoved, unmoved_caster, r.form_factors);
    }
    out->form_factor_seconds = since(t);
    t = Clock::now();
    std::string not_saved;
    try {
      save_form_factors(r.form_factor_cache, f, key, &r.form_factors);
    } catch (const std::runtime_error& e) {
      if (!present) throw;   // a cache asked for and not written fails the run, as any output
      not_saved = e.what();  // a stale one: the run goes on (scene_solve.h)
    }
    out->cache_seconds = since(t);
    if (not_saved.empty()) {
      out->cache = SceneSolution::Cache::Saved;
      out->files_written.push_back(r.form_factor_cache);
      if (present) out->cache_notice = stale + " and saved over it";
    } else {
      out->cache_notice = stale + "; the cache could not be updated (" + not_saved + ")";
    }
  }
  if (!r.moves.empty()) {
    t = Clock::now();
    out->update = update_form_factors(unmoved, after, caster, r.form_factors, &f);
    out->update_seconds = since(t);
  }
  return f;
}

// The full-matrix solve on `f`, and with per_emitter_path one solve per emitter, written.
void solve_on(const SceneSolveRequest& r, const scene::Scene& scene,
              const std::vector<Patch>& patches, const FormFactorMatrix& f, SceneSolution* out) {
  Clock::time_point t = Clock::now();
  const GatherMatrix k = make_gather_matrix(patches, f);
  out->gather_seconds = since(t);
  out->solution = solve_matrix(patches, k, r.solve);
  out->solve_seconds = since(t);
  if (!r.per_emitter_path.empty()) {  // the same form factors, one solve per emitter
    t = Clock::now();
    const prt::EmitterResponses responses =
        solve_emitter_responses(scene, patches, f, r.solve, &out->emitter_reports);
    out->per_emitter_seconds = since(t);
    const prt::Status written = prt::write_emitter_responses(r.per_emitter_path, responses);
    if (!written.ok()) throw std::runtime_error(written.message());
    out->files_written.push_back(r.per_emitter_path);
  }
}

void check_patch_count(const SceneSolveRequest& r, const scene::Scene& scene) {
  const std::size_t n = scene.triangles.size();
  if (n <= kMaxPatches) return;
  std::string advice;
  if (r.max_edge) {
    // Patches grow as 1/edge²: this edge gives about kMaxPatches, rounded up with a margin.
    const double edge = *r.max_edge * std::sqrt(double(n) / kMaxPatches) * 1.1;
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", edge);
    advice = "use a larger --max-edge (about " + std::string(text) + " or more)";
  } else {
    advice = "the scene itself has that many triangles: simplify it (--max-edge only splits)";
  }
  const std::string message = r.scene_path + ": " + std::to_string(n) + " patches, more than the " +
                              std::to_string(kMaxPatches) +
                              " that dense form-factor storage allows (8·N² bytes); " + advice +
                              ", or --solver hierarchical";
  if (r.max_edge) throw RequestError(message);  // the edge length asked for
  throw std::runtime_error(message);
}

// The hierarchical solve with a link cache (link_cache.h): loaded and its links used as they are
// (the same emission and albedo) or re-checked for the new light; absent or of an earlier
// revision: solved and saved (over it, with a notice); made for other geometry or settings or by
// a later revision: refused, as the dense cache is.
HierarchicalSolution cached_hierarchy(const SceneSolveRequest& r, const std::vector<Patch>& patches,
                                      const scene::RayCaster& caster,
                                      const HierarchicalOptions& options, MemoryBudget* budget,
                                      SceneSolution* out) {
  const std::string& path = r.form_factor_cache;
  const LinkCacheKeys keys = link_cache_keys(patches, options);
  Clock::time_point t = Clock::now();
  const bool present = std::filesystem::exists(path);
  const LinkCacheInfo cached = present ? read_link_cache_info(path) : LinkCacheInfo{};
  if (!present || cached.revision < kLinkCacheRevision) {
    if (present)
      out->cache_notice = path + ": links of algorithm revision " +
                          std::to_string(cached.revision) + ", earlier than this prt's " +
                          std::to_string(kLinkCacheRevision) + ": recomputed and saved over them";
    HierarchicalSolution solved = solve_hierarchical(patches, caster, options, budget);
    t = Clock::now();
    save_link_cache(path, keys, options, solved);
    out->cache_seconds = since(t);
    out->cache = SceneSolution::Cache::Saved;
    char text[48];
    std::snprintf(text, sizeof text, " (%.2f s)", out->cache_seconds);
    out->cache_message = "links saved to " + path + text;
    out->files_written.push_back(path);
    return solved;
  }
  const std::string mismatch = link_cache_mismatch(path, cached, keys, options, patches.size());
  if (!mismatch.empty()) throw std::runtime_error(mismatch);
  LinkCache cache = load_link_cache(path, budget);
  out->cache_seconds = since(t);
  out->cache = SceneSolution::Cache::Loaded;
  t = Clock::now();
  Hierarchy hierarchy = build_hierarchy(patches);
  const double hierarchy_seconds = since(t);
  if (hierarchy.order != cache.order)
    throw std::runtime_error(path + ": link cache of another hierarchy (its leaf order differs)");
  std::vector<uint32_t>().swap(cache.order);
  const bool same = cache.info.keys.lighting == keys.lighting;
  char text[96];
  std::snprintf(text, sizeof text, " (%.2f s): %zu links, ", out->cache_seconds,
                cache.links.size());
  out->cache_message = "links loaded from " + path + text +
                       (same ? "the same emission and albedo: used as they are"
                             : "other emission or albedo: re-checked for them");
  HierarchicalSolution solved =
      resume_hierarchical(patches, caster, options, std::move(hierarchy), std::move(cache.links),
                          same ? &cache.start : nullptr, budget);
  solved.stats.hierarchy_seconds = hierarchy_seconds;
  return solved;
}

// The hierarchical solve, and with per_emitter_path one gather solve per emitter on its links.
void solve_hierarchy(const SceneSolveRequest& r, const scene::Scene& scene,
                     std::vector<Patch>* patches, SceneSolution* out) {
  const scene::RayCaster caster(scene);
  if (r.hide_enclosed) mark_hidden_parts(patches, caster, r.form_factors);
  MemoryBudget budget(r.memory_limit, r.scene_path);
  HierarchicalOptions options = r.hierarchy;
  options.solve.tolerance = r.solve.tolerance;
  options.solve.max_iterations = r.solve.max_iterations;
  const HierarchicalSolution solved =
      r.form_factor_cache.empty() ? solve_hierarchical(*patches, caster, options, &budget)
                                  : cached_hierarchy(r, *patches, caster, options, &budget, out);
  out->solution = solved.solution;
  out->hierarchical = solved.stats;
  out->form_factor_seconds = solved.stats.hierarchy_seconds + solved.stats.link_seconds;
  out->solve_seconds = solved.stats.solve_seconds;
  if (r.per_emitter_path.empty()) return;
  const Clock::time_point t = Clock::now();
  const prt::EmitterResponses responses =
      hierarchical_emitter_responses(scene, *patches, solved, r.solve, &out->emitter_reports);
  out->per_emitter_seconds = since(t);
  const prt::Status written = prt::write_emitter_responses(r.per_emitter_path, responses);
  if (!written.ok()) throw std::runtime_error(written.message());
  out->files_written.push_back(r.per_emitter_path);
}

constexpr const char* kHierarchicalCacheMove =
    "--move: not with --form-factor-cache and the hierarchical solver (a move changes the "
    "patches its hierarchy and links are built on, which cannot be updated in part as dense form "
    "factors are); solve the moved scene without the cache";

void check_unit_albedo(const SceneSolveRequest& r, const scene::Scene& scene,
                       const std::vector<Patch>& patches, SceneSolution* out) {
  if (!has_unit_albedo(scene)) return;
  const scene::RayCaster probe(scene);
  out->escape_probe = escape_fraction(patches, probe, 64, 7);
  if (out->escape_probe == 0.0)
    throw std::runtime_error(r.scene_path +
                             ": albedo 1 in a closed scene (no probe ray escapes): the "
                             "radiosity grows without bound; lower it with --albedo "
                             "MATERIAL=r,g,b");
}

// Patch refinement: replaces `scene` with the refined one and returns its patches.
std::vector<Patch> solve_refined(const SceneSolveRequest& r, scene::Scene* scene,
                                 SceneSolution* out) {
  PatchRefinementResult result = [&] {
    try {  // a threshold, level or patch budget that does not fit the scene
      return solve_with_refinement(std::move(*scene), r.form_factors, r.solve, *r.refinement);
    } catch (const std::invalid_argument& e) {
      throw RequestError(e.what());
    }
  }();
  *scene = std::move(result.scene);
  out->solution = std::move(result.solution);
  out->refinement_passes = result.passes;
  for (const RefinementPass& pass : result.passes) {
    out->form_factor_seconds += pass.form_factor_seconds;
    out->solve_seconds += pass.solve_seconds;
  }
  return std::move(result.patches);
}

}  // namespace

FormFactorChoice choose_form_factors(std::size_t patches, const FormFactorOptions& given) {
  FormFactorChoice c;
  c.options = given;
  char text[256];
  if (patches <= kAnalyticPatchLimit) {
    c.options.method = FormFactorMethod::Analytic;
    c.options.quadrature_points = 3;
    std::snprintf(text, sizeof text,
                  "form factors: analytic (%zu patches, at most %zu: exact and cheap; "
                  "--form-factors rays|hemicube to override)",
                  patches, kAnalyticPatchLimit);
  } else {
    c.options.method = FormFactorMethod::Rays;
    c.options.rays_per_patch = kDefaultRaysPerPatch;
    c.options.emitter_rays_per_patch = 0;
    c.options.sampling = RaySampling::Sobol;
    c.options.emitter_rows = EmitterRows::Reciprocal;
    std::snprintf(text, sizeof text,
                  "form factors: rays, %d per patch (%zu patches, more than %zu: analytic costs "
                  "N^2; rays stay within %.0f%% RMS of it; --form-factors analytic to override)",
                  kDefaultRaysPerPatch, patches, kAnalyticPatchLimit, 100 * kDefaultRaysError);
  }
  c.reason = text;
  return c;
}

ObjectMove parse_object_move(const std::string& text) {
  const std::size_t eq = text.find('=');
  ObjectMove m;
  char extra = 0;
  if (eq == std::string::npos || eq == 0 ||
      std::sscanf(text.c_str() + eq + 1, "%lf,%lf,%lf%c", &m.offset.x, &m.offset.y, &m.offset.z,
                  &extra) != 3 ||
      !std::isfinite(m.offset.x) || !std::isfinite(m.offset.y) || !std::isfinite(m.offset.z))
    throw std::invalid_argument("--move " + text + ": expected OBJECT=dx,dy,dz (finite numbers)");
  m.object = text.substr(0, eq);
  return m;
}

void check_scene_solve(const SceneSolveRequest& r, const std::vector<std::string>& other_outputs) {
  scene::check_output_path(r.per_emitter_path, r.scene_path, {".prte"});
  if (!r.per_emitter_path.empty() && r.solve.solver == SolverKind::Progressive)
    throw std::invalid_argument(
        "--per-emitter needs a full-matrix solver (--solver gauss-seidel or jacobi)");
  if (r.max_edge && !(*r.max_edge > 0.0 && std::isfinite(*r.max_edge)))
    throw std::invalid_argument("--max-edge " + format_number(*r.max_edge) +
                                ": the target edge length must be a finite positive number");
  if (!r.form_factor_cache.empty()) {
    scene::check_output_path(r.form_factor_cache, r.scene_path, {});
    if (r.solve.solver == SolverKind::Progressive)
      throw std::invalid_argument("--form-factor-cache " + r.form_factor_cache +
                                  ": needs a full-matrix solver (gauss-seidel or jacobi)");
    for (const std::string& out : other_outputs) {
      std::error_code ec;
      if (!out.empty() &&
          (out == r.form_factor_cache || std::filesystem::equivalent(out, r.form_factor_cache, ec)))
        throw std::invalid_argument(out + ": an output may not overwrite the form-factor cache");
    }
  }
  if (r.refinement) {
    const char* other = !r.form_factor_cache.empty()  ? "--form-factor-cache"
                        : !r.moves.empty()            ? "--move"
                        : !r.per_emitter_path.empty() ? "--per-emitter"
                                                      : nullptr;
    if (other)
      throw std::invalid_argument(std::string("--adaptive: not with ") + other +
                                  " (the patches change from pass to pass)");
    if (!r.choose_method && r.form_factors.method == FormFactorMethod::Hemicube &&
        r.solve.solver == SolverKind::Progressive)
      throw std::invalid_argument(
          "--adaptive with --form-factors hemicube needs --solver gauss-seidel or jacobi "
          "(progressive shoots raw hemicube rows, which alias on refined patches)");
  }
  if (r.hierarchical) {
    if (!r.form_factor_cache.empty() && !r.moves.empty())
      throw std::invalid_argument(kHierarchicalCacheMove);
    if (r.refinement)
      throw std::invalid_argument(
          "--adaptive: not with the hierarchical solver (it refines its own links)");
  }
  if (!(r.solve.tolerance > 0.0 && r.solve.tolerance < 1.0))
    throw std::invalid_argument("--tolerance " + std::to_string(r.solve.tolerance) +
                                ": must be in (0, 1)");
}

SceneSolution solve_scene(const SceneSolveRequest& request,
                          const std::function<void(const scene::Scene&)>& before_solve) {
  check_scene_solve(request, {});
  SceneSolveRequest r = request;
  const scene::Scene before = prepare_scene(r, false);
  scene::Scene scene = r.moves.empty() ? before : prepare_scene(r, true);
  SceneSolution out;
  if (!r.hierarchical && r.choose_solver && !r.refinement && scene.triangles.size() > kMaxPatches) {
    if (!r.form_factor_cache.empty() && !r.moves.empty())
      throw RequestError(kHierarchicalCacheMove);
    r.hierarchical = true;
    out.solver_choice = "solver: hierarchical (" + std::to_string(scene.triangles.size()) +
                        " patches, more than the " + std::to_string(kMaxPatches) +
                        " of dense form factors)";
  }
  if (r.hierarchical) {
    r.choose_method = false;  // no dense form factors; hidden parts at 3 quadrature points
    r.form_factors.method = FormFactorMethod::Analytic;
    r.form_factors.quadrature_points = 3;
  } else {
    check_patch_count(r, scene);
  }
  if (!r.per_emitter_path.empty()) emitter_groups(scene);  // refused before solving
  if (before_solve) before_solve(scene);
  if (r.choose_method) {
    std::size_t count = scene.triangles.size();
    if (r.refinement)
      count =
          r.refinement->max_patches ? r.refinement->max_patches : std::min(4 * count, kMaxPatches);
    const FormFactorChoice choice = choose_form_factors(count, r.form_factors);
    r.form_factors = choice.options;
    out.form_factor_choice = choice.reason;
  }
  std::vector<Patch> patches = make_patches(scene);
  check_unit_albedo(r, scene, patches, &out);
  if (!r.hierarchical) {
    // Dense storage (solver.h) for the largest pass: F and K, 8·N² bytes; progressive at most
    // every row of F, 4·N².
    const uint64_t n = !r.refinement               ? patches.size()
                       : r.refinement->max_patches ? r.refinement->max_patches
                                                   : std::min(4 * patches.size(), kMaxPatches);
    const bool progressive = !r.refinement && r.solve.solver == SolverKind::Progressive;
    MemoryBudget budget(r.memory_limit, r.scene_path);
    budget.charge((progressive ? 4 : 8) * n * n, progressive
                                                     ? "the form-factor rows"
                                                     : "the dense form factors and gather matrix");
  }
  if (r.hierarchical) {
    solve_hierarchy(r, scene, &patches, &out);
  } else if (r.refinement) {
    patches = solve_refined(r, &scene, &out);  // pass by pass
    if (r.hide_enclosed) mark_hidden_parts(&patches, scene::RayCaster(scene), r.form_factors);
  } else if (r.solve.solver == SolverKind::Progressive) {
    const scene::RayCaster caster(scene);
    if (r.hide_enclosed) mark_hidden_parts(&patches, caster, r.form_factors);
    const Clock::time_point t = Clock::now();
    out.solution = solve_progressive(patches, caster, r.form_factors, r.solve);
    out.solve_seconds = since(t);  // includes the rows computed on the fly
  } else {
    const scene::RayCaster caster(scene);
    if (r.hide_enclosed) mark_hidden_parts(&patches, caster, r.form_factors);
    solve_on(r, scene, patches, form_factors(r, before, patches, caster, &out), &out);
  }
  out.patches = patches.size();
  out.vertex_radiance = vertex_radiance(scene, patches, out.solution.display_radiance);
  out.solution.radiance.clear();
  out.solution.display_radiance.clear();
  out.scene = std::move(scene);
  return out;
}

FormFactorShard compute_form_factor_shard(const SceneSolveRequest& request, uint32_t index,
                                          uint32_t count) {
  check_scene_solve(request, {});
  SceneSolveRequest r = request;
  if (!r.moves.empty() || r.refinement || r.hierarchical || count == 0 || index >= count)
    throw RequestError(r.scene_path + ": form-factor shards are for dense solves without --move " +
                       "or --adaptive");
  const scene::Scene scene = prepare_scene(r, false);
  if (r.choose_solver && scene.triangles.size() > kMaxPatches)
    throw RequestError(r.scene_path + ": " + std::to_string(scene.triangles.size()) +
                       " patches need the hierarchical solver, which has no dense form factors "
                       "to shard");
  check_patch_count(r, scene);
  FormFactorShard out;
  if (r.choose_method)
    r.form_factors = choose_form_factors(scene.triangles.size(), r.form_factors).options;
  if (r.form_factors.method == FormFactorMethod::Hemicube)
    throw RequestError(r.scene_path +
                       ": hemicube form factors combine rows across the matrix and cannot be "
                       "sharded; use --form-factors analytic or rays");
  std::vector<Patch> patches = make_patches(scene);
  SceneSolution unused;
  check_unit_albedo(r, scene, patches, &unused);
  out.key = form_factor_key(patches, r.form_factors);
  out.options = r.form_factors;
  const std::size_t n = patches.size();
  out.patches = n;
  const auto bound = [&](uint64_t i) { return i * (n / count) + i * (n % count) / count; };
  out.first = bound(index);
  out.end = bound(uint64_t{index} + 1);
  const Clock::time_point t = Clock::now();
  const scene::RayCaster caster(scene);
  if (r.hide_enclosed) mark_hidden_parts(&patches, caster, r.form_factors);
  MemoryBudget budget(r.memory_limit, r.scene_path);
  budget.charge(4 * uint64_t(out.end - out.first) * n, "the form-factor rows");
  out.rows.assign((out.end - out.first) * n, 0.f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(out.first, out.end, 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        detail::row_into(patches, caster, static_cast<uint32_t>(i), out.options,
                                         out.rows.data() + (i - out.first) * n);
                    });
  out.seconds = since(t);
  return out;
}

}  // namespace prt::radiosity
