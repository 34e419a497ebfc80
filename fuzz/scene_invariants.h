// fuzz/scene_invariants.h — what every successfully loaded Scene must satisfy (scene/scene.h):
// parallel per-vertex arrays, in-range triangle indices, finite positions, unit finite normals,
// primitive ranges inside the arrays. A violation aborts (a finding for the fuzzer).
#pragma once

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "scene/scene.h"

namespace prt::fuzz {

inline void check_scene_invariants(const prt::scene::Scene& scene) {
  const std::size_t n = scene.positions.size();
  if (scene.normals.size() != n || scene.albedo.size() != n) std::abort();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3& p = scene.positions[i];
    const glm::vec3& nn = scene.normals[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
    const float len2 = nn.x * nn.x + nn.y * nn.y + nn.z * nn.z;
    if (!std::isfinite(len2) || std::fabs(len2 - 1.0f) > 1e-3f) std::abort();
  }
  for (const glm::uvec3& t : scene.triangles)
    if (t.x >= n || t.y >= n || t.z >= n) std::abort();
  for (const prt::scene::ScenePrimitive& prim : scene.primitives) {
    if (static_cast<std::size_t>(prim.first_vertex) + prim.vertex_count > n) std::abort();
    if (static_cast<std::size_t>(prim.first_triangle) + prim.triangle_count >
        scene.triangles.size())
      std::abort();
  }
}

// Loader errors are one line, "PATH: problem".
inline void check_one_line_message(const char* message) {
  if (message == nullptr || message[0] == '\0' || std::strchr(message, '\n') != nullptr)
    std::abort();
}

}  // namespace prt::fuzz
