// scene/src/triangle_tessellation.h — a conforming triangulation of one triangle whose three
// edges are split into given numbers of equal segments (subdivide_to_edge_length's building
// block; internal to prt_scene).
//
// Triangle (a, b, c) in its own plane; edge 0 runs a → b, edge 1 b → c, edge 2 c → a, edge e
// split into k_e ≥ 1 equal segments. Let n = max k_e. Points (local indices):
//   0, 1, 2                    the corners a, b, c;
//   then per edge e = 0, 1, 2  its k_e − 1 inner points, m = 1 … k_e − 1 from its start corner;
//   then the lattice points    a + (b − a)·i/n + (c − a)·j/n with i, j ≥ 1, i + j ≤ n − 1
//                              (j-major, i ascending);
//   then the midpoints           see below.
// The boundary of the result is exactly the edges' segments, so two triangles that split a
// shared edge alike (the same k, the same points) meet without a T-junction whatever their
// other edges. Construction: the lattice triangles of the inner triangle (1,1), (n−2,1),
// (1,n−2) (n ≥ 4), the three trapezoids between it and the edges zipped (shorter diagonal
// first; any zip between two parallel rows is valid), for n = 2 ear clipping; then Lawson's
// edge flips ([92] of docs/REFERENCES.md) to the Delaunay triangulation of these points (interior
// edges only; a flip when the opposite angles sum to more than π), which maximises the smallest
// angle. With all k_e = n it gives the n² lattice triangles (for a non-obtuse triangle; an obtuse
// one gets the lattice's shorter diagonals). Finally, while an interior edge is longer than
// max_edge (a Delaunay edge between a coarse edge's points and the lattice can be, near the
// corners: 7% longer in a 1 × 2 × 3 box at max_edge 0.4), the longest is split at its midpoint
// and the Delaunay property restored — points inside the triangle only, so the boundary stays
// as it is. Triangles keep the winding of (a, b, c).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace prt::scene::detail {

struct Tessellation {
  int n = 1;                          // the lattice level, max k_e
  std::array<int, 3> k{1, 1, 1};      // segments per edge
  std::vector<glm::ivec3> triangles;  // local point indices, (a, b, c)'s winding
  // Points added after the lattice points: each the midpoint of these two earlier points.
  std::vector<std::array<int, 2>> midpoints;
  std::size_t point_count() const;     // 3 + Σ(k_e − 1) + lattice points + midpoints
  int edge_point(int e, int m) const;  // local index of point m (1 … k_e − 1) of edge e
  int lattice_point(int i, int j) const;
};

// a, b, c: the corners (any frame; only their relative positions matter). k: segments per edge
// (each ≥ 1). max_edge: the longest interior edge wanted (≤ 0: no splitting). Degenerate
// corners (collinear) are not refused; the flips then keep the construction's triangles.
Tessellation tessellate_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                 std::array<int, 3> k, double max_edge);

// Triangles tessellate_triangle makes for these counts before any midpoint (each adds two):
// Σk_e + (n − 1)(n − 2) − 2 (the triangulation of a convex polygon with Σk_e boundary and
// (n − 1)(n − 2)/2 inner points). In double, for counts of any size (a tiny max_edge).
double tessellation_triangle_count(std::array<double, 3> k);

}  // namespace prt::scene::detail
