// scene/tangent_frames.h — a tangent frame at every vertex of a scene: the local shading frame
// of prt/brdf/brdf.h (+z the normal, +x the tangent = the α_x direction of anisotropic BRDFs,
// +y the bitangent = w · cross(normal, tangent)).
//
// Sources, per vertex, in order of preference:
//   1. the file's tangent (Scene::tangents, glTF TANGENT) when it is usable (finite, not
//      parallel to the normal; zero marks "missing"), re-orthogonalised against the normal
//      (Gram–Schmidt);
//   2. otherwise, when the scene has texture coordinates (Scene::texcoords), the direction of
//      increasing u: dP/du of each triangle around the vertex (solved from its edges and their
//      UV differences), summed with weight |UV area| × 2 (the determinant), projected off the
//      normal and normalised; the handedness w = sign((cross(n, t)) · Σ dP/dv), so the
//      bitangent follows increasing v. A vertex whose triangles all have degenerate UVs (zero
//      UV area, e.g. vertices of primitives without coordinates, padded with zeros) or whose
//      dP/du sum cancels or is parallel to the normal falls through to 3;
//   3. otherwise a frame built from the normal alone by the branch-free orthonormal basis of
//      Duff et al. 2017 ([12] of docs/REFERENCES.md): continuous except across the plane
//      normal.z = 0 crossing at the branch sign, and the same for equal normals, so it is
//      consistent between runs and between the baker and the renderer.
// Then each primitive's anisotropy_rotation r (ScenePrimitive; per vertex when it has
// anisotropy_rotation_of_vertex) turns the tangent about the normal: t' = cos r · t + sin r · b
// (b the bitangent above), w unchanged.
// Frame and units: the Scene's (world space).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

// The frame of one unit normal by Duff et al.'s construction: a unit tangent ⊥ n, w = +1.
glm::vec4 normal_only_tangent(const glm::vec3& n);

// Per-vertex tangents from the texture coordinates (source 2 above), zero where the UVs give
// none; empty when the scene has no texture coordinates.
std::vector<glm::vec4> uv_tangents(const Scene& scene);

// One frame per vertex (xyz unit tangent ⊥ the vertex normal, w = ±1).
std::vector<glm::vec4> tangent_frames(const Scene& scene);

}  // namespace prt::scene
