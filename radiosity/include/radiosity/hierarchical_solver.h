// radiosity/hierarchical_solver.h — hierarchical radiosity: the radiosity equation of
// radiosity/solver.h solved on links between the nodes of an element hierarchy instead of a dense
// N × N form-factor matrix (Hanrahan, Salzman & Aupperle 1991, "A rapid hierarchical radiosity
// algorithm", SIGGRAPH '91; clusters: Smits, Arvo & Greenberg 1994, "A clustering algorithm for
// radiosity in complex environments", SIGGRAPH '94; Sillion 1995, "A unified hierarchical
// algorithm for global illumination with scattering volumes and object clusters", IEEE TVCG 1(3)).
//
// Steps: the hierarchy (radiosity/hierarchy.h); pass 0 refines the links from the root's link to
// itself against the emission (radiosity/links.h); then gather / push–pull iterations until the
// unshot power is at most `solve.tolerance` of the emitted power; each further pass re-checks
// every link against the radiosity just solved (the "BF" refinement: reflectors now carry light)
// and solves again from the current solution, until a pass splits no link or `max_passes`.
//
// One iteration (Jacobi), fine transfer (HierarchicalOptions::fine_up_to): every patch gathers its
// exact links and the point links of its leaf and all its ancestors, each evaluated at the
// patch's centroid toward its own normal; no push. Otherwise: every node gathers over its links
// (planar nodes into irradiance H, clusters into six axis buckets of power; a planar node that has
// children evaluates its point links at their two centroids instead of its own, a
// piecewise-constant rather than constant irradiance over it); push: a planar node hands its H (and
// each child its own part) down, a cluster hands each bucket to its children in proportion to their
// axis areas (a planar child turns its share into irradiance); at the patches L = E + ρ·H; pull: a
// planar node's radiance is the area-weighted mean of its children's, a cluster's six
// radiance-weighted axis areas Q_{k,±} = Σ_i L_i A_{i,k,±} are summed (a cluster sends Σ_k |d_k|
// Q_{k,sign d_k} toward d). The unshot power of an iteration is Σ_i A_i Σ_c |L_i,c − L'_i,c| over
// the patches, the change it made (the residual of the previous iterate, as radiosity/solver.h
// defines it). Energy account (per channel): emitted Σ A E; absorbed Σ A (1 − ρ) H; escaped Σ A L −
// Σ A H (what left the patches and arrived nowhere, measured by the links: negative if the
// approximations send more than a patch has); unshot as above; the balance holds exactly.
// Memory: the hierarchy, the per-node state and the links are charged to `budget`.
// Results do not depend on the thread count. Frame and units: the Scene's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/memory_budget.h"
#include "prt/emitters/emitter_responses.h"
#include "radiosity/emitter_solve.h"
#include "radiosity/hierarchy.h"
#include "radiosity/links.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace prt::radiosity {

struct HierarchicalOptions {
  LinkOptions links;  // `fine` is set from fine_up_to
  // Fine transfer for at most this many patches (LinkOptions::fine, and the gather below): every
  // patch gathers its ancestors' point links at its own centroid and normal instead of a push
  // down the hierarchy. Its cost per iteration is the sum over links of their receivers' patches
  // and its links and rays grow with it: measured 3.41% → 1.41% against dense on the Cornell box
  // at 9,624 patches, but at 300k level patches 12× the time (docs/BENCHMARKS.md).
  std::size_t fine_up_to = 100000;
  // Visibility rays a point link when links.visibility_rays is 0 (the default). The fine transfer
  // gives a receiver's patches its links' visibility, so it needs more: on the Cornell box at 9,624
  // patches 1.41% against dense with 4, 0.99% with 8, 0.87% with 12 for 3.7× the rays of 4
  // (docs/BENCHMARKS.md). The coarse transfer spreads a node's irradiance over its patches anyway.
  int fine_visibility_rays = 12, coarse_visibility_rays = 4;
  int max_passes = 4;  // refinement passes (each followed by a solve), at least 1
  SolveOptions solve;  // tolerance and max_iterations; the solver kind is ignored
};

