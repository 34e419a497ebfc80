// patch_refinement_error — what patch refinement (radiosity/patch_refinement.h, `prt radiosity
// --adaptive T`) buys on the shadow floor of tests/radiosity (a 1 × 1 floor, a small lamp at
// height 2, an occluder casting a sharp shadow): for each threshold and patch budget, the passes
// (patches / marked / split) and the floor's error against a fine uniform solution, beside
// uniform patches of the same count (docs/RADIOSITY.md, "Adaptive patches" ... "patch
// refinement"). Analytic form factors, Gauss–Seidel: deterministic.
// Usage: patch_refinement_error [--quick]   (--quick: one small case, for the test suite)
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "fixtures/radiosity/radiosity_fixtures.h"
#include "fixtures/radiosity/shadow_floor.h"
#include "radiosity/patch_refinement.h"

int main(int argc, char** argv) {
  using namespace prt::radiosity;
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 2 || (argc == 2 && !quick)) {
    std::fprintf(stderr, "usage: patch_refinement_error [--quick]\n");
    return 2;
  }
  const prt::test::FloorSolution reference = prt::test::uniform_floor(quick ? 8 : 28);
  const std::vector<double> thresholds =
      quick ? std::vector<double>{0.2} : std::vector<double>{0.02, 0.05, 0.1, 0.2};
  const std::vector<std::size_t> budgets =
      quick ? std::vector<std::size_t>{60} : std::vector<std::size_t>{300, 600};
  std::printf("reference: uniform %zu patches\n", reference.patches.size());
  bool finite = true;
  for (double threshold : thresholds)
    for (std::size_t budget : budgets) {
      PatchRefinementOptions options;
      options.threshold = threshold;
      options.max_patches = budget;
      const PatchRefinementResult refined =
          solve_with_refinement(prt::test::shadow_scene(4), {}, {}, options);
      const prt::test::FloorSolution r{refined.scene, refined.patches, refined.solution.radiance};
      // Uniform n × n floor with about as many patches (2n² floor triangles + 4 others).
      const int n =
          static_cast<int>(std::lround(std::sqrt(double(refined.patches.size() - 4) / 2.0)));
      const prt::test::FloorSolution u = prt::test::uniform_floor(n);
      const double e_refined = prt::test::floor_error(r, reference);
      const double e_uniform = prt::test::floor_error(u, reference);
      finite = finite && std::isfinite(e_refined) && std::isfinite(e_uniform);
      std::printf("threshold %.2f budget %zu: passes", threshold, budget);
      for (const RefinementPass& p : refined.passes)
        std::printf(" %zu/%zu/%zu", p.patches, p.marked, p.refined);
      std::printf("; refined %zu error %.4f, uniform %zu error %.4f\n", refined.patches.size(),
                  e_refined, u.patches.size(), e_uniform);
    }
  return finite ? 0 : 1;
}
