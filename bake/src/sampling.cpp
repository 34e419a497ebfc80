// bake/src/sampling.cpp — Owen-scrambled Sobol' points and cosine-weighted directions.
#include "bake/sampling.h"

#include <algorithm>
#include <cmath>

#include "sh/constants.h"

namespace prt::bake {
namespace {

using sh::kPiFloat;

uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// 2^-32 as float; the result is clamped below 1 (float rounding of values near 1).
float to_unit_float(uint32_t x) {
  return std::min(static_cast<float>(x) * 2.3283064365386963e-10f, 0x1.fffffep-1f);
}

}  // namespace

int round_up_to_packet(int samples) {
  const int s = std::max(samples, 1);
  return (s + kPacketSize - 1) / kPacketSize * kPacketSize;
}

uint64_t hash_seed(uint64_t seed, uint64_t index) {
  return mix64(mix64(seed + 0x9e3779b97f4a7c15ULL) ^ (index * 0xd1b54a32d192ed03ULL));
}

uint32_t sobol_dimension0(uint32_t i) {
  return reverse_bits(i);
}

uint32_t sobol_dimension1(uint32_t i) {
  // Direction numbers of the second Sobol' dimension (primitive polynomial x + 1): the
  // generator matrix is Pascal's triangle mod 2, built column by column as v ^= v >> 1.
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) r ^= v;
  return r;
}

uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  // Laine–Karras permutation on the bit-reversed value: each bit is flipped by a hash of the
  // bits above it (more significant in the original), i.e. a nested uniform scramble.
  // Constants from Vegdahl's improved variant (discussed in Burley 2020's follow-ups).
  x = reverse_bits(x);
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return reverse_bits(x);
}

glm::vec2 sample_sobol_2d(uint32_t i, uint64_t vertex_seed) {
  const auto s0 = static_cast<uint32_t>(vertex_seed);
  const auto s1 = static_cast<uint32_t>(vertex_seed >> 32);
  return {to_unit_float(owen_scramble(sobol_dimension0(i), s0)),
          to_unit_float(owen_scramble(sobol_dimension1(i), s1))};
}

glm::vec2 map_square_to_concentric_disk(const glm::vec2& u) {
  const float a = 2.f * u.x - 1.f, b = 2.f * u.y - 1.f;
  if (a == 0.f && b == 0.f) return {0.f, 0.f};
  float r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = (kPiFloat / 4.f) * (b / a);
  } else {
    r = b;
    phi = (kPiFloat / 2.f) - (kPiFloat / 4.f) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

glm::vec3 sample_cosine_hemisphere(const glm::vec2& u) {
  const glm::vec2 d = map_square_to_concentric_disk(u);
  const float z = std::sqrt(std::max(0.f, 1.f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

void generate_cosine_directions(const glm::vec3& n, uint64_t seed, uint64_t vertex, uint32_t first,
                                int count, glm::vec3* dirs) {
  glm::vec3 t, b;
  build_orthonormal_basis(n, t, b);
  const uint64_t vertex_seed = hash_seed(seed, vertex);
  for (int i = 0; i < count; ++i) {
    const glm::vec3 l =
        sample_cosine_hemisphere(sample_sobol_2d(first + static_cast<uint32_t>(i), vertex_seed));
    dirs[i] = glm::normalize(l.x * t + l.y * b + l.z * n);
  }
}

}  // namespace prt::bake
