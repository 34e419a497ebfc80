// Measures of a triangle mesh's shape for the subdivision and refinement tests and the
// subdivision_quality bench: triangle areas, the smallest angle, T-junctions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::test {

inline double triangle_area(const scene::Scene& s, const glm::uvec3& t) {
  const glm::dvec3 a(s.positions[t.x]), b(s.positions[t.y]), c(s.positions[t.z]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// The smallest angle of any triangle, in degrees.
inline double smallest_angle_degrees(const scene::Scene& s) {
  double smallest = 180.0;
  for (const glm::uvec3& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p(s.positions[t[k]]), u = glm::dvec3(s.positions[t[(k + 1) % 3]]) - p,
                                             v = glm::dvec3(s.positions[t[(k + 2) % 3]]) - p;
      smallest =
          std::min(smallest, glm::degrees(std::acos(std::clamp(
                                 glm::dot(u, v) / (glm::length(u) * glm::length(v)), -1.0, 1.0))));
    }
  return smallest;
}

// The number of (triangle edge, vertex) pairs where the vertex lies strictly inside the edge
// (farther than 1e-6 of the edge's length from either end, within 1e-6 of it from the line).
// Brute force: small meshes only.
inline std::size_t t_junctions(const scene::Scene& s) {
  std::size_t count = 0;
  for (const glm::uvec3& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 a(s.positions[t[k]]), b(s.positions[t[(k + 1) % 3]]);
      const double l2 = glm::dot(b - a, b - a);
      for (const glm::vec3& position : s.positions) {
        const glm::dvec3 p(position);
        const double u = glm::dot(p - a, b - a) / l2;
        if (u <= 1e-6 || u >= 1 - 1e-6) continue;
        if (glm::length(a + (b - a) * u - p) < 1e-6 * std::sqrt(l2)) ++count;
      }
    }
  return count;
}

}  // namespace prt::test
