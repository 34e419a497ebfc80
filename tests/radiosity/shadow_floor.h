// The shadow floor (radiosity_fixtures.h shadow_scene) solved on uniform patches, and the error
// of a solution on its floor against a reference: for the patch refinement test and the
// patch_refinement_error bench.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "radiosity_fixtures.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace prt::test {

// The triangle of `s` whose xy-projection holds (x, y), among those with normal +z in z = 0;
// −1 when none does.
inline int locate(const scene::Scene& s, const std::vector<radiosity::Patch>& patches, double x,
                  double y) {
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (patches[t].normal.z < 0.99 || std::abs(patches[t].centroid.z) > 1e-9) continue;
    const glm::dvec2 p(x, y);
    const auto corner = [&](int k) {
      return glm::dvec2(glm::dvec3(s.positions[s.triangles[t][k]]));
    };
    const glm::dvec2 a = corner(0), b = corner(1), c = corner(2);
    const auto cross = [](glm::dvec2 u, glm::dvec2 v) { return u.x * v.y - u.y * v.x; };
    if (cross(b - a, p - a) >= 0 && cross(c - b, p - b) >= 0 && cross(a - c, p - c) >= 0)
      return static_cast<int>(t);
  }
  return -1;
}

struct FloorSolution {
  scene::Scene scene;
  std::vector<radiosity::Patch> patches;
  std::vector<glm::dvec3> radiance;
};

// Mean |L − L_ref| over a 40 × 40 grid of floor points (piecewise constant per patch), relative
// to the mean reference radiance; 1e9 when a point lies on no floor patch.
inline double floor_error(const FloorSolution& s, const FloorSolution& reference) {
  double diff = 0.0, total = 0.0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double x = (i + 0.5) / 40, y = (j + 0.5) / 40;
      const int a = locate(s.scene, s.patches, x, y),
                b = locate(reference.scene, reference.patches, x, y);
      if (a < 0 || b < 0) return 1e9;  // a point no floor patch covers: fail loudly
      diff += std::abs(s.radiance[a].x - reference.radiance[b].x);
      total += reference.radiance[b].x;
    }
  return diff / total;
}

// shadow_scene(n) solved on its own patches (analytic form factors, Gauss–Seidel).
inline FloorSolution uniform_floor(int n) {
  FloorSolution s;
  s.scene = shadow_scene(n);
  s.patches = radiosity::make_patches(s.scene);
  const scene::RayCaster caster(s.scene);
  radiosity::SolveOptions solve;
  s.radiance = radiosity::solve_matrix(
                   s.patches, radiosity::compute_form_factors(s.patches, caster, {}), solve)
                   .radiance;
  return s;
}

}  // namespace prt::test
