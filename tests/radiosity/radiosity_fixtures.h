// Scenes for the radiosity tests: procedural pieces merged into one Scene.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
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

// The walls of an open room in the unit cube (top y = 1 and front z = 0 open): a white floor
// (y = 0, 4 × 4 cells), a red left wall (x = 0), a green right wall (x = 1) and a white back wall
// (z = 1), the walls `wall_cells` × `wall_cells`. Every wall faces into the room (the back wall
// −z): patches are one-sided, so a wall facing out would receive and reflect nothing.
inline void append_open_room_walls(scene::Scene& s, int wall_cells) {
  using scene::make_quad;
  const int w = wall_cells;
  append(s, make_quad({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 4, 4, glm::vec3(0.7f), "floor"), "white");
  append(s, make_quad({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, w, w, {0.7f, 0.1f, 0.1f}, "left"), "red");
  append(s, make_quad({1, 0, 0}, {0, 0, 1}, {0, 1, 0}, w, w, {0.1f, 0.7f, 0.1f}, "right"), "green");
  append(s, make_quad({0, 0, 1}, {0, 1, 0}, {1, 0, 0}, w, w, glm::vec3(0.7f), "back"), "white");
}

// The open room of the solver tests: 4 × 4 walls, a white block (0.3, 0, 0.4)–(0.6, 0.4, 0.7)
// on the floor and a 0.3 × 0.3 lamp (2 × 2 cells, emission 10, material `lamp_material`) at
// y = 0.9 facing down: open (light escapes), occluded (the block shadows), coloured walls.
inline scene::Scene open_room(const std::string& lamp_material) {
  scene::Scene s;
  append_open_room_walls(s, 4);
  append(s,
         scene::make_box({0.3f, 0, 0.4f}, {0.6f, 0.4f, 0.7f}, 1, false, glm::vec3(0.6f), "block"),
         "white");
  append(s,
         scene::make_quad({0.35f, 0.9f, 0.35f}, {0.3f, 0, 0}, {0, 0, 0.3f}, 2, 2, glm::vec3(0.5f),
                          "lamp"),
         lamp_material, glm::vec3(10.f));
  return s;
}

// An irregular octahedron (vertices at +x 1, −x 0.5, +y 2.3, −y 1.1, +z 0.6, −z 1.4 from the
// origin: its eight faces all differ, so neighbours ask for different splits), outward, closed.
// One primitive sharing its 6 vertices, or two (the faces above and below y = 0, each primitive
// with its own copies of the 4 equator vertices).
inline scene::Scene octahedron(bool two_primitives) {
  const glm::vec3 x(1.f, 0, 0), y(0, 2.3f, 0), z(0, 0, 0.6f);
  const glm::vec3 nx(-0.5f, 0, 0), ny(0, -1.1f, 0), nz(0, 0, -1.4f);
  const std::vector<std::array<glm::vec3, 3>> faces = {
      {x, y, z},  {z, y, nx},  {nx, y, nz},  {nz, y, x},  // above y = 0
      {x, z, ny}, {z, nx, ny}, {nx, nz, ny}, {nz, x, ny}};
  scene::Scene s;
  for (int half = 0; half < (two_primitives ? 2 : 1); ++half) {
    scene::ScenePrimitive p;
    p.first_vertex = uint32_t(s.positions.size());
    p.first_triangle = uint32_t(s.triangles.size());
    p.material = half == 0 ? "upper" : "lower";
    std::vector<glm::vec3> corners = {x, nx, y, ny, z, nz};
    for (const glm::vec3& c : corners) {
      s.positions.push_back(c);
      s.normals.push_back(glm::normalize(c));
      s.albedo.push_back(glm::vec3(0.5f));
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (two_primitives && (f < 4) != (half == 0)) continue;
      glm::uvec3 t;
      for (int k = 0; k < 3; ++k)
        t[k] = p.first_vertex +
               uint32_t(std::find(corners.begin(), corners.end(), faces[f][k]) - corners.begin());
      s.triangles.push_back(t);
    }
    p.vertex_count = uint32_t(s.positions.size()) - p.first_vertex;
    p.triangle_count = uint32_t(s.triangles.size()) - p.first_triangle;
    s.primitives.push_back(p);
  }
  return s;
}

// A 1 × 1 floor (z = 0, facing up) split into n × n squares, a small lamp above it facing
// down, high enough to light the floor almost evenly, and an occluding square near the floor
// casting a sharp shadow (a narrow penumbra).
inline scene::Scene shadow_scene(int n) {
  scene::Scene s;
  append(s, scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, n, n, glm::vec3(0.5f)), "floor");
  append(s,
         scene::make_quad({0.45f, 0.45f, 2.f}, {0, 0.1f, 0}, {0.1f, 0, 0}, 1, 1, glm::vec3(0.5f)),
         "lamp", glm::vec3(200.f));
  append(s,
         scene::make_quad({0.3f, 0.25f, 0.15f}, {0, 0.3f, 0}, {0.3f, 0, 0}, 1, 1, glm::vec3(0.5f)),
         "occluder");
  return s;
}

// max over entries of |a − b| / (largest component of b).
inline double max_relative_difference(const std::vector<glm::dvec3>& a,
                                      const std::vector<glm::dvec3>& b) {
  double worst = 0.0, scale = 0.0;
  for (const glm::dvec3& v : b) scale = std::max({scale, v.x, v.y, v.z});
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[i][c] - b[i][c]) / scale);
  return worst;
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
