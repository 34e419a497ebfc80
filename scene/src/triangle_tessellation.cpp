#include "triangle_tessellation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace prt::scene::detail {

std::size_t Tessellation::point_count() const {
  const std::size_t inner = n >= 3 ? std::size_t(n - 1) * std::size_t(n - 2) / 2 : 0;
  return 3 + std::size_t(k[0] - 1) + std::size_t(k[1] - 1) + std::size_t(k[2] - 1) + inner +
         midpoints.size();
}

int Tessellation::edge_point(int e, int m) const {
  int first = 3;
  for (int f = 0; f < e; ++f) first += k[f] - 1;
  return first + m - 1;
}

int Tessellation::lattice_point(int i, int j) const {
  // Rows j = 1 … n − 2, row j holding i = 1 … n − 1 − j.
  const int first = 3 + (k[0] - 1) + (k[1] - 1) + (k[2] - 1);
  const int before = (j - 1) * (n - 1) - (j - 1) * j / 2;  // Σ_{r<j} (n − 1 − r)
  return first + before + (i - 1);
}

double tessellation_triangle_count(std::array<double, 3> k) {
  const double n = std::max({k[0], k[1], k[2]});
  return double(k[0]) + k[1] + k[2] + (n - 1.0) * (n - 2.0) - 2.0;
}

namespace {

double cross2(const glm::dvec2& u, const glm::dvec2& v) {
  return u.x * v.y - u.y * v.x;
}

// Lawson's flips on a triangulation of a convex polygon (boundary edges have one triangle).
class Flipper {
 public:
  Flipper(std::vector<glm::dvec2>& p, std::vector<glm::ivec3>& tris) : p_(p), tris_(tris) {
    edges_.reserve(tris.size() * 2);
    for (int t = 0; t < int(tris.size()); ++t)
      for (int c = 0; c < 3; ++c) attach(tris[t][c], tris[t][(c + 1) % 3], t);
  }

  void run() {
    std::vector<uint64_t> stack;
    stack.reserve(edges_.size());
    for (const auto& [key, on] : edges_)
      if (on[1] >= 0) stack.push_back(key);
    std::sort(stack.begin(), stack.end());  // a fixed order: results do not depend on hashing
    legalize(stack);
  }

  // Splits interior edges longer than max_length at their midpoints (in rounds: every long
  // edge of the round, longest first, the Delaunay property restored after each split),
  // recording each new point's two parents.
  void split_long_edges(double max_length, std::vector<std::array<int, 2>>& parents) {
    for (int round = 0; round < 64; ++round) {
      std::vector<std::pair<double, uint64_t>> long_edges;
      for (const auto& [key, on] : edges_) {
        if (on[1] < 0) continue;
        const double l = glm::length(p_[int(key >> 32)] - p_[int(key & 0xFFFFFFFFu)]);
        if (l > max_length) long_edges.emplace_back(-l, key);
      }
      if (long_edges.empty()) return;
      std::sort(long_edges.begin(), long_edges.end());  // longest first, then by key
      for (const auto& [minus_length, key] : long_edges) {
        const auto found = edges_.find(key);  // flips may have removed it meanwhile
        if (found == edges_.end() || found->second[1] < 0) continue;
        const int u = int(key >> 32), v = int(key & 0xFFFFFFFFu);
        parents.push_back({u, v});
        std::vector<uint64_t> stack;
        split(u, v, stack);
        legalize(stack);
      }
    }
  }

 private:
  void legalize(std::vector<uint64_t>& stack) {
    // Each flip raises the smallest angle of its quad; the guard only stops a float cycle.
    std::size_t guard = 50 * tris_.size() + 100;
    while (!stack.empty() && guard-- > 0) {
      const uint64_t key = stack.back();
      stack.pop_back();
      const auto found = edges_.find(key);
      if (found == edges_.end() || found->second[1] < 0) continue;
      flip_if_illegal(int(key >> 32), int(key & 0xFFFFFFFFu), found->second, stack);
    }
  }

