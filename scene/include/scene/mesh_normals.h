// scene/mesh_normals.h — cleaning a loaded triangle list and computing missing vertex normals.
//
// Frame and units: those of the scene (world space after node transforms).
//
// Degenerate triangles (rule used by remove_degenerate_triangles): a triangle is degenerate
// when two of its indices are equal, or when its area |cross(b - a, c - a)| / 2, computed in
// double, is <= 1e-12 * extent^2 (extent = the scene's bounding-box diagonal), or not finite.
// This catches repeated indices, coincident vertices and collinear vertices without a
// per-mesh tolerance, and is scale-invariant.
//
// Vertex normals (compute_vertex_normals): the normal of vertex v is the normalised sum over
// the triangles using v of   n_f * area_f * angle_f(v),   where n_f is the unit face normal
// (counter-clockwise winding), area_f the triangle area and angle_f(v) the triangle's interior
// angle at v (computed with atan2, stable for thin triangles). Angle weighting makes the
// result independent of how a flat region is triangulated around v (Thürmer & Wüthrich 1998,
// "Computing vertex normals from polygonal facets"); the extra area factor damps slivers
// (Max 1999, "Weights for computing vertex normals from facet normals", compares the schemes).
// A vertex used by no triangle, or whose weighted sum has length <= 1e-30 (opposite faces
// cancelling), gets the deterministic fallback normal +Y and is counted.
// References: [18] of docs/REFERENCES.md.
#pragma once

#include <cstddef>

#include "scene/scene.h"

namespace prt::scene {

// True when triangle (a, b, c) is degenerate by the rule above, for a scene of extent `extent`.
bool is_degenerate_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            double extent);

// Removes degenerate triangles from scene.triangles (keeping order), fixes the primitives'
// triangle ranges, adds the count to scene.skipped_degenerate_triangles and returns it.
// Indices must be in range.
std::size_t remove_degenerate_triangles(Scene& scene);

struct NormalComputation {
  std::size_t computed = 0;  // vertices whose normal was (re)computed
  std::size_t fallback = 0;  // of those, vertices given the +Y fallback
};

// Computes vertex normals as described above. With only_missing, only vertices whose current
// normal is missing (scene.normals shorter than positions, or a zero / non-finite entry) are
// recomputed; otherwise all are. scene.normals is resized to the vertex count, and
// scene.computed_normal_vertices is increased by the number computed.
NormalComputation compute_vertex_normals(Scene& scene, bool only_missing);

}  // namespace prt::scene
