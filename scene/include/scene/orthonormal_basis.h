// scene/orthonormal_basis.h — the branch-free orthonormal basis around a unit vector of Duff et
// al. 2017 ([12] of docs/REFERENCES.md): for unit n, t and b such that (t, b, n) is a
// right-handed orthonormal frame. Continuous except across the plane n.z = 0 (the branch sign),
// and a pure function of n, so the baker's sampling frames (bake/sampling.h) and the normal-only
// tangent frames (scene/tangent_frames.h) are the same construction. Floats, no normalisation:
// t and b are unit to float rounding when n is.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace prt::scene {

inline void build_orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.f, n.z);
  const float a = -1.f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace prt::scene
