// scene/tangent_frames.h — a tangent frame at every vertex of a scene: the local shading frame
// of prt/brdf/brdf.h (+z the normal, +x the tangent = the α_x direction of anisotropic BRDFs,
// +y the bitangent = w · cross(normal, tangent)).
//
// Sources, in order of preference:
//   1. the file's tangents (Scene::tangents, glTF TANGENT), re-orthogonalised against the
//      normal (Gram–Schmidt);
//   2. otherwise a frame built from the normal alone by the branch-free orthonormal basis of
//      Duff et al. 2017 ([12] of docs/REFERENCES.md): continuous except across the plane
//      normal.z = 0 crossing at the branch sign, and the same for equal normals, so it is
//      consistent between runs and between the baker and the renderer.
// Frame and units: the Scene's (world space).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

// The frame of one unit normal by Duff et al.'s construction: a unit tangent ⊥ n, w = +1.
glm::vec4 normal_only_tangent(const glm::vec3& n);

// One frame per vertex (xyz unit tangent ⊥ the vertex normal, w = ±1).
std::vector<glm::vec4> tangent_frames(const Scene& scene);

}  // namespace prt::scene
