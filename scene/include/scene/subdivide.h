// scene/subdivide.h — splitting a scene's triangles until no edge is longer than a target length
// (the patches of a radiosity solution; any consumer that wants finer triangles can use it).
//
// Frame and units: the Scene's. A triangle (a, b, c) whose longest edge is ℓ is split into n²
// congruent triangles, n = ⌈ℓ / max_edge⌉ (n = 1 keeps it): the lattice points
// a + (b − a)·i/n + (c − a)·j/n, i + j ≤ n, joined in the winding of (a, b, c), so faces keep
// their orientation and the sub-triangles tile the original exactly (same total area).
// Vertices: each primitive keeps its own vertices first, in order (vertex v of the input is
// vertex v of the output when every primitive is contiguous, as the loaders make them), then
// the new ones of that primitive. A point on an edge shared by two triangles of the same
// primitive that pick the same n is one vertex; neighbours with different n meet in T-junctions
// (the surface has no cracks: every new point lies on the original edge). New vertices
// interpolate their corners' normals (renormalised), albedo and texture coordinates
// barycentrically, and their file tangents (renormalised; w of the nearest corner; zero, i.e.
// "missing", when a corner has none). Primitives keep their names, materials, BRDFs and
// anisotropy rotations, albedo and emission; cameras and source_path are copied.
#pragma once

#include <cstddef>

#include "scene/scene.h"

namespace prt::scene {

// At most this many output triangles (a guard against a max_edge far too small for the scene).
constexpr std::size_t kMaxSubdividedTriangles = 20'000'000;

// Throws std::invalid_argument (one line) when max_edge is not a finite positive number or the
// result would exceed kMaxSubdividedTriangles.
Scene subdivide_to_edge_length(const Scene& scene, double max_edge);

}  // namespace prt::scene
