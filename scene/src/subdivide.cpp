#include "scene/subdivide.h"

#include "triangle_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace prt::scene {
namespace {

// Segments of edge (u, w): ⌈length / max_edge⌉, at least 1 (the same from either side), in
// double: it may be far beyond int when max_edge is tiny (refused by the caller's count).
double edge_segments(const Scene& scene, uint32_t u, uint32_t w, double max_edge) {
  const double length =
      glm::length(glm::dvec3(scene.positions[w]) - glm::dvec3(scene.positions[u]));
  return std::max(1.0, std::ceil(length / max_edge - 1e-9));
}

// Builds the vertices and triangles of one primitive into `out`.
class PrimitiveSplitter {
 public:
  PrimitiveSplitter(const Scene& in, Scene& out) : in_(in), out_(out) {}

  void split(const glm::uvec3& t, const std::array<int, 3>& k, double max_edge,
             uint32_t vertex_shift) {
    const uint32_t corner[3] = {t.x, t.y, t.z};
    const auto at = [&](uint32_t v) { return glm::dvec3(in_.positions[v]); };
    const detail::Tessellation tess =
        detail::tessellate_triangle(at(corner[0]), at(corner[1]), at(corner[2]), k, max_edge);
    // Every local point's barycentric weights on (a, b, c), and its output vertex.
    std::vector<glm::dvec3> weight(tess.point_count(), glm::dvec3(0.0));
    std::vector<uint32_t> ids(tess.point_count(), 0);
    for (int e = 0; e < 3; ++e) {
      ids[e] = corner[e] + vertex_shift;
      for (int m = 1; m < k[e]; ++m)
        ids[tess.edge_point(e, m)] = edge_vertex(corner[e], corner[(e + 1) % 3], k[e], m);
    }
    const int n = tess.n;
    for (int j = 1; j <= n - 2; ++j) {
      for (int i = 1; i + j <= n - 1; ++i) {
        const double w1 = double(i) / n, w2 = double(j) / n;
        weight[tess.lattice_point(i, j)] = glm::dvec3(1.0 - w1 - w2, w1, w2);
      }
    }
    const std::size_t first_midpoint = tess.point_count() - tess.midpoints.size();
    for (int e = 0; e < 3; ++e) {  // edge points' weights, for the midpoints' parents
      weight[e][e] = 1.0;
      for (int m = 1; m < k[e]; ++m) {
        weight[tess.edge_point(e, m)][e] = 1.0 - double(m) / k[e];
        weight[tess.edge_point(e, m)][(e + 1) % 3] = double(m) / k[e];
      }
    }
    for (std::size_t q = 0; q < tess.midpoints.size(); ++q)
      weight[first_midpoint + q] =
          0.5 * (weight[tess.midpoints[q][0]] + weight[tess.midpoints[q][1]]);
    for (std::size_t q = 3 + (k[0] - 1) + (k[1] - 1) + (k[2] - 1); q < ids.size(); ++q)
      ids[q] = add(corner[0], corner[1], corner[2], weight[q].x, weight[q].y, weight[q].z);
    for (const glm::ivec3& tri : tess.triangles)
      out_.triangles.emplace_back(ids[tri.x], ids[tri.y], ids[tri.z]);
  }

