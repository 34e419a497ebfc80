// scene/orthonormal_basis.h — the branch-free orthonormal basis around a unit vector of Duff et
// al. 2017 ([12] of docs/REFERENCES.md): for unit n, t and b such that (t, b, n) is a
// right-handed orthonormal frame. Continuous except across the plane n.z = 0 (the branch sign),
// and a pure function of n, so the baker's sampling frames (bake/sampling.h) and the normal-only
// tangent frames (scene/tangent_frames.h) are the same construction. Floats, no normalisation:
// t and b are unit to float rounding when n is. The construction is numerics/sampling.h's
// build_orthonormal_basis; this is its glm form.
#pragma once

#include <glm/glm.hpp>

#include "numerics/sampling.h"

namespace prt::scene {

inline void build_orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  numerics::Vec3<float> tn, bn;
  numerics::build_orthonormal_basis(numerics::Vec3<float>{n.x, n.y, n.z}, &tn, &bn);
  t = glm::vec3(tn.x, tn.y, tn.z);
  b = glm::vec3(bn.x, bn.y, bn.z);
}

}  // namespace prt::scene
