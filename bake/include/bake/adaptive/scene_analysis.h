// bake/adaptive/scene_analysis.h — cheap, conservative analysis of a scene before baking: which
// vertices have a hemisphere that no ray can leave blocked (they get the analytic unshadowed
// transfer, with no rays), and whether the albedo allows interreflection at all.
//
// Frame and units: the Scene's (glTF frame, +Y up; the file's units).
//
// Open-hemisphere test (the proof). Let p be a vertex with unit normal n and let
// h(q) = (q − p)·n be the height of a point q above p's tangent plane. A triangle is the convex
// hull of its three vertices, and h is affine, so h ≤ max over the triangle's vertices on the
// whole triangle. If every vertex q of every triangle has h(q) ≤ τ, all geometry lies in the
// half-space h ≤ τ. The baker casts rays from o = p + ε·n + t⊥ (scene/ray_caster.h, t⊥ a nudge
// in the tangent plane) in directions ω with ω·n ≥ 0, so every point o + sω (s ≥ 0) has height
// ε + s·(ω·n) ≥ ε, less the rounding of o. With τ_v of scene/ray_offset.h (half of ε_v after
// that rounding) no ray can reach any triangle: the vertex's visibility is 1 in every direction of
// its hemisphere, and its shadowed (and interreflected: nothing is hit) transfer equals the
// unshadowed one exactly. Examples: every vertex of a convex mesh whose normals lie in the normal
// cone (any positive blend of the adjacent face normals, or the radial normals of a sphere), the
// top of an object standing on a ground plane with nothing above it. τ_v follows the float rounding
// at the vertex, not the scene's size. The test is conservative: a vertex it rejects may still be
// open (then rays simply find nothing).
//
// Acceleration: a bounding-volume hierarchy over the triangles' vertices (median splits, leaves
// of ≤ 16 points). For a box with centre c and half-extent e, max h = (c − p)·n + Σ|n_i|·e_i, so
// a whole subtree below the plane is dismissed in one test; the first point above the plane
// ends the query. Cost: O(V log V) for convex-like scenes, O(V) early exits elsewhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace prt::bake {

struct HemisphereAnalysis {
  std::vector<uint8_t> open;  // per vertex: 1 = provably unoccluded hemisphere
  std::size_t open_count = 0;
  double seconds = 0.0;
};

// Runs the open-hemisphere test for every vertex with τ_v of `starts` (in parallel;
// deterministic).
HemisphereAnalysis find_open_hemispheres(const scene::Scene& scene,
                                         const scene::VertexRayStarts& starts);

// Reference path for tests: the same test by brute force over every triangle vertex, O(V·T).
bool is_hemisphere_open_brute_force(const scene::Scene& scene, std::size_t vertex,
                                    double threshold);

// Albedo facts the adaptive baker acts on.
struct AlbedoAnalysis {
  bool grey = true;      // r = g = b at every vertex: one channel
  bool all_zero = true;  // no vertex reflects anything: no interreflection
  float max_albedo = 0.f;
};
AlbedoAnalysis analyze_albedo(const scene::Scene& scene);

}  // namespace prt::bake
