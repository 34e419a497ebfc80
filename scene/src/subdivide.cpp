#include "scene/subdivide.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace prt::scene {
namespace {

int split_count(const Scene& scene, const glm::uvec3& t, double max_edge) {
  const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
  const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
  return std::max(1, static_cast<int>(std::ceil(longest / max_edge - 1e-9)));
}

// Builds the vertices and triangles of one primitive into `out`.
class PrimitiveSplitter {
 public:
  PrimitiveSplitter(const Scene& in, Scene& out) : in_(in), out_(out) {}

  void split(const glm::uvec3& t, int n, uint32_t vertex_shift) {
    const uint32_t corner[3] = {t.x, t.y, t.z};
    // Each lattice point once: ids[j * (n + 1) + i].
    std::vector<uint32_t> ids(static_cast<std::size_t>(n + 1) * (n + 1), 0);
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i + j <= n; ++i) ids[j * (n + 1) + i] = vertex(corner, n, i, j, vertex_shift);
    const auto id = [&](int i, int j) { return ids[j * (n + 1) + i]; };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i + j < n; ++i) {
        out_.triangles.emplace_back(id(i, j), id(i + 1, j), id(i, j + 1));
        if (i + j < n - 1)
          out_.triangles.emplace_back(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  }

 private:
  // Output index of lattice point (i, j) of the triangle with input corners `corner`.
  uint32_t vertex(const uint32_t corner[3], int n, int i, int j, uint32_t shift) {
    if (i == 0 && j == 0) return corner[0] + shift;
    if (i == n) return corner[1] + shift;
    if (j == n) return corner[2] + shift;
    if (j == 0) return edge_vertex(corner[0], corner[1], n, i);
    if (i == 0) return edge_vertex(corner[0], corner[2], n, j);
    if (i + j == n) return edge_vertex(corner[1], corner[2], n, j);
    const double w1 = double(i) / n, w2 = double(j) / n;
    return add(corner[0], corner[1], corner[2], 1.0 - w1 - w2, w1, w2);
  }

  // The point k/n of the way from u to w, shared with the neighbour across edge (u, w).
  uint32_t edge_vertex(uint32_t u, uint32_t w, int n, int k) {
    if (u > w) {
      std::swap(u, w);
      k = n - k;
    }
    const auto key = std::make_tuple(u, w, n, k);
    const auto found = edges_.find(key);
    if (found != edges_.end()) return found->second;
    const double s = double(k) / n;
    const uint32_t v = add(u, w, w, 1.0 - s, s, 0.0);
    edges_.emplace(key, v);
    return v;
  }

  uint32_t add(uint32_t a, uint32_t b, uint32_t c, double wa, double wb, double wc) {
    const auto mix = [&](const std::vector<glm::vec3>& x) {
      return glm::dvec3(x[a]) * wa + glm::dvec3(x[b]) * wb + glm::dvec3(x[c]) * wc;
    };
    out_.positions.emplace_back(glm::vec3(mix(in_.positions)));
    const glm::dvec3 n = mix(in_.normals);
    const double length = glm::length(n);
    out_.normals.emplace_back(length > 0.0 ? glm::vec3(n / length) : in_.normals[a]);
    out_.albedo.emplace_back(glm::vec3(mix(in_.albedo)));
    if (!in_.texcoords.empty()) {
      const auto mix2 = [&](const std::vector<glm::vec2>& x) {
        return glm::dvec2(x[a]) * wa + glm::dvec2(x[b]) * wb + glm::dvec2(x[c]) * wc;
      };
      out_.texcoords.emplace_back(glm::vec2(mix2(in_.texcoords)));
    }
    if (!in_.tangents.empty()) out_.tangents.push_back(tangent(a, b, c, wa, wb, wc));
    return static_cast<uint32_t>(out_.positions.size() - 1);
  }

  // The interpolated file tangent (renormalised), w of the corner with the largest weight;
  // zero ("missing", scene/tangent_frames.h) when a corner has none or they cancel.
  glm::vec4 tangent(uint32_t a, uint32_t b, uint32_t c, double wa, double wb, double wc) const {
    const glm::vec4 ta = in_.tangents[a], tb = in_.tangents[b], tc = in_.tangents[c];
    if (ta.w == 0.f || (wb > 0.0 && tb.w == 0.f) || (wc > 0.0 && tc.w == 0.f))
      return glm::vec4(0.f);
    const glm::dvec3 t = glm::dvec3(ta) * wa + glm::dvec3(tb) * wb + glm::dvec3(tc) * wc;
    const double length = glm::length(t);
    if (!(length > 1e-9)) return glm::vec4(0.f);
    const float w = wa >= wb && wa >= wc ? ta.w : (wb >= wc ? tb.w : tc.w);
    return glm::vec4(glm::vec3(t / length), w);
  }

  const Scene& in_;
  Scene& out_;
  std::map<std::tuple<uint32_t, uint32_t, int, int>, uint32_t> edges_;
};

}  // namespace

Scene subdivide_to_edge_length(const Scene& scene, double max_edge) {
  if (!(max_edge > 0.0) || !std::isfinite(max_edge))
    throw std::invalid_argument("--max-edge " + std::to_string(max_edge) +
                                ": the target edge length must be a finite positive number");
  std::vector<int> splits(scene.triangles.size());
  double total = 0.0;
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    splits[t] = split_count(scene, scene.triangles[t], max_edge);
    total += double(splits[t]) * splits[t];
  }
  if (total > double(kMaxSubdividedTriangles))
    throw std::invalid_argument("--max-edge " + std::to_string(max_edge) + " would make " +
                                std::to_string(static_cast<long long>(total)) +
                                " triangles (at most " + std::to_string(kMaxSubdividedTriangles) +
                                "): use a longer edge");
  Scene out;
  out.cameras = scene.cameras;
  out.source_path = scene.source_path;
  out.skipped_degenerate_triangles = scene.skipped_degenerate_triangles;
  out.computed_normal_vertices = scene.computed_normal_vertices;
  for (const ScenePrimitive& primitive : scene.primitives) {
    ScenePrimitive p = primitive;
    p.first_vertex = static_cast<uint32_t>(out.positions.size());
    p.first_triangle = static_cast<uint32_t>(out.triangles.size());
    const uint32_t shift = p.first_vertex - primitive.first_vertex;
    for (uint32_t v = 0; v < primitive.vertex_count; ++v) {
      const uint32_t src = primitive.first_vertex + v;
      out.positions.push_back(scene.positions[src]);
      out.normals.push_back(scene.normals[src]);
      out.albedo.push_back(scene.albedo[src]);
      if (!scene.texcoords.empty()) out.texcoords.push_back(scene.texcoords[src]);
      if (!scene.tangents.empty()) out.tangents.push_back(scene.tangents[src]);
    }
    PrimitiveSplitter splitter(scene, out);
    for (uint32_t k = 0; k < primitive.triangle_count; ++k) {
      const uint32_t t = primitive.first_triangle + k;
      splitter.split(scene.triangles[t], splits[t], shift);
    }
    p.vertex_count = static_cast<uint32_t>(out.positions.size()) - p.first_vertex;
    p.triangle_count = static_cast<uint32_t>(out.triangles.size()) - p.first_triangle;
    out.primitives.push_back(std::move(p));
  }
  return out;
}

}  // namespace prt::scene
