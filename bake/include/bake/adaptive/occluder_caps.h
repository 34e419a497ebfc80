// bake/adaptive/occluder_caps.h — where a vertex's rays can hit anything: a few cones of directions
// (caps) that hold every blockable direction of its hemisphere, found without rays.
//
// `prt bake --auto` samples such a vertex only inside its caps (bake/adaptive/cap_sampling.h) and
// takes the rest of the hemisphere analytically: a floor vertex far from the objects on it needs
// rays toward those objects only, not toward the open sky.
//
// Frame and units: the Scene's. The argument is that of bake/adaptive/occlusion_bound.h, per group
// of triangles of a hierarchy (bake/adaptive/triangle_hierarchy.h):
//   - a group whose every vertex lies within τ_v of p's tangent plane cannot be hit (the proof
//     of bake/adaptive/scene_analysis.h; τ_v of scene/ray_offset.h);
//   - a ball B(c, r) that holds the group, seen from p at distance d > r, covers the cap of
//     half-angle α = asin(r/d) around the direction of c; rays leave from p + ε_v·n plus a
//     tangential nudge ≤ ε_v (scene/ray_caster.h), so every radius is inflated by 2ε_v;
//   - caps that lie wholly below the horizon (θ_c − α ≥ 90°) are dropped.
// A group's ball is accepted when r/d ≤ ½ (α ≤ 30°), else its children are visited (a leaf's
// triangles get a ball each). The vertex gets caps only when at most `max_caps` caps with a
// total solid angle ≤ `max_solid_angle` cover it; otherwise (near geometry, inside a ball) it
// gets none and `covered` is 0: sample its whole hemisphere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bake/adaptive/triangle_hierarchy.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace prt::bake {

// The cone of unit directions ω with ω·axis ≥ 1 − one_minus_cos (half-angle α,
// one_minus_cos = 1 − cos α = 2 sin²(α/2), kept as such: tiny caps stay accurate).
struct DirectionCap {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double one_minus_cos = 0.0;

  double solid_angle() const;  // 2π(1 − cos α)
  bool contains(const glm::dvec3& unit_direction) const;
};

struct OccluderCaps {
  std::vector<uint8_t> covered;  // per vertex: 1 = caps[first[v] .. first[v + 1]) hold it
  std::vector<uint32_t> first;   // V + 1 offsets into caps
  std::vector<DirectionCap> caps;
  double seconds = 0.0;

  std::size_t count(std::size_t v) const { return first[v + 1] - first[v]; }
  const DirectionCap* of(std::size_t v) const { return caps.data() + first[v]; }
};

inline constexpr int kDefaultMaxCaps = 8;

// Caps of every vertex with wanted[v] != 0 (wanted empty = every vertex). `starts` holds ε_v
// and τ_v (scene/ray_offset.h). Deterministic, parallel.
// `hierarchy` (optional) is bake/adaptive/triangle_hierarchy.h's over this scene; built when null.
OccluderCaps find_occluder_caps(const scene::Scene& scene, const scene::VertexRayStarts& starts,
                                const std::vector<uint8_t>& wanted, int max_caps,
                                double max_solid_angle,
                                const TriangleHierarchy* hierarchy = nullptr);

// The ball B(c, r) seen from p (to_center = c − p) as a cap; false when p lies inside it.
bool cap_of_ball(const glm::dvec3& to_center, double radius, DirectionCap& cap);

}  // namespace prt::bake