  // Inserts the midpoint m of interior edge (u, v): (u, v, p), (v, u, q) become (u, m, p),
  // (m, v, p), (v, m, q), (m, u, q).
  void split(int u, int v, std::vector<uint64_t>& stack) {
    const std::array<int, 2> on = edges_.at(key(u, v));
    int t1 = on[0], t2 = on[1];
    if (!runs(t1, u, v)) std::swap(t1, t2);
    const int p = opposite(t1, u, v), q = opposite(t2, u, v);
    const int m = int(p_.size());
    p_.push_back(0.5 * (p_[u] + p_[v]));
    const int t3 = int(tris_.size()), t4 = t3 + 1;
    tris_[t1] = glm::ivec3(u, m, p);
    tris_[t2] = glm::ivec3(v, m, q);
    tris_.emplace_back(m, v, p);
    tris_.emplace_back(m, u, q);
    edges_.erase(key(u, v));
    replace(v, p, t1, t3);
    replace(u, q, t2, t4);
    edges_[key(u, m)] = {t1, t4};
    edges_[key(m, v)] = {t3, t2};
    edges_[key(m, p)] = {t1, t3};
    edges_[key(m, q)] = {t2, t4};
    for (const uint64_t e : {key(u, p), key(p, v), key(v, q), key(q, u)}) stack.push_back(e);
  }

  static uint64_t key(int u, int v) {
    return (uint64_t(uint32_t(std::min(u, v))) << 32) | uint32_t(std::max(u, v));
  }
  void attach(int u, int v, int t) {
    auto& on = edges_.try_emplace(key(u, v), std::array<int, 2>{-1, -1}).first->second;
    (on[0] < 0 ? on[0] : on[1]) = t;
  }
  void replace(int u, int v, int from, int to) {
    auto& on = edges_.at(key(u, v));
    (on[0] == from ? on[0] : on[1]) = to;
  }
  // The corner of triangle t that is neither u nor v.
  int opposite(int t, int u, int v) const {
    for (int c = 0; c < 3; ++c)
      if (tris_[t][c] != u && tris_[t][c] != v) return tris_[t][c];
    return -1;
  }
  // Triangle t rotated so that it reads (u, v, ·) in its winding, or false.
  bool runs(int t, int u, int v) const {
    for (int c = 0; c < 3; ++c)
      if (tris_[t][c] == u && tris_[t][(c + 1) % 3] == v) return true;
    return false;
  }

  // Edge (u, v) between triangles (u, v, p) and (v, u, q): illegal when the angles at p and q
  // sum to more than π, i.e. sin(α + β) < 0 (by a relative margin, so cocircular quads stay).
  void flip_if_illegal(int u, int v, std::array<int, 2> on, std::vector<uint64_t>& stack) {
    int t1 = on[0], t2 = on[1];
    if (!runs(t1, u, v)) std::swap(t1, t2);
    if (!runs(t1, u, v) || !runs(t2, v, u)) return;
    const int p = opposite(t1, u, v), q = opposite(t2, u, v);
    const glm::dvec2 pu = p_[u] - p_[p], pv = p_[v] - p_[p];
    const glm::dvec2 qv = p_[v] - p_[q], qu = p_[u] - p_[q];
    const double sin_a = cross2(pu, pv), cos_a = glm::dot(pu, pv);
    const double sin_b = cross2(qv, qu), cos_b = glm::dot(qv, qu);
    const double scale = glm::length(pu) * glm::length(pv) * glm::length(qv) * glm::length(qu);
    if (!(sin_a * cos_b + cos_a * sin_b < -1e-10 * scale)) return;
    // The new triangles (u, q, p) and (q, v, p) must be properly oriented (a convex quad).
    if (!(cross2(p_[q] - p_[u], p_[p] - p_[u]) > 0.0) ||
        !(cross2(p_[v] - p_[q], p_[p] - p_[q]) > 0.0))
      return;
    tris_[t1] = glm::ivec3(u, q, p);
    tris_[t2] = glm::ivec3(q, v, p);
    edges_.erase(key(u, v));
    replace(u, q, t2, t1);
    replace(v, p, t1, t2);
    edges_[key(p, q)] = {t1, t2};
    for (const uint64_t e : {key(u, q), key(q, v), key(v, p), key(p, u)}) stack.push_back(e);
  }

