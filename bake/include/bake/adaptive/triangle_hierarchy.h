// bake/adaptive/triangle_hierarchy.h — a bounding hierarchy of triangle groups with a box and a
// ball per group, for the ray-free queries of bake/adaptive/occlusion_bound.h and
// bake/adaptive/occluder_caps.h (built once per `prt bake --auto` and shared by both).
//
// Groups split between primitives first (a floor and the objects on it get separate groups, so
// a group's ball is not stretched over the floor), then at the median centroid along the
// longest axis of the centroids' box; leaves hold ≤ 8 triangles. Nodes are in depth-first
// order: the children of node i are i + 1 and `second`. A group's box and ball hold its
// triangles' vertices; the ball is centred on the box (not minimal, but cheap and exact).
// Frame and units: the Scene's. The hierarchy refers to the scene, which must outlive it.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::bake {

struct TriangleHierarchy {
  static constexpr uint32_t kLeafTriangles = 8;
  struct Node {
    glm::dvec3 box_center{0.0}, box_half{0.0};  // of the group's vertices
    glm::dvec3 ball_center{0.0};                // = box_center
    double ball_radius = 0.0;                   // holds the group's vertices
    uint32_t first = 0, count = 0;              // range of `order`; count > 0 only at leaves
    uint32_t size = 0;                          // triangles in the group
    uint32_t second = 0;                        // the second child (internal nodes)
  };
  const scene::Scene* scene = nullptr;
  std::vector<uint32_t> order;  // triangle indices, grouped by primitive
  std::vector<Node> nodes;

  glm::dvec3 vertex(uint32_t triangle, int i) const {
    return glm::dvec3(scene->positions[scene->triangles[triangle][i]]);
  }
};

enum class HierarchyBuild {
  Parallel,  // large groups' halves split concurrently (the default)
  Serial,    // one thread: the reference the parallel build must equal node for node
};

// Builds the hierarchy over every triangle of `scene` (no nodes when it has none). Boxes and
// balls are computed in parallel. Deterministic: both modes give the same nodes and order.
TriangleHierarchy build_triangle_hierarchy(const scene::Scene& scene,
                                           HierarchyBuild mode = HierarchyBuild::Parallel);

}  // namespace prt::bake
