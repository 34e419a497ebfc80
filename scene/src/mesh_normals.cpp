// Degenerate-triangle removal and angle-and-area weighted vertex normals (see
// scene/mesh_normals.h).
#include "scene/mesh_normals.h"

#include <cmath>
#include <vector>

namespace prt::scene {
namespace {

constexpr double kRelativeAreaEpsilon = 1e-12;
constexpr double kZeroNormalLength = 1e-30;

bool is_usable_normal(const glm::vec3& n) {
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return false;
  return glm::dot(glm::dvec3(n), glm::dvec3(n)) > 1e-12;
}

// Interior angle between edge vectors e1 and e2, in [0, pi].
double angle_between(const glm::dvec3& e1, const glm::dvec3& e2) {
  return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
}

}  // namespace

bool is_degenerate_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            double extent) {
  const glm::dvec3 pa(a), pb(b), pc(c);
  const double area = 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
  if (!std::isfinite(area)) return true;
  return area <= kRelativeAreaEpsilon * extent * extent;
}

std::size_t remove_degenerate_triangles(Scene& scene) {
  const double extent = scene.extent();
  std::vector<glm::uvec3> kept;
  kept.reserve(scene.triangles.size());
  std::size_t removed = 0;
  const auto keep_range = [&](std::size_t first, std::size_t count) {
    std::size_t kept_here = 0;
    for (std::size_t t = first; t < first + count && t < scene.triangles.size(); ++t) {
      const glm::uvec3& tri = scene.triangles[t];
      const bool repeated = tri.x == tri.y || tri.y == tri.z || tri.x == tri.z;
      if (repeated || is_degenerate_triangle(scene.positions[tri.x], scene.positions[tri.y],
                                             scene.positions[tri.z], extent)) {
        ++removed;
        continue;
      }
      kept.push_back(tri);
      ++kept_here;
    }
    return kept_here;
  };
  if (scene.primitives.empty()) {
    keep_range(0, scene.triangles.size());
  } else {
    for (ScenePrimitive& primitive : scene.primitives) {
      const std::size_t first = primitive.first_triangle;
      const std::size_t count = primitive.triangle_count;
      primitive.first_triangle = static_cast<uint32_t>(kept.size());
      primitive.triangle_count = static_cast<uint32_t>(keep_range(first, count));
    }
  }
  scene.triangles = std::move(kept);
  scene.skipped_degenerate_triangles += removed;
  return removed;
}

NormalComputation compute_vertex_normals(Scene& scene, bool only_missing) {
  const std::size_t n = scene.positions.size();
  std::vector<bool> wanted(n, true);
  if (only_missing) {
    for (std::size_t v = 0; v < n && v < scene.normals.size(); ++v) {
      wanted[v] = !is_usable_normal(scene.normals[v]);
    }
  }
  scene.normals.resize(n, glm::vec3(0.f));

  NormalComputation result;
  for (std::size_t v = 0; v < n; ++v) result.computed += wanted[v] ? 1 : 0;
  if (result.computed == 0) return result;

  std::vector<glm::dvec3> sums(n, glm::dvec3(0.0));
  for (const glm::uvec3& tri : scene.triangles) {
    if (!wanted[tri.x] && !wanted[tri.y] && !wanted[tri.z]) continue;
    const glm::dvec3 p[3] = {glm::dvec3(scene.positions[tri.x]), glm::dvec3(scene.positions[tri.y]),
                             glm::dvec3(scene.positions[tri.z])};
    // cross = 2 * area * unit normal, so the corner weight area * angle is cross / 2 * angle.
    const glm::dvec3 half_cross = 0.5 * glm::cross(p[1] - p[0], p[2] - p[0]);
    const uint32_t index[3] = {tri.x, tri.y, tri.z};
    for (int corner = 0; corner < 3; ++corner) {
      if (!wanted[index[corner]]) continue;
      const glm::dvec3& here = p[corner];
      const double angle = angle_between(p[(corner + 1) % 3] - here, p[(corner + 2) % 3] - here);
      sums[index[corner]] += half_cross * angle;
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (!wanted[v]) continue;
    const double length = glm::length(sums[v]);
    if (length > kZeroNormalLength && std::isfinite(length)) {
      scene.normals[v] = glm::vec3(sums[v] / length);
    } else {
      scene.normals[v] = glm::vec3(0.f, 1.f, 0.f);
      ++result.fallback;
    }
  }
  scene.computed_normal_vertices += result.computed;
  return result;
}

}  // namespace prt::scene
