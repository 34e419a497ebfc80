// bake/sampling.h — low-discrepancy, per-vertex decorrelated direction sampling for the baker.
//
// The numerics are prt::numerics' (numerics/low_discrepancy.h, numerics/sampling.h,
// numerics/hash.h); this header fixes how the baker uses them:
// Points: dimensions 0 and 1 of the Owen-scrambled Sobol' sequence (a (0,2)-sequence, so every
// aligned block of 2^m points is a (0,m,2)-net), as floats in [0, 1), with the sequence seed
// hash_seed(seed, vertex): the directions of a vertex depend only on (seed, vertex index) —
// never on thread scheduling.
// Directions: cosine-weighted hemisphere (Malley's method on the Shirley–Chiu concentric disc),
// pdf(ω) = cos θ / π, around a unit normal with the orthonormal basis of Duff et al.
// (scene/orthonormal_basis.h). Frame: any (the scene's, +Y up, for the baker); local +z is the
// normal. References: [10], [11], [12] of docs/REFERENCES.md.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "numerics/hash.h"
#include "numerics/low_discrepancy.h"
#include "numerics/sampling.h"
#include "scene/orthonormal_basis.h"

namespace prt::bake {

// Rays per packet; sample counts are rounded up to a multiple of it.
inline constexpr int kPacketSize = 16;

// Samples per vertex actually used for a requested count (≥ 1): rounded up to a multiple of 16.
int round_up_to_packet(int samples);

using numerics::hash_seed;

// Point i of the Owen-scrambled 2-D Sobol' sequence for a per-vertex seed, in [0, 1)².
inline glm::vec2 sample_sobol_2d(uint32_t i, uint64_t vertex_seed) {
  return {numerics::sobol_owen_float(i, 0, vertex_seed),
          numerics::sobol_owen_float(i, 1, vertex_seed)};
}

// glm views of numerics' sampling types (e.g. to_glm(numerics::sample_cosine_hemisphere(
// to_numerics(u))), the cosine-weighted direction in the local frame, +z = normal).
inline numerics::Vec2<float> to_numerics(const glm::vec2& u) {
  return {u.x, u.y};
}
inline glm::vec3 to_glm(const numerics::Vec3<float>& v) {
  return {v.x, v.y, v.z};
}

// Duff et al. 2017: t, b such that (t, b, n) is right-handed orthonormal, for unit n — the one
// construction scene/orthonormal_basis.h defines (also behind scene::normal_only_tangent).
using scene::build_orthonormal_basis;

// Fills dirs[0 .. count) with the cosine-weighted directions of `vertex` around the unit
// normal n (world frame), for point indices first .. first + count of its sequence.
void generate_cosine_directions(const glm::vec3& n, uint64_t seed, uint64_t vertex, uint32_t first,
                                int count, glm::vec3* dirs);

}  // namespace prt::bake
