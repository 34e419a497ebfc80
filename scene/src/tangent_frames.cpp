#include "scene/tangent_frames.h"

#include <cmath>

namespace prt::scene {

glm::vec4 normal_only_tangent(const glm::vec3& n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  return glm::vec4(glm::normalize(t), 1.0f);
}

std::vector<glm::vec4> tangent_frames(const Scene& scene) {
  std::vector<glm::vec4> frames(scene.vertex_count());
  const bool from_file = scene.tangents.size() == scene.vertex_count();
  for (std::size_t v = 0; v < frames.size(); ++v) {
    const glm::vec3 n = scene.normals[v];
    if (from_file) {
      const glm::vec4 t = scene.tangents[v];
      const glm::vec3 orthogonal = glm::vec3(t) - glm::dot(glm::vec3(t), n) * n;
      const float length = glm::length(orthogonal);
      if (length > 1e-6f && std::isfinite(length)) {
        frames[v] = glm::vec4(orthogonal / length, t.w < 0.0f ? -1.0f : 1.0f);
        continue;
      }
    }
    frames[v] = normal_only_tangent(n);
  }
  return frames;
}

}  // namespace prt::scene
