// bake/src/transfer_geometry.h (private) — the geometry a coefficient file carries, copied from
// the scene by the bakers (transfer_baker.cpp, haar_baker.cpp).
//
// Positions in the scene frame and units (+Y up), normals normalised, primitives in file order,
// and the fingerprint of prt::geometry_fingerprint over the positions
// (prt/formats/transfer_data.h).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "prt/formats/geometry_check.h"
#include "prt/formats/transfer_data.h"
#include "scene/scene.h"

namespace prt::bake::detail {

// Sets vertex_count, positions, normals, primitives and fingerprint of `data` from `scene`.
inline void store_scene_geometry(const scene::Scene& scene, prt::TransferData& data) {
  const std::size_t V = scene.vertex_count();
  data.vertex_count = V;
  data.positions.resize(3 * V);
  data.normals.resize(3 * V);
  for (std::size_t v = 0; v < V; ++v) {
    const glm::vec3 n = glm::normalize(scene.normals[v]);
    for (int a = 0; a < 3; ++a) {
      data.positions[3 * v + a] = scene.positions[v][a];
      data.normals[3 * v + a] = n[a];
    }
  }
  for (const scene::ScenePrimitive& p : scene.primitives)
    data.primitives.push_back({p.first_vertex, p.vertex_count, p.name});
  data.fingerprint = prt::geometry_fingerprint(data.positions.data(), V);
}

}  // namespace prt::bake::detail