 private:
  // Point m of k from u toward w: one vertex per edge of the primitive, and its position
  // computed from the endpoints in a canonical order (by position), so that any two triangles
  // with these endpoints, in this primitive or another, get bit-identical points.
  uint32_t edge_vertex(uint32_t u, uint32_t w, int k, int m) {
    const glm::vec3 pu = in_.positions[u], pw = in_.positions[w];
    if (std::tie(pw.x, pw.y, pw.z, w) < std::tie(pu.x, pu.y, pu.z, u)) {
      std::swap(u, w);
      m = k - m;
    }
    const auto key = std::make_tuple(u, w, k, m);
    const auto found = edges_.find(key);
    if (found != edges_.end()) return found->second;
    const double s = double(m) / k;
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
  std::vector<std::array<int, 3>> splits(scene.triangles.size());
  double total = 0.0;  // counted in double, checked before any count becomes an int
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3& tri = scene.triangles[t];
    const double k0 = edge_segments(scene, tri.x, tri.y, max_edge);
    const double k1 = edge_segments(scene, tri.y, tri.z, max_edge);
    const double k2 = edge_segments(scene, tri.z, tri.x, max_edge);
    total += detail::tessellation_triangle_count({k0, k1, k2});
    if (total <= double(kMaxSubdividedTriangles))
      splits[t] = {static_cast<int>(k0), static_cast<int>(k1), static_cast<int>(k2)};
  }
  if (!(total <= double(kMaxSubdividedTriangles))) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "--max-edge %g would make %.3g triangles (at most %zu): use a longer edge",
                  max_edge, total, kMaxSubdividedTriangles);
    throw std::invalid_argument(text);
  }
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
      splitter.split(scene.triangles[t], splits[t], max_edge, shift);
    }
    p.vertex_count = static_cast<uint32_t>(out.positions.size()) - p.first_vertex;
    p.triangle_count = static_cast<uint32_t>(out.triangles.size()) - p.first_triangle;
    out.primitives.push_back(std::move(p));
  }
  return out;
}

}  // namespace prt::scene

namespace prt::scene {
namespace {

// The working mesh of refine_triangles: triangles are split in place (dead ones keep their
// children), edges map to the live triangles on them.
class Bisector {
 public:
  explicit Bisector(const Scene& in) : in_(in) {
    positions_.assign(in.positions.begin(), in.positions.end());
    normals_.assign(in.normals.begin(), in.normals.end());
    albedo_.assign(in.albedo.begin(), in.albedo.end());
    vertex_primitive_.assign(in.positions.size(), kNone);
    for (uint32_t p = 0; p < in.primitives.size(); ++p) {
      const ScenePrimitive& prim = in.primitives[p];
      for (uint32_t k = 0; k < prim.triangle_count; ++k) {
        const uint32_t t = prim.first_triangle + k;
        if (t < in.triangles.size()) add_triangle(in.triangles[t], p, 0);
      }
    }
  }

  // The working triangle of input triangle t (the input's order within each primitive).
  uint32_t root(uint32_t t) const { return roots_.at(t); }
  void record_root(uint32_t input, uint32_t working) { roots_[input] = working; }
  std::size_t size() const { return tris_.size(); }
  bool alive(uint32_t t) const { return children_[t][0] == kNone; }
  const std::array<uint32_t, 2>& children(uint32_t t) const { return children_[t]; }
  int depth(uint32_t t) const { return depth_[t]; }

  void bisect(uint32_t t) {
    for (;;) {
      const int k = longest_edge(t);
      const uint32_t a = tris_[t][k], b = tris_[t][(k + 1) % 3];
      const uint32_t n = neighbour(t, a, b);
      if (n != kNone) {
        const int kn = longest_edge(n);
        const uint32_t na = tris_[n][kn], nb = tris_[n][(kn + 1) % 3];
        if (!((na == b && nb == a) || (na == a && nb == b))) {
          bisect(n);  // until the shared edge is n's longest too
          continue;
        }
      }
      const uint32_t m = midpoint(a, b, primitive_[t]);
      split(t, k, m);
      if (n != kNone) split(n, index_of(n, b), m);
      return;
    }
  }

  Scene assemble(std::vector<uint32_t>* parent) const;

  static constexpr uint32_t kNone = 0xFFFFFFFFu;

 private:
  using EdgeKey = std::tuple<uint32_t, uint32_t, uint32_t>;  // primitive, lower, higher id
  EdgeKey key(uint32_t a, uint32_t b, uint32_t p) const {
    return {p, std::min(a, b), std::max(a, b)};
  }