  std::vector<glm::dvec2>& p_;
  std::vector<glm::ivec3>& tris_;
  std::unordered_map<uint64_t, std::array<int, 2>> edges_;
};

// Zips the strip between `outer` and the parallel, shorter row `inner` (both in the same
// direction, the strip on the left of `outer`): at each step the shorter new diagonal.
void zip(const std::vector<glm::dvec2>& p, const std::vector<int>& outer,
         const std::vector<int>& inner, std::vector<glm::ivec3>& tris) {
  std::size_t i = 0, j = 0;
  while (i + 1 < outer.size() || j + 1 < inner.size()) {
    bool advance_outer = j + 1 >= inner.size();
    if (i + 1 < outer.size() && j + 1 < inner.size())
      advance_outer =
          glm::length(p[outer[i + 1]] - p[inner[j]]) <= glm::length(p[outer[i]] - p[inner[j + 1]]);
    if (advance_outer) {
      tris.emplace_back(outer[i], outer[i + 1], inner[j]);
      ++i;
    } else {
      tris.emplace_back(outer[i], inner[j + 1], inner[j]);
      ++j;
    }
  }
}

// Ear clipping of a convex polygon (counter-clockwise, collinear points allowed): clips a
// corner whose ear is not flat.
void clip_ears(const std::vector<glm::dvec2>& p, std::vector<int> polygon,
               std::vector<glm::ivec3>& tris) {
  while (polygon.size() > 3) {
    const std::size_t m = polygon.size();
    std::size_t best = 0;
    double best_area = -1.0;
    for (std::size_t c = 0; c < m; ++c) {
      const int u = polygon[(c + m - 1) % m], v = polygon[c], w = polygon[(c + 1) % m];
      const double area = cross2(p[v] - p[u], p[w] - p[u]);
      if (area > best_area) best_area = area, best = c;
    }
    tris.emplace_back(polygon[(best + m - 1) % m], polygon[best], polygon[(best + 1) % m]);
    polygon.erase(polygon.begin() + std::ptrdiff_t(best));
  }
  tris.emplace_back(polygon[0], polygon[1], polygon[2]);
}

}  // namespace

Tessellation tessellate_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                 std::array<int, 3> k, double max_edge) {
  Tessellation t;
  t.k = k;
  t.n = std::max({k[0], k[1], k[2]});
  const int n = t.n;
  // The plane of the triangle: a at the origin, b on the x axis.
  const glm::dvec3 ab = b - a, ac = c - a;
  const double lab = glm::length(ab);
  const glm::dvec3 ex = lab > 0.0 ? ab / lab : glm::dvec3(1, 0, 0);
  const glm::dvec3 normal = glm::cross(ab, ac);
  const glm::dvec3 ey =
      glm::length(normal) > 0.0 ? glm::normalize(glm::cross(normal, ab)) : glm::dvec3(0, 1, 0);
  const std::array<glm::dvec2, 3> corner = {glm::dvec2(0.0), glm::dvec2(lab, 0.0),
                                            glm::dvec2(glm::dot(ac, ex), glm::dot(ac, ey))};
  std::vector<glm::dvec2> p(t.point_count());
  for (int e = 0; e < 3; ++e) {
    p[e] = corner[e];
    for (int m = 1; m < k[e]; ++m)
      p[t.edge_point(e, m)] = corner[e] + (corner[(e + 1) % 3] - corner[e]) * (double(m) / k[e]);
  }
  for (int j = 1; j <= n - 2; ++j)
    for (int i = 1; i + j <= n - 1; ++i)
      p[t.lattice_point(i, j)] = corner[0] + (corner[1] - corner[0]) * (double(i) / n) +
                                 (corner[2] - corner[0]) * (double(j) / n);
  // The boundary of edge e from its start corner to its end corner.
  const auto boundary = [&](int e) {
    std::vector<int> row = {e};
    for (int m = 1; m < k[e]; ++m) row.push_back(t.edge_point(e, m));
    row.push_back((e + 1) % 3);
    return row;
  };
  if (n == 1) {
    t.triangles.emplace_back(0, 1, 2);
  } else if (n == 2) {
    std::vector<int> polygon;
    for (int e = 0; e < 3; ++e) {
      const std::vector<int> row = boundary(e);
      polygon.insert(polygon.end(), row.begin(), row.end() - 1);
    }
    clip_ears(p, polygon, t.triangles);
  } else {
    for (int j = 1; j <= n - 3; ++j)  // the inner lattice triangle's own triangles
      for (int i = 1; i + j <= n - 2; ++i) {
        t.triangles.emplace_back(t.lattice_point(i, j), t.lattice_point(i + 1, j),
                                 t.lattice_point(i, j + 1));
        if (i + j <= n - 3)
          t.triangles.emplace_back(t.lattice_point(i + 1, j), t.lattice_point(i + 1, j + 1),
                                   t.lattice_point(i, j + 1));
      }
    std::array<std::vector<int>, 3> inner;  // its sides, parallel to edges 0, 1, 2
    for (int s = 1; s <= n - 2; ++s) {
      inner[0].push_back(t.lattice_point(s, 1));
      inner[1].push_back(t.lattice_point(n - 1 - s, s));
      inner[2].push_back(t.lattice_point(1, n - 1 - s));
    }
    for (int e = 0; e < 3; ++e) zip(p, boundary(e), inner[e], t.triangles);
  }
  Flipper flipper(p, t.triangles);
  flipper.run();
  if (max_edge > 0.0) flipper.split_long_edges(max_edge, t.midpoints);
  return t;
}

}  // namespace prt::scene::detail
