// bake/src/adaptive/occluder_caps.cpp — caps of blockable directions (occluder_caps.h).
#include "bake/adaptive/occluder_caps.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "bake/adaptive/triangle_hierarchy.h"
#include "sh/constants.h"

namespace prt::bake {
namespace {

using sh::kPi;
constexpr double kAcceptRatio = 0.5;  // accept a group's ball when r/d ≤ this (α ≤ 30°)

// True when some direction of the cap lies strictly above the tangent plane of n:
// θ_c − α < 90°, i.e. cos θ_c > −sin α.
bool reaches_above_horizon(const DirectionCap& cap, const glm::dvec3& n) {
  const double cos_a = 1.0 - cap.one_minus_cos;
  const double sin_a = std::sqrt(std::max(0.0, cap.one_minus_cos * (1.0 + cos_a)));
  return glm::dot(cap.axis, n) > -sin_a;
}

}  // namespace

double DirectionCap::solid_angle() const {
  return 2.0 * kPi * one_minus_cos;
}

bool DirectionCap::contains(const glm::dvec3& w) const {
  // 1 − ω·a = |ω − a|²/2 for unit vectors: accurate for tiny caps.
  const glm::dvec3 d = w - axis;
  return 0.5 * glm::dot(d, d) <= one_minus_cos;
}

bool cap_of_ball(const glm::dvec3& to_center, double radius, DirectionCap& cap) {
  const double d = glm::length(to_center);
  if (!(d > radius)) return false;
  const double sin_a = radius / d;
  // 1 − cos α = sin²α / (1 + cos α), without cancellation.
  cap.one_minus_cos = sin_a * sin_a / (1.0 + std::sqrt(std::max(0.0, 1.0 - sin_a * sin_a)));
  cap.axis = to_center / d;
  return true;
}

OccluderCaps find_occluder_caps(const scene::Scene& scene, const scene::VertexRayStarts& starts,
                                const std::vector<uint8_t>& wanted, int max_caps,
                                double max_solid_angle, const TriangleHierarchy* hierarchy) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t V = scene.positions.size();
  TriangleHierarchy own;
  if (hierarchy == nullptr) own = build_triangle_hierarchy(scene);
  const TriangleHierarchy& h = hierarchy != nullptr ? *hierarchy : own;
  const std::size_t limit = static_cast<std::size_t>(std::max(max_caps, 0));
  // Blocks of vertices keep their caps in their own lists (memory ∝ the caps found, not
  // V × max_caps), concatenated in vertex order afterwards: deterministic.
  constexpr std::size_t kBlock = 256;
  const std::size_t blocks = (V + kBlock - 1) / kBlock;
  std::vector<std::vector<DirectionCap>> found(blocks);
  std::vector<uint32_t> counts(V, 0);
  std::vector<uint8_t> covered(V, 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
    std::vector<DirectionCap> scratch(limit);
    for (std::size_t v = blk * kBlock; v < std::min(V, (blk + 1) * kBlock); ++v) {
      if (!wanted.empty() && !wanted[v]) continue;
      const glm::dvec3 p(scene.positions[v]);
      const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[v]));
      const double threshold = starts.unreachable_height[v];
      const double inflate = 2.0 * static_cast<double>(starts.offset[v]);
      // No usable normal (zero or non-finite): no hemisphere to prove anything about.
      if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) continue;
      const glm::dvec3 abs_n = glm::abs(n);
      DirectionCap* caps = scratch.data();
      std::size_t m = 0;
      double total = 0.0;
      bool ok = true;
      // Adds the cap of B(c, r) unless it lies below the horizon; false ends the walk.
      auto add_ball = [&](const glm::dvec3& c, double r) {
        DirectionCap cap;
        if (!cap_of_ball(c - p, r, cap)) return false;
        if (!reaches_above_horizon(cap, n)) return true;
        if (m == limit) return false;
        total += cap.solid_angle();
        caps[m++] = cap;
        return total <= max_solid_angle;
      };
      uint32_t stack[64];
      int top = 0;
      if (!h.nodes.empty()) stack[top++] = 0;
      while (top > 0 && ok) {
        const uint32_t index = stack[--top];
        const TriangleHierarchy::Node& node = h.nodes[index];
        if (glm::dot(node.box_center - p, n) + glm::dot(node.box_half, abs_n) <= threshold)
          continue;  // the whole group lies within τ of the tangent plane
        const double r = node.ball_radius + inflate;
        const double d = glm::length(node.ball_center - p);
        if (d > 0.0 && r <= kAcceptRatio * d) {
          ok = add_ball(node.ball_center, r);
          continue;
        }
        if (node.count > 0) {
          for (uint32_t i = node.first; i < node.first + node.count && ok; ++i) {
            const uint32_t t = h.order[i];
            glm::dvec3 q[3];
            double height = -std::numeric_limits<double>::infinity();
            for (int k = 0; k < 3; ++k) {
              q[k] = h.vertex(t, k);
              height = std::max(height, glm::dot(q[k] - p, n));
            }
            if (height <= threshold) continue;
            const glm::dvec3 c = (q[0] + q[1] + q[2]) / 3.0;
            double rt = 0.0;
            for (const glm::dvec3& x : q) rt = std::max(rt, glm::length(x - c));
            ok = add_ball(c, rt + inflate);
          }
          continue;
        }
        stack[top++] = node.second;
        stack[top++] = index + 1;
      }
      covered[v] = ok ? 1 : 0;
      counts[v] = ok ? static_cast<uint32_t>(m) : 0;
      if (ok) found[blk].insert(found[blk].end(), caps, caps + m);
    }
  });
  OccluderCaps result;
  result.covered = std::move(covered);
  result.first.assign(V + 1, 0);
  for (std::size_t v = 0; v < V; ++v) result.first[v + 1] = result.first[v] + counts[v];
  result.caps.reserve(result.first[V]);
  for (const std::vector<DirectionCap>& f : found)
    result.caps.insert(result.caps.end(), f.begin(), f.end());
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace prt::bake
