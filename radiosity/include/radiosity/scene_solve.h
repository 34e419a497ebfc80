// radiosity/scene_solve.h — the solve of `prt radiosity`, from a scene file to per-vertex exit
// radiance: load the scene, set its emitters and albedos (scene/material_assignment.h), move
// objects, subdivide it into patches, compute the form factors (or load them from a cache and
// bring them up to date for the moves), solve; on request refine the patches and solve again
// (patch_refinement.h), or solve once more per emitter and write the responses (.prte,
// prt/emitters/emitter_responses.h). Drawing the result is relight's (relight/radiosity_render.h),
// from the solution's scene and vertex radiance alone.
//
// Units: radiance in the units of the emission; the scene's frame.
// Errors throw std::runtime_error / std::invalid_argument / scene::SceneError with one line
// naming the file or option; check_scene_solve refuses a bad request before any file is read,
// solve_scene checks every input before it computes, and each file is written atomically.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/emitter_solve.h"
#include "radiosity/form_factor_update.h"
#include "radiosity/form_factors.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/patch_refinement.h"
#include "radiosity/solver.h"
#include "scene/material_assignment.h"
#include "scene/scene.h"

namespace prt::radiosity {

// A request that is wrong for the scene it names, found once the scene is loaded: an
// --emission, --albedo or --move name the scene does not have, a move beyond
// kMaxMoveInExtents × the scene's extent, a --max-edge that makes too many patches. A caller
// with a command line reports it as the command line's fault.
struct RequestError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The longest move, in units of the scene's extent (its bounding box's diagonal as loaded): far
// enough to take an object out of any room, near enough that every coordinate stays a float
// that ray tracing handles (Embree refuses non-finite and huge bounds).
constexpr double kMaxMoveInExtents = 100.0;

// Moves an object before solving: every primitive whose name is `object` (or whose glTF mesh
// part, before the '/', is) is translated by `offset` (scene units) before subdivision.
struct ObjectMove {
  std::string object;
  glm::dvec3 offset{0.0};
};

// Parses "OBJECT=dx,dy,dz"; throws std::invalid_argument "--move TEXT: problem". The move's
// length is checked against the scene when it is applied (RequestError).
ObjectMove parse_object_move(const std::string& text);

// The default form factors, by the patch count N (docs/RADIOSITY.md, "The default form
// factors"): analytic (3 points) up to kAnalyticPatchLimit patches, where it costs at most about
// 2 CPU-seconds and has no noise; above, rays — kDefaultRaysPerPatch Sobol' rays per patch,
// emitters' rows by reciprocity — which take 4–8× less CPU on the Cornell box at 3,404–10,420
// patches and add about 1.1–1.2% relative RMS of noise (in quadrature) to the discretisation
// error against a path tracer. Stated bound: the rays' solution lies within kDefaultRaysError
// relative RMS (vertex radiance, emitters left out) of the analytic one on the same patches.
constexpr std::size_t kAnalyticPatchLimit = 1500;
constexpr int kDefaultRaysPerPatch = 1024;
constexpr double kDefaultRaysError = 0.01;

struct FormFactorChoice {
  FormFactorOptions options;  // `given` with the method (and for rays its sampling) chosen
  std::string reason;         // one line: what was chosen and why
};

// The choice for `patches` patches; `given` supplies the seed, quadrature and hemicube settings.
FormFactorChoice choose_form_factors(std::size_t patches, const FormFactorOptions& given);

struct SceneSolveRequest {
  std::string scene_path;
  std::vector<scene::MaterialColour> emission, albedo;  // --emission, --albedo
  std::optional<double> max_edge;  // subdivide to this edge length (scene units)
  // Refine where the radiance changes fast (patch_refinement.h), starting from max_edge.
  std::optional<PatchRefinementOptions> refinement;
  FormFactorOptions form_factors;
  // Replace form_factors' method by choose_form_factors' choice for the subdivided scene (with
  // refinement: for its patch budget, which the last, dominant pass approaches).
  bool choose_method = false;
  SolveOptions solve;
  // Form-factor cache (form_factor_cache.h) of the scene as loaded (before `moves`): absent →
  // computed and saved; present → loaded when its key matches, refused otherwise; of an earlier
  // algorithm revision (kFormFactorRevision) → computed and saved over it, with
  // SceneSolution::cache_notice. With the hierarchical solver a link cache (link_cache.h) of the
  // same path, by the same rules on its revision and its geometry and settings keys; other
  // emission or albedo re-check its links. Not with `moves`.
  // When the dense cache's save fails (a folder that cannot be written, a full disk), its role
  // decides. An absent cache is an output the caller asked for: the failure is thrown, as for
  // any output (the CLI refuses a folder it cannot write before any work). A stale cache is an
  // input the caller gave to be reused, whose refresh is a side effect: the run goes on with
  // the factors just computed, the old file is left as it was, cache stays None and
  // cache_notice says (one line) that it was recomputed and could not be updated, and why.
  std::string form_factor_cache;
  std::vector<ObjectMove> moves;  // form factors updated partially when a cache is loaded
  // Optional: per-emitter responses (emitter_solve.h), one more solve per emitter on the same
  // form factors; needs a full-matrix solver.
  std::string per_emitter_path;
  // Keep the hidden parts of patches (the floor under a block resting on it) out of the vertex
  // radiance (radiosity/hidden_patches.h); false: plain area-weighted patch means.
  bool hide_enclosed = true;
  // Bytes the solve may hold (prt/core/memory_budget.h); 0: none.
  uint64_t memory_limit = 0;
  // Hierarchical radiosity (hierarchical_solver.h) in place of dense form factors and `solve`'s
  // solver (its tolerance and max_iterations apply); not with refinement. With
  // choose_solver it is chosen when the patches exceed kMaxPatches (dense below).
  bool hierarchical = false;
  bool choose_solver = false;
  HierarchicalOptions hierarchy;
};

