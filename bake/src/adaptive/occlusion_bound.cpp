// bake/src/adaptive/occlusion_bound.cpp — the ray-free occlusion bound (occlusion_bound.h).
#include "bake/adaptive/occlusion_bound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "bake/adaptive/triangle_hierarchy.h"

namespace prt::bake {
namespace {

constexpr double kAcceptRatio = 0.25;  // accept a group's ball when r/d ≤ this
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Bound of one triangle as seen from p: 0 when it lies within τ of the tangent plane.
double triangle_bound(const scene::Scene& scene, uint32_t t, const glm::dvec3& p,
                      const glm::dvec3& n, double threshold, double inflate) {
  glm::dvec3 q[3];
  double top = -kInfinity;
  for (int k = 0; k < 3; ++k) {
    q[k] = glm::dvec3(scene.positions[scene.triangles[t][k]]);
    top = std::max(top, glm::dot(q[k] - p, n));
  }
  if (top <= threshold) return 0.0;
  const glm::dvec3 c = (q[0] + q[1] + q[2]) / 3.0;
  double r = 0.0;
  for (const glm::dvec3& x : q) r = std::max(r, glm::length(x - c));
  return ball_projected_solid_angle_bound(c - p, r + inflate, n);
}

}  // namespace

double ball_projected_solid_angle_bound(const glm::dvec3& to_center, double radius,
                                        const glm::dvec3& n) {
  const double d = glm::length(to_center);
  if (!(d > radius)) return kInfinity;
  const double sin_a = radius / d, cos_a = std::sqrt(std::max(0.0, 1.0 - sin_a * sin_a));
  const double cos_c = std::clamp(glm::dot(to_center, n) / d, -1.0, 1.0);
  const double sin_c = std::sqrt(std::max(0.0, 1.0 - cos_c * cos_c));
  // cos(θ_c − α) when θ_c > α, else the cap holds the normal: largest cosine 1.
  const double cos_max = cos_c >= cos_a ? 1.0 : cos_c * cos_a + sin_c * sin_a;
  if (cos_max <= 0.0) return 0.0;
  return 2.0 * (1.0 - cos_a) * cos_max;
}

double occlusion_bound_brute_force(const scene::Scene& scene, std::size_t vertex,
                                   const scene::VertexRayStarts& starts) {
  const glm::dvec3 p(scene.positions[vertex]);
  const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[vertex]));
  const double threshold = starts.unreachable_height[vertex];
  const double inflate = 2.0 * static_cast<double>(starts.offset[vertex]);
  double sum = 0.0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t)
    sum += triangle_bound(scene, t, p, n, threshold, inflate);
  return sum;
}

OcclusionBounds bound_occlusion(const scene::Scene& scene, const scene::VertexRayStarts& starts,
                                double cutoff, const std::vector<uint8_t>& skip,
                                const TriangleHierarchy* hierarchy) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t V = scene.positions.size();
  OcclusionBounds result;
  result.bound.assign(V, 0.f);
  TriangleHierarchy own;
  if (hierarchy == nullptr) own = build_triangle_hierarchy(scene);
  const TriangleHierarchy& h = hierarchy != nullptr ? *hierarchy : own;
  tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
    if (!skip.empty() && skip[v]) return;
    const double threshold = starts.unreachable_height[v];
    const double inflate = 2.0 * static_cast<double>(starts.offset[v]);
    const glm::dvec3 p(scene.positions[v]);
    const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[v]));
    const glm::dvec3 abs_n = glm::abs(n);
    double sum = 0.0;
    uint32_t stack[64];
    int top = 0;
    if (!h.nodes.empty()) stack[top++] = 0;
    while (top > 0 && sum <= cutoff) {
      const uint32_t index = stack[--top];
      const TriangleHierarchy::Node& node = h.nodes[index];
      if (glm::dot(node.box_center - p, n) + glm::dot(node.box_half, abs_n) <= threshold)
        continue;  // the whole group lies within τ of the tangent plane
      const glm::dvec3 to_center = node.ball_center - p;
      const double r = node.ball_radius + inflate, d = glm::length(to_center);
      if (d > 0.0 && r <= kAcceptRatio * d) {
        sum += ball_projected_solid_angle_bound(to_center, r, n);
        continue;
      }
      if (node.count > 0) {
        for (uint32_t i = node.first; i < node.first + node.count && sum <= cutoff; ++i)
          sum += triangle_bound(scene, h.order[i], p, n, threshold, inflate);
        continue;
      }
      stack[top++] = node.second;
      stack[top++] = index + 1;
    }
    result.bound[v] = static_cast<float>(std::min(sum, 1e30));
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace prt::bake
