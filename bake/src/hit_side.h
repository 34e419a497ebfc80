// bake/src/hit_side.h (private) — which side of a scene triangle a ray hits, as the transfer
// bakers judge it (transfer_baker.cpp, haar_baker.cpp).
//
// The side is judged with the hit triangle's flat geometric normal n_g = (p1 − p0) × (p2 − p0),
// oriented to agree with the sum of its three vertex normals (so a winding that disagrees with
// the normals does not matter): the ray with direction d sees the front when
// dot(n_g, d) · dot(n_g, n0 + n1 + n2) < 0. Interpolated smooth normals would misjudge rays that
// graze a neighbouring facet of a curved, faceted surface (~1% of rays in the cavity test).
// Back faces occlude but reflect nothing. Frame and units: the Scene's.
//
// front_normal() folds the orientation into n_g once per triangle (n_f = ±n_g, or 0 when the
// orientation is 0 or NaN), so that the per-hit test is the sign of one dot product:
// dot(n_f, d) < 0. It agrees with ray_hits_front_side bit for bit (negating a float is exact, so
// dot(−n_g, d) = −dot(n_g, d)), except where dot(n_g, d)·side underflows below float's smallest
// subnormal (|product| < 1.4e-45), which ray_hits_front_side reads as 0 (no front).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::bake::detail {

// True when a ray of direction `dir` (any length) hits the front of scene triangle `triangle`.
// A degenerate triangle (n_g = 0) has no front.
inline bool ray_hits_front_side(const scene::Scene& scene, uint32_t triangle,
                                const glm::vec3& dir) {
  const glm::uvec3 tri = scene.triangles[triangle];
  const glm::vec3 p0 = scene.positions[tri.x];
  const glm::vec3 ng = glm::cross(scene.positions[tri.y] - p0, scene.positions[tri.z] - p0);
  const float side =
      glm::dot(ng, scene.normals[tri.x] + scene.normals[tri.y] + scene.normals[tri.z]);
  return glm::dot(ng, dir) * side < 0.f;
}

// n_g of `triangle` oriented as above: a ray of direction d hits the front iff dot(n_f, d) < 0.
inline glm::vec3 front_normal(const scene::Scene& scene, uint32_t triangle) {
  const glm::uvec3 tri = scene.triangles[triangle];
  const glm::vec3 p0 = scene.positions[tri.x];
  const glm::vec3 ng = glm::cross(scene.positions[tri.y] - p0, scene.positions[tri.z] - p0);
  const float side =
      glm::dot(ng, scene.normals[tri.x] + scene.normals[tri.y] + scene.normals[tri.z]);
  return side > 0.f ? ng : side < 0.f ? -ng : glm::vec3(0.f);
}

}  // namespace prt::bake::detail
