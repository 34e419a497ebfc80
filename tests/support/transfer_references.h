// tests/support/transfer_references.h — small references shared by the transfer tests (baker,
// ray offsets, ground truth):
// Lambert's exact polygon form factor (an independent check of AO) and scene helpers.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "numerics/constants.h"
#include "scene/scene.h"

namespace prt::test {

using prt::numerics::kPi;

// Cosine-weighted fraction of the hemisphere around unit n at p that the planar polygon
// `loop` covers (the differential-area-to-polygon form factor), by Lambert's formula
//   F = (1/2π) Σ_i γ_i · n·(r_i × r_{i+1}) / |r_i × r_{i+1}|,  r_i = q_i − p,
// γ_i the angle between r_i and r_{i+1}. The polygon must lie entirely above p's horizon.
inline double polygon_form_factor(const glm::dvec3& p, const glm::dvec3& n,
                                  const std::vector<glm::dvec3>& loop) {
  double sum = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec3 a = glm::normalize(loop[i] - p);
    const glm::dvec3 b = glm::normalize(loop[(i + 1) % loop.size()] - p);
    const glm::dvec3 c = glm::cross(a, b);
    const double len = glm::length(c);
    if (len <= 0) continue;
    const double gamma = std::atan2(len, glm::dot(a, b));
    sum += gamma * glm::dot(n, c) / len;
  }
  return std::fabs(sum) / (2.0 * kPi);
}

// Scales every position by s (normals unchanged) and translates by t afterwards.
inline scene::Scene transformed(scene::Scene scene, float s, glm::vec3 t = glm::vec3(0.f)) {
  for (glm::vec3& p : scene.positions) p = p * s + t;
  return scene;
}

// Sets every vertex normal of a primitive-less scene range to n.
inline void set_normals(scene::Scene& scene, std::size_t first, std::size_t count, glm::vec3 n) {
  for (std::size_t v = first; v < first + count; ++v) scene.normals[v] = n;
}

inline void set_albedo(scene::Scene& scene, glm::vec3 a) {
  for (glm::vec3& x : scene.albedo) x = a;
  for (scene::ScenePrimitive& p : scene.primitives) p.albedo = a;
}

}  // namespace prt::test
