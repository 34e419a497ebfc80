// bake/src/triangle_hierarchy.h — a bounding hierarchy of triangle groups with a ball per
// group, for the ray-free queries of bake/occlusion_bound.h and bake/occluder_caps.h.
// Groups split between primitives first (a floor and the objects on it get separate groups, so a
// group's ball is not stretched over the floor), then at the median centroid; leaves hold ≤ 8
// triangles. Nodes are in depth-first order: children of node i at i + 1 and `second`.
// Frame and units: the Scene's.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "bake/scene.h"

namespace prt::bake::detail {

inline constexpr int kLeafTriangles = 8;

inline constexpr double kHierarchyInfinity = std::numeric_limits<double>::infinity();

struct Ball {
  glm::dvec3 center{0.0};
  double radius = 0.0;
};

// Groups of triangles in depth-first order; children of node i at i+1 and `second`.
struct TriangleHierarchy {
  struct Node {
    glm::dvec3 box_center, box_half;  // of the group's vertices
    Ball ball;                        // holds the group's vertices
    uint32_t first = 0, count = 0;    // leaf: range of `order`
    uint32_t second = 0;
  };
  const Scene* scene = nullptr;
  std::vector<uint32_t> order;      // triangle indices, grouped by primitive
  std::vector<uint32_t> primitive;  // per triangle (by its first vertex)
  std::vector<glm::dvec3> centroid;
  std::vector<Node> nodes;

  glm::dvec3 vertex(uint32_t t, int i) const {
    return glm::dvec3(scene->positions[scene->triangles[t][i]]);
  }

  uint32_t build(uint32_t first, uint32_t count) {
    glm::dvec3 lo(kHierarchyInfinity), hi(-kHierarchyInfinity), clo(kHierarchyInfinity),
        chi(-kHierarchyInfinity);
    for (uint32_t i = first; i < first + count; ++i) {
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, vertex(order[i], k));
        hi = glm::max(hi, vertex(order[i], k));
      }
      clo = glm::min(clo, centroid[order[i]]);
      chi = glm::max(chi, centroid[order[i]]);
    }
    Node node;
    node.box_center = 0.5 * (lo + hi);
    node.box_half = 0.5 * (hi - lo);
    node.ball.center = node.box_center;
    for (uint32_t i = first; i < first + count; ++i)
      for (int k = 0; k < 3; ++k)
        node.ball.radius =
            std::max(node.ball.radius, glm::length(vertex(order[i], k) - node.ball.center));
    node.first = first, node.count = count;
    const uint32_t index = static_cast<uint32_t>(nodes.size());
    nodes.push_back(node);
    if (count <= kLeafTriangles) return index;
    // Split between primitives first (a floor and the objects on it get separate groups, so a
    // group's ball is not stretched over the floor), then at the median centroid.
    uint32_t half = count / 2;
    const uint32_t p_first = primitive[order[first]], p_last = primitive[order[first + count - 1]];
    if (p_first != p_last) {
      const uint32_t p_mid = p_first + (p_last - p_first + 1) / 2;
      half = static_cast<uint32_t>(
          std::lower_bound(order.begin() + first, order.begin() + first + count, p_mid,
                           [&](uint32_t t, uint32_t p) { return primitive[t] < p; }) -
          (order.begin() + first));
    } else {
      const glm::dvec3 size = chi - clo;
      const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
      std::nth_element(
          order.begin() + first, order.begin() + first + half, order.begin() + first + count,
          [&](uint32_t a, uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
    }
    nodes[index].count = 0;
    build(first, half);
    const uint32_t second = build(first + half, count - half);
    nodes[index].second = second;
    return index;
  }
};

// Builds the hierarchy over every triangle of `scene` (empty when it has none).
inline TriangleHierarchy build_triangle_hierarchy(const Scene& scene) {
  TriangleHierarchy h;
  h.scene = &scene;
  const std::size_t V = scene.positions.size();
  const uint32_t T = static_cast<uint32_t>(scene.triangles.size());
  h.order.resize(T);
  h.centroid.resize(T);
  std::vector<uint32_t> vertex_primitive(V, 0);
  for (uint32_t p = 0; p < scene.primitives.size(); ++p) {
    const ScenePrimitive& prim = scene.primitives[p];
    for (std::size_t v = prim.first_vertex; v < prim.first_vertex + prim.vertex_count && v < V; ++v)
      vertex_primitive[v] = p;
  }
  h.primitive.assign(T, 0);
  for (uint32_t t = 0; t < T; ++t) {
    h.order[t] = t;
    h.centroid[t] = (h.vertex(t, 0) + h.vertex(t, 1) + h.vertex(t, 2)) / 3.0;
    h.primitive[t] = vertex_primitive[scene.triangles[t].x];
  }
  std::stable_sort(h.order.begin(), h.order.end(),
                   [&](uint32_t a, uint32_t b) { return h.primitive[a] < h.primitive[b]; });
  if (T > 0) h.build(0, T);
  return h;
}

}  // namespace prt::bake::detail
