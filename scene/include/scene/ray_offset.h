// scene/ray_offset.h — where a ray that leaves a surface starts: as close to the surface as float
// arithmetic allows, and no closer. The offset follows the rounding error of the point and of
// the triangles around it, never the scene's size, so a kilometre-wide level keeps the contact
// shadows of its centimetre details (Wächter & Binder 2019, "A Fast and Robust Method for
// Avoiding Self-Intersection"; pbrt-v4's OffsetRayOrigin; docs/RAY_OFFSETS.md derives the
// constants and measures them).
//
// Frame and units: the Scene's (glTF frame, +Y up; the file's units).
//
// The offset of a surface point p whose surrounding triangles have edges of length ≤ L is
//   ε(p, L) = 4·U(p) + 2^-18·L,   U(p) = 2^-23 · max_i |p_i|
// U bounds the spacing of floats around p (one ulp), so:
//   - rounding the origin o = p + ε·n to float moves it by at most √3·U/2 per rounding step
//     (two steps with the tangential nudge: 1.73·U), which leaves o at least 2.27·U above the
//     surface;
//   - Embree's robust triangle test computes the plane distance of o from the triangle's
//     vertices translated to o, whose error is a few units of 2^-24 times |vertex − o| ≤ L
//     for the triangles that meet at p; 2^-18·L is 64 times 2^-24·L.
// Nothing in ε depends on the scene's extent or on other objects.
// References: [14] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

// One ulp bound around p: 2^-23 · max_i |p_i| (≥ the float spacing of every coordinate of p).
double float_spacing_bound(const glm::dvec3& p);

// ε(p, L) of the header: how far a ray origin stands off a surface point p (scene units) that
// lies on triangles whose longest edge is `local_edge`.
double ray_offset(const glm::dvec3& p, double local_edge);

// ε(p, L) for a point p on triangle t: L is t's longest edge, and U covers t's vertices too
// (an interpolated hit point carries their rounding).
double triangle_ray_offset(const Scene& scene, uint32_t triangle, const glm::dvec3& p);

// Where the rays of each vertex start, and what they provably cannot reach.
struct VertexRayStarts {
  // ε_v = ε(p_v, L_v), L_v the longest edge of v's triangles (0 for a vertex on none). The ray
  // origin is p_v + ε_v·n_v, nudged tangentially by at most ε_v (ray_caster.h).
  std::vector<float> offset;
  // τ_v = (ε_v − 2·U(p_v)) / 2: every ray origin of v lies more than 2·τ_v above v's tangent
  // plane after rounding, and its rays climb from there, so geometry whose height above that
  // plane is ≤ τ_v cannot be hit from v. Used by the adaptive planner's proofs.
  std::vector<double> unreachable_height;
};

// ε_v and τ_v for every vertex of `scene`, in one pass over its triangles.
VertexRayStarts compute_vertex_ray_starts(const Scene& scene);

// The longest edge of triangle (a, b, c).
double longest_edge(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// ε rounded up to float, as VertexRayStarts::offset stores it (the origin stands ≥ ε off).
float offset_as_float(double eps);

// The largest VertexRayStarts::offset of `scene`, equal to the maximum of
// compute_vertex_ray_starts(scene).offset, in one pass over the triangles and no per-vertex
// array: ray_offset is non-decreasing in U(p) and in L, and so is their rounded sum.
double max_vertex_ray_offset(const Scene& scene);

}  // namespace prt::scene
