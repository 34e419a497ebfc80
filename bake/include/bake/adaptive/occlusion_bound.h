// bake/adaptive/occlusion_bound.h — a conservative bound, without rays, on how much of a vertex's
// cosine-weighted hemisphere the scene can block: the projected solid angle
//   G_v = (1/π) ∫_{ω·n > 0, the ray from v hits something} (ω·n) dω ∈ [0, 1]
// is ≤ occlusion_bound(v). `prt bake --auto` gives vertices with a small bound the analytic
// unshadowed transfer and charges the bound to the error budget (bake/adaptive/adaptive_baker.h).
//
// Frame and units: the Scene's. The bound is a sum over disjoint groups of triangles (a union
// bound), each group either dismissed or bounded by a ball:
//   - a group whose every vertex lies at height (q − p)·n ≤ τ_v above the tangent plane cannot
//     be hit (the proof of bake/adaptive/scene_analysis.h; τ_v of scene/ray_offset.h);
//   - otherwise, a ball B(c, r) that holds the group, seen from p at distance d > r, covers the
//     cap of half-angle α = asin(r/d) around the direction of c; the cap's solid angle is
//     2π(1 − cos α) and its largest cosine to n is cos(max(0, θ_c − α)), so its projected solid
//     angle is ≤ 2(1 − cos α)·cos(max(0, θ_c − α)) (0 when θ_c − α ≥ 90°).
// Rays leave from p + ε_v·n plus a tangential nudge ≤ ε_v (scene/ray_caster.h); the directions
// from that origin to B(c, r) are those from p to a ball of radius r + 2ε_v, so every radius is
// inflated by 2ε_v. A vertex inside a group's ball gets +∞ (no bound).
// Acceleration: a hierarchy of triangle groups (median splits on centroids, leaves ≤ 8
// triangles); a group's ball is accepted when it looks small (r/d ≤ 1/4), else its children
// are visited. The walk stops as soon as the sum passes `cutoff` (the vertex will cast rays).
#pragma once

#include <cstddef>
#include <vector>

#include "bake/adaptive/triangle_hierarchy.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace prt::bake {

struct OcclusionBounds {
  std::vector<float> bound;  // per vertex: ≥ G_v; > cutoff means "not bounded below cutoff"
  double seconds = 0.0;
};

// Bounds every vertex whose `skip` entry is 0 (skip may be empty); others get 0. `starts` holds
// ε_v and τ_v (scene/ray_offset.h). Deterministic, parallel.
// `hierarchy` (optional) is bake/adaptive/triangle_hierarchy.h's over this scene; built when null.
OcclusionBounds bound_occlusion(const scene::Scene& scene, const scene::VertexRayStarts& starts,
                                double cutoff, const std::vector<uint8_t>& skip = {},
                                const TriangleHierarchy* hierarchy = nullptr);

// Reference path for tests: the same union bound with one ball per triangle, O(T) per vertex.
double occlusion_bound_brute_force(const scene::Scene& scene, std::size_t vertex,
                                   const scene::VertexRayStarts& starts);

// The projected-solid-angle bound of one ball (see above): `to_center` = c − p, unit normal n.
double ball_projected_solid_angle_bound(const glm::dvec3& to_center, double radius,
                                        const glm::dvec3& n);

}  // namespace prt::bake
