// bake/src/adaptive/triangle_hierarchy.cpp — building the triangle-group hierarchy
// (triangle_hierarchy.h).
#include "bake/adaptive/triangle_hierarchy.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace prt::bake {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where the group order[first, first + count) splits: between primitives when it holds more
// than one (order is sorted by primitive), else at the median centroid along the longest axis
// of the centroids' box (order[first, first + count) is partitioned around it).
uint32_t split_point(TriangleHierarchy& h, const std::vector<uint32_t>& primitive,
                     const std::vector<glm::dvec3>& centroid, uint32_t first, uint32_t count) {
  uint32_t half = count / 2;
  const auto begin = h.order.begin() + first;
  const uint32_t p_first = primitive[h.order[first]];
  const uint32_t p_last = primitive[h.order[first + count - 1]];
  if (p_first != p_last) {
    // Between primitives (order is sorted by primitive).
    const uint32_t p_mid = p_first + (p_last - p_first + 1) / 2;
    half = static_cast<uint32_t>(
        std::lower_bound(begin, begin + count, p_mid,
                         [&](uint32_t t, uint32_t p) { return primitive[t] < p; }) -
        begin);
  } else {
    glm::dvec3 lo(kInfinity), hi(-kInfinity);
    for (uint32_t i = first; i < first + count; ++i) {
      lo = glm::min(lo, centroid[h.order[i]]);
      hi = glm::max(hi, centroid[h.order[i]]);
    }
    const glm::dvec3 size = hi - lo;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    std::nth_element(begin, begin + half, begin + count,
                     [&](uint32_t a, uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
  }
  return half;
}

struct Builder {
  TriangleHierarchy& h;
  const std::vector<uint32_t>& primitive;  // per triangle
  const std::vector<glm::dvec3>& centroid;

  // Topology only: the split of order[first, first + count).
  uint32_t build(uint32_t first, uint32_t count) {
    const uint32_t index = static_cast<uint32_t>(h.nodes.size());
    h.nodes.emplace_back();
    h.nodes[index].first = first;
    h.nodes[index].size = count;
    if (count <= TriangleHierarchy::kLeafTriangles) {
      h.nodes[index].count = count;
      return index;
    }
    const uint32_t half = split_point(h, primitive, centroid, first, count);
    build(first, half);
    const uint32_t second = build(first + half, count - half);
    h.nodes[index].second = second;
    return index;
  }
};

// The same splits as Builder, with the two halves of a large group split concurrently (they
// touch disjoint ranges of `order`), into a temporary tree; emit() then numbers it depth-first
// exactly as Builder does. Same order, same nodes.
struct ParallelBuilder {
  static constexpr uint32_t kSerialBelow = 1u << 14;  // smaller groups: one task
  struct Split {
    uint32_t first = 0, count = 0;
    uint32_t left = 0, right = 0;  // temporary indices; count ≤ kLeafTriangles: a leaf
  };
  TriangleHierarchy& h;
  const std::vector<uint32_t>& primitive;
  const std::vector<glm::dvec3>& centroid;
  std::vector<Split> splits;
  std::atomic<uint32_t> used{0};

  uint32_t split(uint32_t first, uint32_t count) {
    const uint32_t index = used.fetch_add(1, std::memory_order_relaxed);
    Split& node = splits[index];
    node.first = first;
    node.count = count;
    if (count <= TriangleHierarchy::kLeafTriangles) return index;
    const uint32_t half = split_point(h, primitive, centroid, first, count);
    if (count >= kSerialBelow) {
      tbb::parallel_invoke([&] { node.left = split(first, half); },
                           [&] { node.right = split(first + half, count - half); });
    } else {
      node.left = split(first, half);
      node.right = split(first + half, count - half);
    }
    return index;
  }

  uint32_t emit(uint32_t s) {
    const uint32_t index = static_cast<uint32_t>(h.nodes.size());
    h.nodes.emplace_back();
    h.nodes[index].first = splits[s].first;
    h.nodes[index].size = splits[s].count;
    if (splits[s].count <= TriangleHierarchy::kLeafTriangles) {
      h.nodes[index].count = splits[s].count;
      return index;
    }
    emit(splits[s].left);
    const uint32_t second = emit(splits[s].right);
    h.nodes[index].second = second;
    return index;
  }
};

// Boxes and balls of the groups' vertices, the same values as a pass over every group's
// vertices (which costs one visit per triangle per level of the tree) at a fraction of the cost:
// - boxes bottom up: a leaf's from its vertices, an internal node's as the union of its
//   children's (min and max are exact, so this is the box of its vertices bit for bit);
// - ball radii deepest level first: the farthest vertex from the node's centre, found by a
//   descent that skips a subtree when its ball, seen from that centre, cannot reach beyond the
//   farthest vertex found so far (|c − c_j| + r_j, with a relative margin of 1e-9 far above
//   the rounding of either side, so a skipped vertex's computed distance never exceeds the
//   maximum: the radius is the brute-force one exactly).
void compute_bounds(TriangleHierarchy& h) {
  const std::size_t N = h.nodes.size();
  std::vector<glm::dvec3> lo(N, glm::dvec3(kInfinity)), hi(N, glm::dvec3(-kInfinity));
  std::vector<uint32_t> depth(N, 0);
  uint32_t max_depth = 0;
  for (std::size_t i = 0; i < N; ++i) {  // parents precede children (depth-first order)
    const TriangleHierarchy::Node& node = h.nodes[i];
    if (node.count > 0) continue;
    depth[i + 1] = depth[node.second] = depth[i] + 1;
    max_depth = std::max(max_depth, depth[i] + 1);
  }
  tbb::parallel_for(std::size_t(0), N, [&](std::size_t i) {
    const TriangleHierarchy::Node& node = h.nodes[i];
    for (uint32_t j = node.first; j < node.first + node.count; ++j)
      for (int k = 0; k < 3; ++k) {
        lo[i] = glm::min(lo[i], h.vertex(h.order[j], k));
        hi[i] = glm::max(hi[i], h.vertex(h.order[j], k));
      }
  });
  for (std::size_t i = N; i-- > 0;) {
    TriangleHierarchy::Node& node = h.nodes[i];
    if (node.count == 0) {
      lo[i] = glm::min(lo[i + 1], lo[node.second]);
      hi[i] = glm::max(hi[i + 1], hi[node.second]);
    }
    node.box_center = 0.5 * (lo[i] + hi[i]);
    node.box_half = 0.5 * (hi[i] - lo[i]);
    node.ball_center = node.box_center;
  }
  // Nodes by depth, deepest first: a node's descendants have their radii when it is measured.
  std::vector<std::vector<uint32_t>> levels(max_depth + 1);
  for (std::size_t i = 0; i < N; ++i) levels[depth[i]].push_back(static_cast<uint32_t>(i));
  const auto reach = [&](uint32_t j, const glm::dvec3& c) {
    return glm::length(h.nodes[j].ball_center - c) + h.nodes[j].ball_radius;
  };
  for (std::size_t d = levels.size(); d-- > 0;) {
    const std::vector<uint32_t>& level = levels[d];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.size()), [&](const auto& range) {
      std::vector<uint32_t> stack(max_depth + 2);  // a descent holds ≤ 1 + depth entries
      for (std::size_t li = range.begin(); li != range.end(); ++li) {
        TriangleHierarchy::Node& node = h.nodes[level[li]];
        const glm::dvec3 c = node.ball_center;
        double r2 = 0.0, r = 0.0;
        std::size_t top = 0;
        stack[top++] = level[li];
        while (top > 0) {
          const uint32_t j = stack[--top];
          const TriangleHierarchy::Node& sub = h.nodes[j];
          if (j != level[li] && reach(j, c) * (1.0 + 1e-9) <= r)
            continue;            // every vertex of this subtree is within the farthest found so far
          if (sub.count == 0) {  // the child reaching farther is taken first
            const bool left_first = reach(j + 1, c) >= reach(sub.second, c);
            stack[top++] = left_first ? sub.second : j + 1;
            stack[top++] = left_first ? j + 1 : sub.second;
            continue;
          }
          for (uint32_t t = sub.first; t < sub.first + sub.count; ++t)
            for (int k = 0; k < 3; ++k) {
              const glm::dvec3 v = h.vertex(h.order[t], k) - c;
              r2 = std::max(r2, glm::dot(v, v));
            }
          r = std::sqrt(r2);
        }
        node.ball_radius = r;
      }
    });
  }
}

}  // namespace

