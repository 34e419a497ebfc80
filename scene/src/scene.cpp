// Scene bounds and the albedo at a surface point (see scene/scene.h).
#include "scene/scene.h"

#include <algorithm>
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

bool Scene::textured() const {
  return std::any_of(primitives.begin(), primitives.end(),
                     [](const ScenePrimitive& p) { return p.base_color_texture.has_value(); });
}

const ScenePrimitive* Scene::primitive_of_triangle(std::size_t t) const {
  // Primitives hold consecutive triangle ranges in order (empty ranges allowed).
  auto it =
      std::upper_bound(primitives.begin(), primitives.end(), t,
                       [](std::size_t x, const ScenePrimitive& p) { return x < p.first_triangle; });
  while (it != primitives.begin()) {
    --it;
    if (t < static_cast<std::size_t>(it->first_triangle) + it->triangle_count) return &*it;
    if (it->triangle_count > 0) break;
  }
  return nullptr;
}

float Scene::uv_footprint(std::size_t t, float world_width) const {
  if (texcoords.size() != positions.size() || t >= triangles.size()) return 0.f;
  const glm::uvec3 tri = triangles[t];
  const glm::dvec3 p0(positions[tri.x]), e1 = glm::dvec3(positions[tri.y]) - p0,
                                         e2 = glm::dvec3(positions[tri.z]) - p0;
  const glm::dvec2 q0(texcoords[tri.x]), f1 = glm::dvec2(texcoords[tri.y]) - q0,
                                         f2 = glm::dvec2(texcoords[tri.z]) - q0;
  const double area = glm::length(glm::cross(e1, e2));
  const double uv_area = std::fabs(f1.x * f2.y - f1.y * f2.x);
  if (!(area > 0.0) || !std::isfinite(uv_area)) return 0.f;
  return static_cast<float>(world_width * std::sqrt(uv_area / area));
}

glm::vec3 Scene::albedo_at(std::size_t t, float u, float v, float footprint) const {
  const glm::uvec3 tri = triangles[t];
  const float w0 = 1.f - u - v;
  if (!texcoords.empty()) {
    const ScenePrimitive* p = primitive_of_triangle(t);
    if (p != nullptr && p->base_color_texture) {
      const glm::vec2 uv = w0 * texcoords[tri.x] + u * texcoords[tri.y] + v * texcoords[tri.z];
      return p->base_color_texture->albedo(uv, footprint > 0.f ? uv_footprint(t, footprint) : 0.f);
    }
  }
  return w0 * albedo[tri.x] + u * albedo[tri.y] + v * albedo[tri.z];
}

}  // namespace prt::scene
