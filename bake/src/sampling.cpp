// bake/src/sampling.cpp — the baker's cosine-weighted directions (bake/sampling.h).
#include "bake/sampling.h"

#include <algorithm>

namespace prt::bake {

int round_up_to_packet(int samples) {
  const int s = std::max(samples, 1);
  return (s + kPacketSize - 1) / kPacketSize * kPacketSize;
}

void generate_cosine_directions(const glm::vec3& n, uint64_t seed, uint64_t vertex, uint32_t first,
                                int count, glm::vec3* dirs) {
  glm::vec3 t, b;
  build_orthonormal_basis(n, t, b);
  const uint64_t vertex_seed = hash_seed(seed, vertex);
  for (int i = 0; i < count; ++i) {
    const glm::vec2 u = sample_sobol_2d(first + static_cast<uint32_t>(i), vertex_seed);
    const glm::vec3 l = to_glm(numerics::sample_cosine_hemisphere(to_numerics(u)));
    dirs[i] = glm::normalize(l.x * t + l.y * b + l.z * n);
  }
}

}  // namespace prt::bake