TriangleHierarchy build_triangle_hierarchy(const scene::Scene& scene, HierarchyBuild mode) {
  TriangleHierarchy h;
  h.scene = &scene;
  const std::size_t V = scene.positions.size();
  const uint32_t T = static_cast<uint32_t>(scene.triangles.size());
  if (T == 0) return h;
  std::vector<uint32_t> vertex_primitive(V, 0);
  for (uint32_t p = 0; p < scene.primitives.size(); ++p) {
    const scene::ScenePrimitive& prim = scene.primitives[p];
    for (std::size_t v = prim.first_vertex; v < prim.first_vertex + prim.vertex_count && v < V; ++v)
      vertex_primitive[v] = p;
  }
  std::vector<uint32_t> primitive(T, 0);
  std::vector<glm::dvec3> centroid(T);
  h.order.resize(T);
  for (uint32_t t = 0; t < T; ++t) {
    h.order[t] = t;
    centroid[t] = (h.vertex(t, 0) + h.vertex(t, 1) + h.vertex(t, 2)) / 3.0;
    primitive[t] = vertex_primitive[scene.triangles[t].x];
  }
  std::stable_sort(h.order.begin(), h.order.end(),
                   [&](uint32_t a, uint32_t b) { return primitive[a] < primitive[b]; });
  h.nodes.reserve(2 * (T / TriangleHierarchy::kLeafTriangles) + 2);
  if (mode == HierarchyBuild::Serial) {
    Builder{h, primitive, centroid}.build(0, T);
  } else {
    ParallelBuilder b{h, primitive, centroid, {}};
    b.splits.resize(2 * static_cast<std::size_t>(T));  // ≤ 2T − 1 nodes: every leaf holds ≥ 1
    b.emit(b.split(0, T));
  }
  compute_bounds(h);
  return h;
}

}  // namespace prt::bake
