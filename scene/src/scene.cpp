// Scene bounds (see scene/scene.h).
#include "scene/scene.h"

#include <cmath>
#include <limits>

namespace prt::scene {

glm::vec3 Scene::bounds_min() const {
  if (positions.empty()) return glm::vec3(0.f);
  glm::vec3 lo(std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : positions) lo = glm::min(lo, p);
  return lo;
}

glm::vec3 Scene::bounds_max() const {
  if (positions.empty()) return glm::vec3(0.f);
  glm::vec3 hi(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : positions) hi = glm::max(hi, p);
  return hi;
}

float Scene::extent() const {
  if (positions.empty()) return 0.f;
  const glm::dvec3 diagonal = glm::dvec3(bounds_max()) - glm::dvec3(bounds_min());
  return static_cast<float>(std::sqrt(glm::dot(diagonal, diagonal)));
}

}  // namespace prt::scene
