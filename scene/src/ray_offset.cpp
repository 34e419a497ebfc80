// scene/src/ray_offset.cpp — ray origins off surfaces by their rounding error (ray_offset.h).
#include "scene/ray_offset.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::scene {
namespace {

constexpr double kUlpsOfPoint = 4.0;           // × U(p): origin rounding plus margin
constexpr double kEdgeFraction = 0x1p-18;      // × L: 64 × 2^-24, the triangle test's error
constexpr double kFloatSpacing = 0x1p-23;      // ulp(x) ≤ 2^-23 · |x| for normal floats
constexpr double kOriginRoundingInUlps = 2.0;  // ≥ 1.73: two roundings of o, √3/2 ulp each

}  // namespace

double longest_edge(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return std::sqrt(
      std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)}));
}

float offset_as_float(double eps) {
  float eps_f = static_cast<float>(eps);
  if (static_cast<double>(eps_f) < eps) eps_f = std::nextafter(eps_f, INFINITY);
  return eps_f;
}

double float_spacing_bound(const glm::dvec3& p) {
  const double m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  // Subnormal coordinates have a fixed spacing: the smallest positive float.
  return std::max(kFloatSpacing * m, static_cast<double>(std::numeric_limits<float>::denorm_min()));
}

double ray_offset(const glm::dvec3& p, double local_edge) {
  const double edge = std::isfinite(local_edge) ? std::max(local_edge, 0.0) : 0.0;
  return kUlpsOfPoint * float_spacing_bound(p) + kEdgeFraction * edge;
}

double triangle_ray_offset(const Scene& scene, uint32_t triangle, const glm::dvec3& p) {
  const glm::uvec3 t = scene.triangles[triangle];
  const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
  const double spacing = std::max({float_spacing_bound(p), float_spacing_bound(a),
                                   float_spacing_bound(b), float_spacing_bound(c)});
  return kUlpsOfPoint * spacing + kEdgeFraction * longest_edge(a, b, c);
}

VertexRayStarts compute_vertex_ray_starts(const Scene& scene) {
  const std::size_t V = scene.positions.size();
  std::vector<double> edge(V, 0.0);
  for (const glm::uvec3& t : scene.triangles) {
    if (t.x >= V || t.y >= V || t.z >= V) continue;
    const double L =
        longest_edge(glm::dvec3(scene.positions[t.x]), glm::dvec3(scene.positions[t.y]),
                     glm::dvec3(scene.positions[t.z]));
    for (const uint32_t v : {t.x, t.y, t.z}) edge[v] = std::max(edge[v], L);
  }
  VertexRayStarts starts;
  starts.offset.resize(V);
  starts.unreachable_height.resize(V);
  for (std::size_t v = 0; v < V; ++v) {
    const glm::dvec3 p(scene.positions[v]);
    const double eps = ray_offset(p, edge[v]);
    starts.offset[v] = offset_as_float(eps);
    starts.unreachable_height[v] = 0.5 * (eps - kOriginRoundingInUlps * float_spacing_bound(p));
  }
  return starts;
}

double max_vertex_ray_offset(const Scene& scene) {
  // ε_v = 4·U(p_v) + k·L_v with L_v the largest L_t of v's triangles, so the largest ε_v is the
  // largest over the triangles of 4·max U(p_v) + k·L_t, and over every vertex of 4·U(p_v) (a
  // vertex on no triangle): each is rounded as ε_v is, and the roundings are monotone. A
  // non-finite L_t (which ε_v treats apart) falls back to the per-vertex computation.
  const std::size_t V = scene.positions.size();
  double largest = 0.0;
  for (std::size_t v = 0; v < V; ++v)
    largest = std::max(largest, ray_offset(glm::dvec3(scene.positions[v]), 0.0));
  for (const glm::uvec3& t : scene.triangles) {
    if (t.x >= V || t.y >= V || t.z >= V) continue;
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    const double L = longest_edge(a, b, c);
    if (!std::isfinite(L)) {
      float m = 0.f;
      for (const float eps : compute_vertex_ray_starts(scene).offset) m = std::max(m, eps);
      return static_cast<double>(m);
    }
    const double spacing =
        std::max({float_spacing_bound(a), float_spacing_bound(b), float_spacing_bound(c)});
    largest = std::max(largest, kUlpsOfPoint * spacing + kEdgeFraction * L);
  }
  return static_cast<double>(offset_as_float(largest));
}

}  // namespace prt::scene
