// radiosity/patch_refinement.h — patch refinement: split the patches where the radiosity changes
// fast (neighbours differ by more than a threshold), by longest-edge bisection ([80] of
// docs/REFERENCES.md), and solve again. `prt radiosity --adaptive T` (the flag keeps its name).
//
// Starting from the given patches (e.g. scene::subdivide_to_edge_length), repeat: compute form
// factors and solve (radiosity/form_factors.h, radiosity/solver.h); mark every patch whose
// radiance differs from an edge neighbour's by more than `threshold` × L_ref, L_ref the largest
// radiance component of any non-emitting patch; split the marked patches into four by
// conforming longest-edge bisection (scene::refine_triangles: no T-junctions, shape kept), and
// solve again — until nothing is marked, the patch budget is reached, or `max_passes` passes
// have refined. Neighbours: patches sharing an edge (two vertex ids) whose normals agree
// (n_i · n_j ≥ 0.9, so a box's faces meeting at a corner are not compared); pairs with an
// emitter are not compared. Difference: the largest over RGB of |L_i − L_j|. When the budget
// allows fewer than all marked patches, the largest differences go first (ties: lower index);
// each marked patch is counted as 4 new patches against the budget (its bisection closure
// rarely adds more; a refinement that overshoots is retried with half as many). A patch that
// has reached `max_levels` (by area) is not split again.
// Every pass recomputes all form factors from scratch (N² each; the final pass dominates).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/scene.h"

namespace prt::radiosity {

struct PatchRefinementOptions {
  double threshold = 0.05;      // relative to L_ref; finite and > 0
  std::size_t max_patches = 0;  // budget; 0: 4 × the starting count (at most kMaxPatches)
  int max_passes = 8;           // refinement passes at most
  // A patch is split only while its area exceeds its starting patch's / 4^max_levels (edges
  // about 2^−max_levels as long): true discontinuities (a floor running under a block) would
  // otherwise take the whole budget.
  int max_levels = 3;
};

struct RefinementPass {
  std::size_t patches = 0;  // patches solved in this pass
  std::size_t marked = 0;   // patches over the threshold
  std::size_t refined = 0;  // patches split after it (≤ marked, by the budget)
  double form_factor_seconds = 0, solve_seconds = 0;
};

struct PatchRefinementResult {
  scene::Scene scene;  // the refined scene (patch t = triangle t)
  std::vector<Patch> patches;
  Solution solution;
  std::vector<RefinementPass> passes;
};

// Per patch: the largest relative difference to an edge neighbour (0 without neighbours).
std::vector<double> neighbour_differences(const scene::Scene& scene,
                                          const std::vector<Patch>& patches,
                                          const std::vector<glm::dvec3>& radiance);

// Throws std::invalid_argument for a threshold that is not finite and > 0, a budget over
// kMaxPatches or below the starting count, or max_levels outside 1..16.
PatchRefinementResult solve_with_refinement(scene::Scene scene,
                                            const FormFactorOptions& form_factors,
                                            const SolveOptions& solve,
                                            const PatchRefinementOptions& options);

}  // namespace prt::radiosity
