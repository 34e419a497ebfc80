// radiosity/src/hierarchy.cpp — see radiosity/hierarchy.h.
#include "radiosity/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/task_group.h>

namespace prt::radiosity {
namespace {

constexpr float kSameNormal = 1.f - 1e-6f;

class Builder {
 public:
  Builder(const std::vector<Patch>& patches, Hierarchy* h) : patches_(patches), h_(h) {}

  // Builds node `index` over order[first, first + count).
  void build(uint32_t index, uint32_t first, uint32_t count, int depth) {
    HierarchyNode& node = h_->nodes[index];
    node.first = first;
    node.count = count;
    if (count == 1) {
      make_leaf(index, h_->order[first]);
      return;
    }
    glm::dvec3 lo(1e300), hi(-1e300);
    for (uint32_t k = first; k < first + count; ++k) {
      lo = glm::min(lo, patches_[h_->order[k]].centroid);
      hi = glm::max(hi, patches_[h_->order[k]].centroid);
    }
    const glm::dvec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const uint32_t half = count / 2;
    uint32_t* begin = h_->order.data() + first;
    std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
      const double ca = patches_[a].centroid[axis], cb = patches_[b].centroid[axis];
      return ca < cb || (ca == cb && a < b);
    });
    node.left = index + 1;
    node.right = index + 2 * half;
    if (depth < 12 && count > 4096) {
      tbb::task_group group;
      group.run([&] { build(node.left, first, half, depth + 1); });
      build(node.right, first + half, count - half, depth + 1);
      group.wait();
    } else {
      build(node.left, first, half, depth + 1);
      build(node.right, first + half, count - half, depth + 1);
    }
    combine(index);
  }

 private:
  void make_leaf(uint32_t index, uint32_t patch) {
    HierarchyNode& node = h_->nodes[index];
    const Patch& p = patches_[patch];
    glm::dvec3 lo = p.corners[0], hi = p.corners[0];
    for (const glm::dvec3& c : p.corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
    node.lo = glm::vec3(lo);
    node.hi = glm::vec3(hi);
    node.radius = float(0.5 * glm::length(hi - lo));
    node.centroid = glm::vec3(p.centroid);
    const double area = p.area * std::clamp(p.visible, 0.0, 1.0);  // the visible part
    node.area = float(area);
    node.normal = glm::vec3(p.normal);
    node.planar = true;
    node.partly_hidden = p.visible > 0.0 && p.visible < 1.0;
    for (int k = 0; k < 3; ++k) {
      node.axis_area[2 * k] = float(area * std::max(0.0, p.normal[k]));
      node.axis_area[2 * k + 1] = float(area * std::max(0.0, -p.normal[k]));
    }
    h_->leaf_of[patch] = index;
  }

  void combine(uint32_t index) {
    HierarchyNode& node = h_->nodes[index];
    const HierarchyNode& a = h_->nodes[node.left];
    const HierarchyNode& b = h_->nodes[node.right];
    node.lo = glm::min(a.lo, b.lo);
    node.hi = glm::max(a.hi, b.hi);
    node.radius = 0.5f * glm::length(node.hi - node.lo);
    const double area = double(a.area) + double(b.area);
    node.area = float(area);
    node.centroid = area > 0.0 ? glm::vec3((glm::dvec3(a.centroid) * double(a.area) +
                                            glm::dvec3(b.centroid) * double(b.area)) /
                                           area)
                               : 0.5f * (a.centroid + b.centroid);
    // One plane: the same normal and the same offset along it.
    node.planar =
        a.planar && b.planar && glm::dot(a.normal, b.normal) >= kSameNormal &&
        std::abs(glm::dot(a.normal, b.centroid - a.centroid)) <= 1e-5f * (a.radius + b.radius);
    node.normal = node.planar ? a.normal : glm::vec3(0.f);
    node.partly_hidden = a.partly_hidden || b.partly_hidden;
    for (int k = 0; k < 6; ++k) node.axis_area[k] = a.axis_area[k] + b.axis_area[k];
  }

  const std::vector<Patch>& patches_;
  Hierarchy* h_;
};

}  // namespace

uint64_t hierarchy_bytes(std::size_t patches) {
  return uint64_t(2 * patches) * sizeof(HierarchyNode) + uint64_t(patches) * 2 * sizeof(uint32_t);
}

Hierarchy build_hierarchy(const std::vector<Patch>& patches) {
  if (patches.empty()) throw std::invalid_argument("build_hierarchy: no patches");
  if (patches.size() > (std::size_t(1) << 31))
    throw std::invalid_argument("build_hierarchy: more than 2^31 patches");
  Hierarchy h;
  const uint32_t n = static_cast<uint32_t>(patches.size());
  h.nodes.resize(2 * std::size_t(n) - 1);
  h.order.resize(n);
  h.leaf_of.resize(n);
  for (uint32_t i = 0; i < n; ++i) h.order[i] = i;
  Builder(patches, &h).build(0, 0, n, 0);
  for (const HierarchyNode& node : h.nodes)
    if (!node.leaf()) (node.planar ? h.planar_nodes : h.clusters) += 1;
  return h;
}

}  // namespace prt::radiosity
