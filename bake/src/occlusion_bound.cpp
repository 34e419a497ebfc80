// bake/src/occlusion_bound.cpp — the ray-free occlusion bound (occlusion_bound.h).
#include "bake/occlusion_bound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "bake/ray_caster.h"

namespace prt::bake {
namespace {

constexpr int kLeafTriangles = 8;
constexpr double kAcceptRatio = 0.25;  // accept a group's ball when r/d ≤ this
constexpr double kInfinity = std::numeric_limits<double>::infinity();

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
  std::vector<uint32_t> order;  // triangle indices, grouped by primitive
  std::vector<uint32_t> primitive;  // per triangle (by its first vertex)
  std::vector<glm::dvec3> centroid;
  std::vector<Node> nodes;

  glm::dvec3 vertex(uint32_t t, int i) const {
    return glm::dvec3(scene->positions[scene->triangles[t][i]]);
  }

  uint32_t build(uint32_t first, uint32_t count) {
    glm::dvec3 lo(kInfinity), hi(-kInfinity), clo(kInfinity), chi(-kInfinity);
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
      std::nth_element(order.begin() + first, order.begin() + first + half,
                       order.begin() + first + count, [&](uint32_t a, uint32_t b) {
                         return centroid[a][axis] < centroid[b][axis];
                       });
    }
    nodes[index].count = 0;
    build(first, half);
    const uint32_t second = build(first + half, count - half);
    nodes[index].second = second;
    return index;
  }
};

// Bound of one triangle as seen from p: 0 when it lies within τ of the tangent plane.
double triangle_bound(const Scene& scene, uint32_t t, const glm::dvec3& p, const glm::dvec3& n,
                      double threshold, double inflate) {
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

double occlusion_bound_brute_force(const Scene& scene, std::size_t vertex, double threshold) {
  const glm::dvec3 p(scene.positions[vertex]);
  const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[vertex]));
  const double inflate = 2.0 * static_cast<double>(ray_offset_scale(scene));
  double sum = 0.0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t)
    sum += triangle_bound(scene, t, p, n, threshold, inflate);
  return sum;
}

OcclusionBounds bound_occlusion(const Scene& scene, double threshold, double cutoff,
                                const std::vector<uint8_t>& skip) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t V = scene.positions.size();
  OcclusionBounds result;
  result.bound.assign(V, 0.f);
  TriangleHierarchy h;
  h.scene = &scene;
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
  const double inflate = 2.0 * static_cast<double>(ray_offset_scale(scene));
  tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
    if (!skip.empty() && skip[v]) return;
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
      const glm::dvec3 to_center = node.ball.center - p;
      const double r = node.ball.radius + inflate, d = glm::length(to_center);
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
