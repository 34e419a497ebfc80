// scene/translucent_scene.h — the bundled translucent scene and its lone slab and sphere, for
// subsurface scattering (prt make-scene --scene translucent | translucent-slab |
// translucent-sphere).
//
// Units: 1 scene unit = 1 mm (kTranslucentMmPerUnit), the unit of the dipole's published σ
// values (mm⁻¹), so a preset applies to these scenes as it is. Frame: glTF's (+Y up).
// Every translucent part is a closed (watertight once coincident positions are welded),
// outward-facing surface: the dipole and the depth-map approximation need an inside.
//
// The full scene (make_translucent_scene), on a grey ground (y = 0, x ∈ [−80, 80],
// z ∈ [−50, 50], albedo 0.5, primitive "ground"):
//   - "slab": a box x ∈ [−70, −20], y ∈ [0, 10], z ∈ [−20, 20] (50 × 10 × 40), cells of
//     kSlabCell on every face;
//   - "sphere": a UV sphere of radius 12 centred at (0, 12, 0), 48 rings × 96 segments;
//   - "fin": the ear-like thin part: an ellipsoid with semi-axes (14, 20, 1.25) bent about the
//     Y axis, p = (14x, 20y, 1.25z + x'²/28) for the unit sphere (x, y, z) and x' = 14x, centred
//     at (45, 18, 0) (its lower tip 2 below the ground). Its thickness along Z at (x', y') from
//     its centre is exactly 2.5·√(1 − (x'/14)² − (y'/20)²) (the bend moves both sides alike):
//     2.5 at the centre, thinning to 0 at the rim, like an ear; 64 rings × 128 segments, normals
//     from the mesh (scene/mesh_normals.h);
//   - one camera "camera" looking from +Z (eye (0, 45, 130), target (0, 12, 0)), so light from
//     −Z is back light for the fin.
// The lone slab (make_translucent_slab): a box x, z ∈ [−50, 50], y ∈ [−20, 0] (top face at
// y = 0), cells of kSlabCell; the lone sphere (make_translucent_sphere): radius 10 at the
// origin, 64 rings × 128 segments. Both have a camera. Albedo of translucent parts: 0.8 grey
// (what a diffuse bake would use; the subsurface bake takes σ from its material).
#pragma once

#include "scene/scene.h"

namespace prt::scene {

inline constexpr double kTranslucentMmPerUnit = 1.0;
inline constexpr float kSlabCell = 1.5f;  // edge length of the slabs' grid cells, mm

// The fin's shape (see above), for tests and documentation.
struct FinShape {
  float semi_width = 14.f, semi_height = 20.f, half_thickness = 1.25f;
  float bend = 1.f / 28.f;  // z offset = bend · x'²
  glm::vec3 centre{45.f, 18.f, 0.f};
};

// A closed box [lo, hi] made of six grids with cells of about `cell` (each face's segment count
// is round(length / cell), at least 1; neighbouring faces share their edges' points, so the
// box is watertight after welding). Outward normals; one primitive `name`.
Scene make_closed_slab(glm::vec3 lo, glm::vec3 hi, float cell, glm::vec3 albedo, std::string name);

// The fin of FinShape, one primitive "fin".
Scene make_fin(const FinShape& shape, int rings, int segments, glm::vec3 albedo);

Scene make_translucent_scene();
Scene make_translucent_slab();
Scene make_translucent_sphere();

}  // namespace prt::scene