struct SceneSolution {
  scene::Scene scene;                  // the patch scene: patch t is triangle t
  std::vector<float> vertex_radiance;  // 3 per vertex: patches' display radiance, area-weighted
  std::size_t patches = 0;
  Solution solution;  // its radiance vectors emptied; history and energy account kept
  double form_factor_seconds = 0, solve_seconds = 0;
  double cache_seconds = 0;   // loading or saving the form-factor cache
  double update_seconds = 0;  // the partial update after the moves
  double gather_seconds = 0;  // K from F (part of solve_seconds)
  enum class Cache { None, Loaded, Saved } cache = Cache::None;
  std::string cache_message;  // hierarchical solver: what the link cache did (one line)
  std::string cache_notice;   // a cache of earlier algorithms recomputed, saved or not (one line)
  FormFactorUpdate update;    // counts of the partial update
  double escape_probe = -1;   // escape fraction measured for albedo-1 scenes (else −1)
  std::vector<RefinementPass> refinement_passes;    // with `refinement`: one per solve
  double per_emitter_seconds = 0;                   // the per-emitter solves
  std::vector<EmitterSolveReport> emitter_reports;  // one per emitter
  std::vector<std::string> files_written;           // the cache when saved, the responses
  std::string form_factor_choice;                 // with choose_method: choose_form_factors' reason
  std::optional<HierarchicalStats> hierarchical;  // set when the hierarchical solver ran
  std::string solver_choice;  // with choose_solver: which solver and why (one line)
};

// Checks the request before any file is read: the responses file (.prte, a full-matrix
// solver), max_edge, the cache (a full-matrix solver, no moves with the hierarchical one; none of
// `other_outputs` — the caller's own output files — may be it), refinement (not with a cache, moves
// or per-emitter responses, nor with hemicube form factors and the progressive solver, whose raw
// rows alias on refined patches: radiosity/hemicube.h) and the tolerance. Outputs may not be the
// scene file (scene/output_path.h).
void check_scene_solve(const SceneSolveRequest& request,
                       const std::vector<std::string>& other_outputs);

// Solves the request (check_scene_solve first). `before_solve` (optional) is called once with
// the patch scene (loaded, its materials checked, moved and subdivided; not yet refined) before
// any ray is cast: a caller's own checks on the scene (e.g. its camera) fail there, before the
// long part; an exception it throws leaves no file written.
SceneSolution solve_scene(const SceneSolveRequest& request,
                          const std::function<void(const scene::Scene&)>& before_solve = {});

// One shard of the form factors a cached dense solve computes (a farm bake, docs/FARM.md): the
// scene prepared as solve_scene prepares it, the method chosen as it chooses it, the cache key of
// form_factor_cache.h, and the rows of senders [⌊i·N/n⌋, ⌊(i+1)·N/n⌋) of F for shard i of n, each
// computed as compute_form_factors computes it (rows are independent: seeded by (seed, row)).
// The request must ask for a dense solve without moves, refinement or hemicube form factors
// (whose rows are combined across the matrix); RequestError otherwise.
struct FormFactorShard {
  uint64_t key = 0;                // form_factor_key of the patches and options
  std::size_t patches = 0;         // N
  FormFactorOptions options;       // as chosen (what the cache records)
  std::size_t first = 0, end = 0;  // the rows
  std::vector<float> rows;         // (end − first) × N
  double seconds = 0;              // computing the rows
};
FormFactorShard compute_form_factor_shard(const SceneSolveRequest& request, uint32_t index,
                                          uint32_t count);

}  // namespace prt::radiosity
