// Scenes for the radiosity tests: procedural pieces merged into one Scene.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/procedural_mesh.h"
#include "scene/scene.h"

namespace prt::test {

// Appends `part` to `scene` (its primitives keep their names; `material` names them all).
inline void append(scene::Scene& scene, scene::Scene part, const std::string& material,
                   glm::vec3 emission = glm::vec3(0.f)) {
  const uint32_t v0 = static_cast<uint32_t>(scene.positions.size());
  const uint32_t t0 = static_cast<uint32_t>(scene.triangles.size());
  scene.positions.insert(scene.positions.end(), part.positions.begin(), part.positions.end());
  scene.normals.insert(scene.normals.end(), part.normals.begin(), part.normals.end());
  scene.albedo.insert(scene.albedo.end(), part.albedo.begin(), part.albedo.end());
  for (const glm::uvec3& t : part.triangles) scene.triangles.push_back(t + glm::uvec3(v0));
  for (scene::ScenePrimitive p : part.primitives) {
    p.first_vertex += v0;
    p.first_triangle += t0;
    p.material = material;
    p.emission = emission;
    scene.primitives.push_back(p);
  }
}

// Two unit squares, each two triangles: A in z = 0 facing +z, B facing A: parallel at z = 1
// (facing −z) or perpendicular in x = 0 (facing +x) sharing A's edge x = 0.
inline scene::Scene two_squares(bool perpendicular, int segments = 1) {
  scene::Scene s;
  append(
      s,
      scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, segments, segments, glm::vec3(0.5f), "A"),
      "a");
  if (perpendicular)
    append(
        s,
        scene::make_quad({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, segments, segments, glm::vec3(0.5f), "B"),
        "b");
  else
    append(
        s,
        scene::make_quad({0, 0, 1}, {0, 1, 0}, {1, 0, 0}, segments, segments, glm::vec3(0.5f), "B"),
        "b");
  return s;
}

// Closed-form patch-to-patch form factors of unit squares (Howell's catalogue, C-11 and C-14):
// directly opposed at distance 1, and perpendicular with a common edge.
constexpr double kParallelUnitSquares = 0.199825;
constexpr double kPerpendicularUnitSquares = 0.200044;

}  // namespace prt::test
