// bake/src/adaptive/scene_analysis.cpp — the open-hemisphere test and albedo facts
// (scene_analysis.h).
#include "bake/adaptive/scene_analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

namespace prt::bake {
namespace {

constexpr int kLeafSize = 16;

// A BVH over points; nodes in depth-first order, children of node i at i+1 and `second`.
struct PointHierarchy {
  struct Node {
    glm::dvec3 center, half;        // bounding box
    uint32_t first = 0, count = 0;  // leaf: range of `points`
    uint32_t second = 0;            // inner: index of the second child (count == 0)
  };
  std::vector<glm::dvec3> points;
  std::vector<Node> nodes;

  uint32_t build(uint32_t first, uint32_t count) {
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i = first; i < first + count; ++i) {
      lo = glm::min(lo, points[i]);
      hi = glm::max(hi, points[i]);
    }
    const uint32_t index = static_cast<uint32_t>(nodes.size());
    nodes.push_back({0.5 * (lo + hi), 0.5 * (hi - lo), first, count, 0});
    if (count <= kLeafSize) return index;
    const glm::dvec3 size = hi - lo;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    const uint32_t half = count / 2;
    std::nth_element(
        points.begin() + first, points.begin() + first + half, points.begin() + first + count,
        [axis](const glm::dvec3& a, const glm::dvec3& b) { return a[axis] < b[axis]; });
    nodes[index].count = 0;
    build(first, half);
    const uint32_t second = build(first + half, count - half);
    nodes[index].second = second;
    return index;
  }

  // True when some point has (q − p)·n > threshold.
  bool any_above(const glm::dvec3& p, const glm::dvec3& n, double threshold) const {
    const glm::dvec3 abs_n = glm::abs(n);
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes[stack[--top]];
      const double bound = glm::dot(node.center - p, n) + glm::dot(node.half, abs_n);
      if (bound <= threshold) continue;
      if (node.count > 0) {
        for (uint32_t i = node.first; i < node.first + node.count; ++i)
          if (glm::dot(points[i] - p, n) > threshold) return true;
        continue;
      }
      const uint32_t self = static_cast<uint32_t>(&node - nodes.data());
      stack[top++] = node.second;
      stack[top++] = self + 1;
    }
    return false;
  }
};

}  // namespace

bool is_hemisphere_open_brute_force(const scene::Scene& scene, std::size_t vertex,
                                    double threshold) {
  const glm::dvec3 p(scene.positions[vertex]);
  const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[vertex]));
  for (const glm::uvec3& t : scene.triangles)
    for (int i = 0; i < 3; ++i)
      if (glm::dot(glm::dvec3(scene.positions[t[i]]) - p, n) > threshold) return false;
  return true;
}

HemisphereAnalysis find_open_hemispheres(const scene::Scene& scene,
                                         const scene::VertexRayStarts& starts) {
  const auto t0 = std::chrono::steady_clock::now();
  HemisphereAnalysis result;
  const std::size_t V = scene.positions.size();
  result.open.assign(V, 0);
  // Only points that belong to a triangle can block a ray.
  std::vector<uint8_t> used(V, 0);
  for (const glm::uvec3& t : scene.triangles) used[t.x] = used[t.y] = used[t.z] = 1;
  PointHierarchy bvh;
  for (std::size_t v = 0; v < V; ++v)
    if (used[v]) bvh.points.emplace_back(scene.positions[v]);
  if (!bvh.points.empty()) bvh.build(0, static_cast<uint32_t>(bvh.points.size()));
  tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[v]));
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return;
    const bool above = !bvh.nodes.empty() && bvh.any_above(glm::dvec3(scene.positions[v]), n,
                                                           starts.unreachable_height[v]);
    result.open[v] = above ? 0 : 1;
  });
  result.open_count =
      static_cast<std::size_t>(std::count(result.open.begin(), result.open.end(), uint8_t{1}));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

AlbedoAnalysis analyze_albedo(const scene::Scene& scene) {
  AlbedoAnalysis a;
  for (const glm::vec3& c : scene.albedo) {
    a.grey = a.grey && c.x == c.y && c.y == c.z;
    a.all_zero = a.all_zero && c.x == 0.f && c.y == 0.f && c.z == 0.f;
    a.max_albedo = std::max({a.max_albedo, c.x, c.y, c.z});
  }
  return a;
}

}  // namespace prt::bake