  uint32_t add_triangle(const glm::uvec3& v, uint32_t primitive, int depth) {
    const uint32_t t = static_cast<uint32_t>(tris_.size());
    tris_.push_back(v);
    primitive_.push_back(primitive);
    depth_.push_back(depth);
    children_.push_back({kNone, kNone});
    for (int k = 0; k < 3; ++k) edges_[key(v[k], v[(k + 1) % 3], primitive)].push_back(t);
    return t;
  }

  void remove_edges(uint32_t t) {
    for (int k = 0; k < 3; ++k) {
      std::vector<uint32_t>& on = edges_[key(tris_[t][k], tris_[t][(k + 1) % 3], primitive_[t])];
      on.erase(std::remove(on.begin(), on.end(), t), on.end());
    }
  }

  double length2(uint32_t a, uint32_t b) const {
    const glm::dvec3 d = glm::dvec3(positions_[a]) - glm::dvec3(positions_[b]);
    return glm::dot(d, d);
  }

  // Edge k runs from corner k to corner k + 1; ties go to the smaller (lower, higher) ids.
  int longest_edge(uint32_t t) const {
    int best = 0;
    for (int k = 1; k < 3; ++k) {
      const uint32_t a = tris_[t][k], b = tris_[t][(k + 1) % 3];
      const uint32_t ba = tris_[t][best], bb = tris_[t][(best + 1) % 3];
      const double l = length2(a, b), lb = length2(ba, bb);
      if (l > lb || (l == lb && std::make_pair(std::min(a, b), std::max(a, b)) <
                                    std::make_pair(std::min(ba, bb), std::max(ba, bb))))
        best = k;
    }
    return best;
  }

  int index_of(uint32_t t, uint32_t v) const {
    return tris_[t][0] == v ? 0 : tris_[t][1] == v ? 1 : 2;
  }

  uint32_t neighbour(uint32_t t, uint32_t a, uint32_t b) const {
    const auto found = edges_.find(key(a, b, primitive_[t]));
    if (found == edges_.end()) return kNone;
    for (uint32_t u : found->second)
      if (u != t) return u;
    return kNone;
  }

  uint32_t midpoint(uint32_t a, uint32_t b, uint32_t primitive) {
    const EdgeKey k = key(a, b, primitive);
    const auto found = midpoints_.find(k);
    if (found != midpoints_.end()) return found->second;
    positions_.push_back(0.5f * (positions_[a] + positions_[b]));
    const glm::vec3 n = normals_[a] + normals_[b];
    normals_.push_back(glm::length(n) > 0.f ? glm::normalize(n) : normals_[a]);
    albedo_.push_back(0.5f * (albedo_[a] + albedo_[b]));
    vertex_primitive_.push_back(primitive);
    const uint32_t m = static_cast<uint32_t>(positions_.size() - 1);
    midpoints_.emplace(k, m);
    return m;
  }

  // Splits t at midpoint m of its edge k: (a, m, c) and (m, b, c) keep the winding.
  void split(uint32_t t, int k, uint32_t m) {
    const uint32_t a = tris_[t][k], b = tris_[t][(k + 1) % 3], c = tris_[t][(k + 2) % 3];
    remove_edges(t);
    const uint32_t first = add_triangle({a, m, c}, primitive_[t], depth_[t] + 1);
    const uint32_t second = add_triangle({m, b, c}, primitive_[t], depth_[t] + 1);
    children_[t] = {first, second};
  }

