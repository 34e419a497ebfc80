// scene/subdivide.h — splitting a scene's triangles until no edge is longer than a target length
// (the patches of a radiosity solution; any consumer that wants finer triangles can use it).
//
// Frame and units: the Scene's. Conforming: every edge of length ℓ is split into
// k = ⌈ℓ / max_edge⌉ equal segments whatever triangle it belongs to, its points computed from
// the endpoints taken in a canonical order (by position), so two triangles sharing an edge —
// of one primitive or of two — get bit-identical points on it and no T-junction appears; a
// closed mesh stays closed. Each triangle is then triangulated from its three counts
// (scene/src/triangle_tessellation.h): its lattice points of level n = max k inside, zipped to
// the edge points, turned into the Delaunay triangulation of these points by edge flips
// (largest smallest angle), and interior edges still longer than max_edge split at their
// midpoints. With equal counts on an acute triangle that is the n² congruent triangles (a right
// one may get the other diagonal in some lattice cells, of the same length).
// Every output edge is ≤ max_edge; the pieces tile the original exactly (same total area) and
// keep its winding, so faces keep their orientation.
// Vertices: each primitive keeps its own vertices first, in order (vertex v of the input is
// vertex v of the output when every primitive is contiguous, as the loaders make them), then
// the new ones of that primitive; a point of an edge shared by two triangles of the primitive
// is one vertex. New vertices interpolate their corners' normals (renormalised), albedo and
// texture coordinates barycentrically, and their file tangents (renormalised; w of the nearest
// corner; zero, i.e. "missing", when a corner has none). Primitives keep their names,
// materials, BRDFs and anisotropy rotations, albedo and emission; cameras and source_path are
// copied. `prt bake --max-edge`, `prt radiosity --max-edge` and `prt relight --max-edge` all
// call this, so they agree vertex for vertex.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace prt::scene {

// At most this many output triangles (a guard against a max_edge far too small for the scene).
constexpr std::size_t kMaxSubdividedTriangles = 20'000'000;

// Throws std::invalid_argument (one line) when max_edge is not a finite positive number or the
// result would exceed kMaxSubdividedTriangles (counted before the midpoint splits, which add a
// few).
Scene subdivide_to_edge_length(const Scene& scene, double max_edge);

// Conforming local refinement (adaptive patches): every triangle t with marked[t] is bisected
// `levels` times (levels = 2: into four), by longest-edge bisection (Rivara 1984, [80] of
// docs/REFERENCES.md): a triangle is split at the midpoint of its longest edge (ties: the edge
// with the smaller vertex ids), after the neighbour across that edge has been split until that
// edge is the neighbour's longest too; then both halves of the edge split together. So no
// T-junction is created (a mesh without T-junctions keeps none), the smallest angle is at
// least half the smallest input angle, and refinement spreads only as far as needed.
// Neighbours are triangles of the same primitive sharing an edge (two vertex ids). Children keep
// the winding, so faces keep their orientation, and tile the parent exactly. Vertices: each
// primitive keeps its own vertices first, in order, then its new ones (edge midpoints, normals
// renormalised, albedo averaged); triangles: each input triangle's pieces in its place.
// Texture coordinates and tangents are dropped, as in subdivide_to_edge_length. `parent`, when
// given, receives the input triangle of each output triangle.
// Throws std::invalid_argument when marked.size() ≠ the triangle count or levels ∉ 1..8.
Scene refine_triangles(const Scene& scene, const std::vector<bool>& marked, int levels = 2,
                       std::vector<uint32_t>* parent = nullptr);

}  // namespace prt::scene
