#include "scene/tangent_frames.h"

#include <cmath>

#include "scene/orthonormal_basis.h"

namespace prt::scene {
namespace {

// The unit tangent of t projected off the unit normal n, w = ±1; zero when unusable.
glm::vec4 orthogonalised(const glm::vec3& n, const glm::vec4& t) {
  const glm::dvec3 nd(n), td(t);
  const glm::dvec3 orthogonal = td - glm::dot(td, nd) * nd;
  const double length = glm::length(orthogonal);
  if (!(length > 1e-6) || !std::isfinite(length) || !std::isfinite(t.w)) return glm::vec4(0.f);
  return glm::vec4(glm::vec3(orthogonal / length), t.w < 0.0f ? -1.0f : 1.0f);
}

bool usable(const glm::vec4& t) {
  return t.x != 0.f || t.y != 0.f || t.z != 0.f;
}

// Turns the tangent of `frame` by r about n toward its bitangent.
glm::vec4 rotated(const glm::vec3& n, const glm::vec4& frame, float r) {
  const glm::dvec3 t(frame), b = double(frame.w) * glm::cross(glm::dvec3(n), t);
  const glm::dvec3 turned = std::cos(double(r)) * t + std::sin(double(r)) * b;
  return glm::vec4(glm::vec3(glm::normalize(turned)), frame.w);
}

}  // namespace

glm::vec4 normal_only_tangent(const glm::vec3& n) {
  glm::vec3 t, b;
  build_orthonormal_basis(n, t, b);
  return glm::vec4(glm::normalize(t), 1.0f);
}

std::vector<glm::vec4> uv_tangents(const Scene& scene) {
  const std::size_t n = scene.vertex_count();
  if (scene.texcoords.size() != n || scene.normals.size() != n) return {};
  std::vector<glm::dvec3> du(n, glm::dvec3(0.0)), dv(n, glm::dvec3(0.0));
  for (const glm::uvec3& tri : scene.triangles) {
    const glm::dvec3 p0(scene.positions[tri.x]);
    const glm::dvec3 e1 = glm::dvec3(scene.positions[tri.y]) - p0;
    const glm::dvec3 e2 = glm::dvec3(scene.positions[tri.z]) - p0;
    const glm::dvec2 q0(scene.texcoords[tri.x]);
    const glm::dvec2 f1 = glm::dvec2(scene.texcoords[tri.y]) - q0;
    const glm::dvec2 f2 = glm::dvec2(scene.texcoords[tri.z]) - q0;
    // e1 = f1.x dP/du + f1.y dP/dv, e2 = f2.x dP/du + f2.y dP/dv; det × the solution weights
    // each triangle by its UV area (with the sign of the UV orientation removed).
    const double det = f1.x * f2.y - f1.y * f2.x;
    if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;
    const double sign = det > 0.0 ? 1.0 : -1.0;
    const glm::dvec3 dpdu = sign * (e1 * f2.y - e2 * f1.y);
    const glm::dvec3 dpdv = sign * (e2 * f1.x - e1 * f2.x);
    for (uint32_t v : {tri.x, tri.y, tri.z}) {
      du[v] += dpdu;
      dv[v] += dpdv;
    }
  }
  std::vector<glm::vec4> out(n, glm::vec4(0.f));
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 normal = scene.normals[v];
    const glm::vec4 t = orthogonalised(normal, glm::vec4(glm::vec3(du[v]), 1.f));
    if (!usable(t)) continue;
    const double handed = glm::dot(glm::cross(glm::dvec3(normal), glm::dvec3(t)), dv[v]);
    out[v] = glm::vec4(glm::vec3(t), handed < 0.0 ? -1.f : 1.f);
  }
  return out;
}

std::vector<glm::vec4> tangent_frames(const Scene& scene) {
  const std::size_t n = scene.vertex_count();
  std::vector<glm::vec4> frames(n, glm::vec4(0.f));
  const bool from_file = scene.tangents.size() == n;
  std::vector<glm::vec4> from_uv;
  bool uv_tried = false;
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 normal = scene.normals[v];
    if (from_file) frames[v] = orthogonalised(normal, scene.tangents[v]);
    if (usable(frames[v])) continue;
    if (!uv_tried) {
      from_uv = uv_tangents(scene);
      uv_tried = true;
    }
    if (!from_uv.empty() && usable(from_uv[v])) {
      frames[v] = from_uv[v];
      continue;
    }
    frames[v] = normal_only_tangent(normal);
  }
  for (const ScenePrimitive& p : scene.primitives) {
    const bool per_vertex = p.anisotropy_rotation_of_vertex.size() == p.vertex_count;
    if (!per_vertex && p.anisotropy_rotation == 0.f) continue;
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count && v < n; ++v) {
      const float r =
          per_vertex ? p.anisotropy_rotation_of_vertex[v - p.first_vertex] : p.anisotropy_rotation;
      if (r != 0.f) frames[v] = rotated(scene.normals[v], frames[v], r);
    }
  }
  return frames;
}

}  // namespace prt::scene
