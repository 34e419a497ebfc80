// radiosity/src/patch_refinement.cpp — see radiosity/patch_refinement.h.
#include "radiosity/patch_refinement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "scene/ray_caster.h"
#include "scene/subdivide.h"

namespace prt::radiosity {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Solves the current patches (the full-matrix solvers or progressive refinement).
Solution solve_once(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                    const FormFactorOptions& ff, const SolveOptions& solve, RefinementPass* pass) {
  if (solve.solver == SolverKind::Progressive) {
    const Clock::time_point t = Clock::now();
    Solution s = solve_progressive(patches, caster, ff, solve);
    pass->solve_seconds = since(t);
    return s;
  }
  Clock::time_point t = Clock::now();
  const FormFactorMatrix f = compute_form_factors(patches, caster, ff);
  pass->form_factor_seconds = since(t);
  t = Clock::now();
  Solution s = solve_matrix(patches, f, solve);
  pass->solve_seconds = since(t);
  return s;
}

// The patches to split: those over the threshold, largest difference first, as many as the
// budget allows (4 new patches each).
std::vector<bool> choose(const std::vector<double>& difference, double threshold,
                         const std::vector<bool>& splittable, std::size_t room,
                         RefinementPass* pass) {
  std::vector<uint32_t> over;
  for (uint32_t t = 0; t < difference.size(); ++t)
    if (difference[t] > threshold && splittable[t]) over.push_back(t);
  pass->marked = over.size();
  std::stable_sort(over.begin(), over.end(),
                   [&](uint32_t a, uint32_t b) { return difference[a] > difference[b]; });
  over.resize(std::min(over.size(), room / 4));
  std::vector<bool> marked(difference.size(), false);
  for (uint32_t t : over) marked[t] = true;
  pass->refined = over.size();
  return marked;
}

}  // namespace

std::vector<double> neighbour_differences(const scene::Scene& scene,
                                          const std::vector<Patch>& patches,
                                          const std::vector<glm::dvec3>& radiance) {
  if (patches.size() != scene.triangles.size() || radiance.size() != patches.size())
    throw std::invalid_argument("neighbour_differences: one patch and radiance per triangle");
  double reference = 0.0;
  for (std::size_t t = 0; t < patches.size(); ++t)
    if (patches[t].emission == glm::dvec3(0.0))
      reference = std::max({reference, radiance[t].x, radiance[t].y, radiance[t].z});
  std::vector<double> difference(patches.size(), 0.0);
  if (!(reference > 0.0)) return difference;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> first_on_edge;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = scene.triangles[t][k], b = scene.triangles[t][(k + 1) % 3];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = first_on_edge.find(key);
      if (found == first_on_edge.end()) {
        first_on_edge.emplace(key, t);
        continue;
      }
      const uint32_t u = found->second;
      if (glm::dot(patches[u].normal, patches[t].normal) < 0.9) continue;
      if (patches[u].emission != glm::dvec3(0.0) || patches[t].emission != glm::dvec3(0.0))
        continue;
      const glm::dvec3 d = glm::abs(radiance[u] - radiance[t]);
      const double r = std::max({d.x, d.y, d.z}) / reference;
      difference[u] = std::max(difference[u], r);
      difference[t] = std::max(difference[t], r);
    }
  }
  return difference;
}

PatchRefinementResult solve_with_refinement(scene::Scene scene,
                                            const FormFactorOptions& form_factors,
                                            const SolveOptions& solve,
                                            const PatchRefinementOptions& options) {
  if (!(options.threshold > 0.0) || !std::isfinite(options.threshold))
    throw std::invalid_argument("--adaptive " + std::to_string(options.threshold) +
                                ": the threshold must be a finite positive number");
  const std::size_t start = scene.triangles.size();
  const std::size_t budget =
      options.max_patches ? options.max_patches : std::min(4 * start, kMaxPatches);
  if (options.max_levels < 1 || options.max_levels > 16)
    throw std::invalid_argument("patch refinement: max_levels must be in 1..16");
  if (budget > kMaxPatches || budget < start)
    throw std::invalid_argument("--max-patches " + std::to_string(budget) + ": must be in " +
                                std::to_string(start) + ".." + std::to_string(kMaxPatches) +
                                " (the starting patches .. the dense form-factor limit)");
  PatchRefinementResult result;
  // The smallest area each patch may be split to (from its starting patch).
  std::vector<double> smallest(start);
  {
    const std::vector<Patch> initial = make_patches(scene);
    const double shrink = std::pow(4.0, options.max_levels);
    for (std::size_t t = 0; t < start; ++t) smallest[t] = initial[t].area / shrink;
  }
  for (int pass_index = 0;; ++pass_index) {
    RefinementPass pass;
    pass.patches = scene.triangles.size();
    const scene::RayCaster caster(scene);
    std::vector<Patch> patches = make_patches(scene);
    Solution solution = solve_once(patches, caster, form_factors, solve, &pass);
    const std::vector<double> difference =
        neighbour_differences(scene, patches, solution.display_radiance);
    std::vector<bool> splittable(patches.size());
    // 1.5: a margin for the rounding of areas halved repeatedly.
    for (std::size_t t = 0; t < patches.size(); ++t)
      splittable[t] = patches[t].area > 1.5 * smallest[t];
    std::vector<bool> marked =
        choose(difference, options.threshold, splittable, budget - scene.triangles.size(), &pass);
    scene::Scene refined;
    std::vector<uint32_t> parent;
    while (pass.refined > 0 && pass_index < options.max_passes) {
      refined = scene::refine_triangles(scene, marked, 2, &parent);
      if (refined.triangles.size() <= budget) break;
      // Over budget (a long bisection closure): keep the first half of the chosen patches.
      std::size_t keep = pass.refined / 2, kept = 0;
      std::vector<uint32_t> order;
      for (uint32_t t = 0; t < marked.size(); ++t)
        if (marked[t]) order.push_back(t);
      std::stable_sort(order.begin(), order.end(),
                       [&](uint32_t a, uint32_t b) { return difference[a] > difference[b]; });
      std::fill(marked.begin(), marked.end(), false);
      for (uint32_t t : order)
        if (kept < keep) marked[t] = true, ++kept;
      pass.refined = kept;
    }
    if (pass_index >= options.max_passes) pass.refined = 0;
    result.passes.push_back(pass);
    if (pass.refined == 0 || pass_index >= options.max_passes) {
      result.patches = std::move(patches);
      result.solution = std::move(solution);
      result.scene = std::move(scene);
      return result;
    }
    std::vector<double> next(parent.size());
    for (std::size_t t = 0; t < parent.size(); ++t) next[t] = smallest[parent[t]];
    smallest = std::move(next);
    scene = std::move(refined);
  }
}

}  // namespace prt::radiosity