struct HierarchicalPass {
  std::size_t links = 0, exact_links = 0, rays = 0, refined = 0, iterations = 0;
  double link_seconds = 0, solve_seconds = 0;
};

struct HierarchicalStats {
  std::size_t patches = 0, nodes = 0, planar_nodes = 0, clusters = 0;
  bool fine = false;  // fine transfer (HierarchicalOptions::fine_up_to)
  std::vector<HierarchicalPass> passes;
  std::size_t links = 0, exact_links = 0, rays = 0;  // links of the last pass; rays of all
  double hierarchy_seconds = 0, link_seconds = 0, solve_seconds = 0;
  uint64_t link_bytes = 0;      // the final links
  uint64_t budget_peak = 0;     // the largest total charged to the budget by the solve
  double epsilon_absolute = 0;  // the oracle's ε in radiance units
};

struct HierarchicalSolution {
  Hierarchy hierarchy;
  std::vector<Link> links;
  Solution solution;  // per patch; display_radiance = radiance
  HierarchicalStats stats;
  // The patches' radiance the last solve started from (per patch, as the solver holds it: the
  // visible part's radiance): with `links` and `hierarchy`, what resume_hierarchical needs to
  // repeat that solve bit for bit (radiosity/link_cache.h).
  std::vector<glm::dvec3> last_start;
};

// The link options solve_hierarchical uses for `patches` patches: fine by fine_up_to, and the
// visibility rays when options.links.visibility_rays is 0.
LinkOptions resolved_link_options(std::size_t patches, const HierarchicalOptions& options);

// Solves for `patches` (the triangles of the scene `caster` was built on). Throws
// std::invalid_argument for options out of range (epsilon ≤ 0, max_passes < 1, visibility_rays <
// 0, fine or coarse visibility rays < 1) and MemoryBudgetExceeded when the budget is too small.
HierarchicalSolution solve_hierarchical(const std::vector<Patch>& patches,
                                        const scene::RayCaster& caster,
                                        const HierarchicalOptions& options,
                                        MemoryBudget* budget = nullptr);

// The solve from given links (of a solve of the same patches with the same options, e.g. from a
// link cache), on `hierarchy` (build_hierarchy of `patches`). With `start` (that solve's
// last_start; the same emission and albedo): no refinement, one solve from `start` on the links
// as they are — the radiance of that solve, bit for bit. Without: the refinement passes of
// solve_hierarchical with the first one re-checking `links` (against the emission) instead of
// refining the root's self-link: links are only split where this emission and albedo need it,
// never merged. Stats count this solve's passes, rays and iterations only.
HierarchicalSolution resume_hierarchical(const std::vector<Patch>& patches,
                                         const scene::RayCaster& caster,
                                         const HierarchicalOptions& options, Hierarchy hierarchy,
                                         std::vector<Link> links,
                                         const std::vector<glm::dvec3>* start,
                                         MemoryBudget* budget = nullptr);

// Gather / push–pull iterations on given links (any emission and albedo of the same patches),
// from L = E; `fine` as the solve that made the links (HierarchicalStats::fine).
Solution solve_on_links(const std::vector<Patch>& patches, const Hierarchy& hierarchy,
                        const std::vector<Link>& links, bool fine, const SolveOptions& options,
                        MemoryBudget* budget = nullptr);

// The irradiance H at every patch that one gather and push over `links` delivers when the patches
// have the area-mean radiance `radiance` (no emission added, no iteration): the transport the
// links stand for, for comparing them with a dense matrix link by link (any subset of the links).
std::vector<glm::dvec3> gather_irradiance(const std::vector<Patch>& patches,
                                          const Hierarchy& hierarchy,
                                          const std::vector<Link>& links, bool fine,
                                          const std::vector<glm::dvec3>& radiance);

// One solve per emitter of `scene` on the same hierarchy and links (radiosity/emitter_solve.h's
// responses: unit white emission on that emitter, every other patch dark).
prt::EmitterResponses hierarchical_emitter_responses(const scene::Scene& scene,
                                                     const std::vector<Patch>& patches,
                                                     const HierarchicalSolution& solved,
                                                     const SolveOptions& options,
                                                     std::vector<EmitterSolveReport>* reports);

}  // namespace prt::radiosity
