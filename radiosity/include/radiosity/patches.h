// radiosity/patches.h — the patches of a radiosity solution: one per scene triangle, with the
// material of its primitive; and the patch → vertex interpolation used for output.
//
// Frame and units: the Scene's. A patch is one-sided: it emits and receives on its front face,
// the side its counter-clockwise winding faces (normal = normalize((b − a) × (c − a)), glTF's
// convention). Radiance is exit radiance of a Lambertian surface, linear RGB, in the units of the
// emission (radiosity B = π·L).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::radiosity {

struct Patch {
  std::array<glm::dvec3, 3> corners;  // scene positions, in the triangle's winding
  glm::dvec3 centroid{0.0};
  glm::dvec3 normal{0.0, 1.0, 0.0};  // unit front-face normal
  double area = 0.0;
  glm::dvec3 albedo{0.0};    // the mean of its corners' albedo
  glm::dvec3 emission{0.0};  // its primitive's emission (exit radiance)
  // The fraction of its area that something can see (radiosity/hidden_patches.h); 1 unless
  // set by mark_hidden_parts. Only vertex_radiance reads it: the solve keeps every patch.
  double visible = 1.0;
};

// Patch t is scene triangle t. The scene's primitives must cover its triangles (the loaders and
// scene::subdivide_to_edge_length make them so); a triangle no primitive covers emits nothing.
std::vector<Patch> make_patches(const scene::Scene& scene);

// Per-vertex radiance, 3 floats per scene vertex: the mean radiance of the visible parts of the
// patches (triangles) around each vertex, weighted by their visible areas,
//     L_v = Σ_i A_i L_i / Σ_i A_i v_i   over the patches i around v with v_i = Patch::visible > 0,
// since a patch's hidden part has radiance 0 (L_i / v_i is the radiance of its visible part). So
// a vertex on a contact line (a floor vertex at a block's foot) takes the visible side's value,
// and the floor under the block adds nothing. With every v_i = 1 this is the area-weighted mean
// of the patches around v. 0 for a vertex on no triangle or on hidden patches only.
std::vector<float> vertex_radiance(const scene::Scene& scene, const std::vector<Patch>& patches,
                                   const std::vector<glm::dvec3>& patch_radiance);

}  // namespace prt::radiosity