  const Scene& in_;
  std::vector<glm::vec3> positions_, normals_, albedo_;
  std::vector<uint32_t> vertex_primitive_;  // new vertices: their primitive
  std::vector<glm::uvec3> tris_;
  std::vector<uint32_t> primitive_;
  std::vector<int> depth_;
  std::vector<std::array<uint32_t, 2>> children_;
  std::map<EdgeKey, std::vector<uint32_t>> edges_;
  std::map<EdgeKey, uint32_t> midpoints_;
  std::map<uint32_t, uint32_t> roots_;
};

Scene Bisector::assemble(std::vector<uint32_t>* parent) const {
  Scene out;
  out.cameras = in_.cameras;
  out.source_path = in_.source_path;
  out.skipped_degenerate_triangles = in_.skipped_degenerate_triangles;
  out.computed_normal_vertices = in_.computed_normal_vertices;
  if (parent) parent->clear();
  std::vector<uint32_t> remap(positions_.size(), kNone);
  const auto push_vertex = [&](uint32_t v) {
    remap[v] = static_cast<uint32_t>(out.positions.size());
    out.positions.push_back(positions_[v]);
    out.normals.push_back(normals_[v]);
    out.albedo.push_back(albedo_[v]);
  };
  for (uint32_t p = 0; p < in_.primitives.size(); ++p) {
    const ScenePrimitive& primitive = in_.primitives[p];
    ScenePrimitive prim = primitive;
    prim.first_vertex = static_cast<uint32_t>(out.positions.size());
    prim.first_triangle = static_cast<uint32_t>(out.triangles.size());
    for (uint32_t v = 0; v < primitive.vertex_count; ++v) push_vertex(primitive.first_vertex + v);
    for (uint32_t v = static_cast<uint32_t>(in_.positions.size()); v < positions_.size(); ++v)
      if (vertex_primitive_[v] == p) push_vertex(v);
    for (uint32_t k = 0; k < primitive.triangle_count; ++k) {
      const uint32_t input = primitive.first_triangle + k;
      if (roots_.find(input) == roots_.end()) continue;
      std::vector<uint32_t> stack = {root(input)};
      while (!stack.empty()) {  // depth first, first child first
        const uint32_t t = stack.back();
        stack.pop_back();
        if (!alive(t)) {
          stack.push_back(children_[t][1]);
          stack.push_back(children_[t][0]);
          continue;
        }
        out.triangles.emplace_back(remap[tris_[t].x], remap[tris_[t].y], remap[tris_[t].z]);
        if (parent) parent->push_back(input);
      }
    }
    prim.vertex_count = static_cast<uint32_t>(out.positions.size()) - prim.first_vertex;
    prim.triangle_count = static_cast<uint32_t>(out.triangles.size()) - prim.first_triangle;
    out.primitives.push_back(std::move(prim));
  }
  return out;
}

}  // namespace

Scene refine_triangles(const Scene& scene, const std::vector<bool>& marked, int levels,
                       std::vector<uint32_t>* parent) {
  if (marked.size() != scene.triangles.size())
    throw std::invalid_argument("refine_triangles: one mark per triangle needed");
  if (levels < 1 || levels > 8)
    throw std::invalid_argument("refine_triangles: levels must be in 1..8");
  Bisector mesh(scene);
  // The working triangles were created in primitive order: map input triangles to them.
  uint32_t working = 0;
  for (const ScenePrimitive& prim : scene.primitives)
    for (uint32_t k = 0; k < prim.triangle_count; ++k)
      if (prim.first_triangle + k < scene.triangles.size())
        mesh.record_root(prim.first_triangle + k, working++);
  for (int level = 1; level <= levels; ++level) {
    for (uint32_t t = 0; t < marked.size(); ++t) {
      if (!marked[t] || scene.primitive_of_triangle(t) == nullptr) continue;
      // Bisect every live piece of t that is not yet `level` bisections deep.
      std::vector<uint32_t> stack = {mesh.root(t)};
      while (!stack.empty()) {
        const uint32_t u = stack.back();
        stack.pop_back();
        if (!mesh.alive(u)) {
          stack.push_back(mesh.children(u)[0]);
          stack.push_back(mesh.children(u)[1]);
        } else if (mesh.depth(u) < level) {
          mesh.bisect(u);
        }
      }
    }
  }
  return mesh.assemble(parent);
}

}  // namespace prt::scene
