// bake/sampling.h — low-discrepancy, per-vertex decorrelated direction sampling for the baker.
//
// Points: the first two dimensions of Sobol' (a (0,2)-sequence: van der Corput in base 2 and
// the Pascal-matrix dimension), each Owen-scrambled with the hash-based nested uniform scramble
// of Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020 (Laine–Karras style
// permutation on bit-reversed values). Owen scrambling keeps the (0,m,2)-net property of
// every aligned block of 2^m points, and the scramble seeds come from hash(seed, vertex), so the
// directions of a vertex depend only on (seed, vertex index) — never on thread scheduling.
//
// Directions: cosine-weighted hemisphere (Malley's method: Shirley–Chiu concentric disk mapping
// lifted to the hemisphere), pdf(ω) = cos θ / π, around a unit normal with the branchless
// orthonormal basis of Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
// Frame: any (the scene's, +Y up, for the baker); local +z is the normal.
// References: [10], [11], [12] of docs/REFERENCES.md.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/orthonormal_basis.h"

namespace prt::bake {

// Rays per packet; sample counts are rounded up to a multiple of it.
inline constexpr int kPacketSize = 16;

// Samples per vertex actually used for a requested count (≥ 1): rounded up to a multiple of 16.
int round_up_to_packet(int samples);

// A 64-bit mix of (seed, index) (SplitMix64 finaliser applied twice); well distributed bits.
uint64_t hash_seed(uint64_t seed, uint64_t index);

// Unscrambled Sobol' dimensions 0 and 1 of point i, as 32-bit fixed-point fractions.
uint32_t sobol_dimension0(uint32_t i);
uint32_t sobol_dimension1(uint32_t i);

// Owen scramble (nested uniform, hash-based) of a 32-bit fixed-point fraction.
uint32_t owen_scramble(uint32_t x, uint32_t seed);

// Point i of the Owen-scrambled 2-D Sobol' sequence for a per-vertex seed, in [0, 1)².
glm::vec2 sample_sobol_2d(uint32_t i, uint64_t vertex_seed);

// Shirley–Chiu concentric map of the unit square onto the unit disk (area preserving).
glm::vec2 map_square_to_concentric_disk(const glm::vec2& u);

// Cosine-weighted direction in the local frame (+z = normal), z ≥ 0; pdf = z / π.
glm::vec3 sample_cosine_hemisphere(const glm::vec2& u);

// Duff et al. 2017: t, b such that (t, b, n) is right-handed orthonormal, for unit n — the one
// construction scene/orthonormal_basis.h defines (also behind scene::normal_only_tangent).
using scene::build_orthonormal_basis;

// Fills dirs[0 .. count) with the cosine-weighted directions of `vertex` around the unit
// normal n (world frame), for point indices first .. first + count of its sequence.
void generate_cosine_directions(const glm::vec3& n, uint64_t seed, uint64_t vertex, uint32_t first,
                                int count, glm::vec3* dirs);

}  // namespace prt::bake
