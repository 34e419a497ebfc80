// radiosity/hierarchy.h — the element hierarchy of hierarchical radiosity: a binary volume
// hierarchy (BVH) over the patches, whose lower nodes are pieces of one surface and whose upper
// nodes are clusters of surfaces.
//
// Leaves are the patches (the scene's triangles after --max-edge subdivision: HR's minimum
// element). Inner nodes split their patches at the median centroid along the longest axis of the
// centroids' box, so every node holds a contiguous range of `order`. A node all of whose patches
// lie in one plane (one front normal within 1e-6 of a unit dot product, centroids' offsets along
// it within 1e-5 of the radii) is *planar*: it sends and receives
// like one surface of its total area A (projected area A·max(0, n·d) in direction d), as the
// quadtree nodes of Hanrahan, Salzman & Aupperle 1991 do. Any other node is a *cluster* (Smits,
// Arvo & Greenberg 1994; Sillion 1995): its projected area toward d is approximated from its six
// axis areas, P(d) = Σ_k |d_k|·A_{k,sign d_k} with A_{k,±} = Σ_i A_i max(0, ±n_i,k) — exact for
// patches whose normals are axis-aligned (rooms, boxes), an overestimate bounded by √3 otherwise.
// Directions are unit vectors from the node's area-weighted centroid. Areas are visible areas,
// A·Patch::visible (radiosity/hidden_patches.h; 1 unless marked): the floor under a block takes
// no part in the exchange, and a patch's radiance in the solve is that of its visible part.
//
// A node is *partly hidden* when one of its patches is (0 < Patch::visible < 1: the patch lies
// partly in a contact or under an occluder that nearly touches it); the links refine their
// receivers down to such patches (radiosity/links.h).
//
// Node indices: the root is 0, a node's children come after it (left = node + 1, right = node +
// 2·(leaves of left) ), so a forward sweep visits parents first. Built in parallel (TBB),
// deterministic. Frame and units: the Scene's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/patches.h"

namespace prt::radiosity {

struct HierarchyNode {
  glm::vec3 centroid{0.f};  // area-weighted centroid of its patches
  float radius = 0.f;       // half the diagonal of its patches' bounding box
  glm::vec3 lo{0.f}, hi{0.f};
  float area = 0.f;       // visible area (see above)
  glm::vec3 normal{0.f};  // planar nodes: the common unit normal; clusters: 0
  bool planar = false;
  bool partly_hidden = false;        // holds a patch with 0 < Patch::visible < 1
  uint32_t first = 0, count = 0;     // its patches: order[first, first + count)
  uint32_t left = 0, right = 0;      // children; 0 for a leaf
  std::array<float, 6> axis_area{};  // A_{x,+}, A_{x,−}, A_{y,+}, … (see above)
  bool leaf() const { return count == 1; }
};

struct Hierarchy {
  std::vector<HierarchyNode> nodes;  // 2N − 1 for N patches
  std::vector<uint32_t> order;       // patch of each leaf position
  std::vector<uint32_t> leaf_of;     // node of each patch
  std::size_t planar_nodes = 0, clusters = 0;
};

// Bytes a hierarchy over `patches` patches holds (what build_hierarchy allocates).
uint64_t hierarchy_bytes(std::size_t patches);

// The hierarchy over `patches` (at least one; patches of zero area are kept as leaves).
Hierarchy build_hierarchy(const std::vector<Patch>& patches);

// Projected area of node `n` toward the unit direction d (see above).
inline float projected_area(const HierarchyNode& n, const glm::vec3& d) {
  if (n.planar) return n.area * glm::max(0.f, glm::dot(n.normal, d));
  return std::abs(d.x) * n.axis_area[d.x < 0.f] + std::abs(d.y) * n.axis_area[2 + (d.y < 0.f)] +
         std::abs(d.z) * n.axis_area[4 + (d.z < 0.f)];
}

}  // namespace prt::radiosity
