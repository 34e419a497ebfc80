// Tests of bake/adaptive/occlusion_bound.h: the ray-free bound on the blockable projected solid
// angle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bake/adaptive/occlusion_bound.h"
#include "bake/adaptive/scene_analysis.h"
#include "bake/adaptive/triangle_hierarchy.h"
#include "bake/sampling.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"

using namespace prt::bake;
using namespace prt::scene;

namespace {

// The 24×24 floor of the adaptive proof with one ball: far corners see the ball tiny.
Scene floor_with_ball() {
  Scene s = make_quad({-12.f, 0.f, 12.f}, {24.f, 0.f, 0.f}, {0.f, 0.f, -24.f}, 48, 48,
                      glm::vec3(0.5f), "ground");
  append_scene(s, make_uv_sphere({0.f, 0.7f, 0.f}, 0.7f, 16, 32, false, glm::vec3(0.5f), "ball"));
  return s;
}

// G_v measured with rays: the occluded fraction of 4096 cosine-distributed scrambled Sobol'
// directions (the cosine pdf makes the occluded fraction an estimate of (1/π)∫ cos over the
// blocked set); for these smooth silhouettes the error is far below 2e-3.
double measured_g(const RayCaster& caster, const Scene& scene, uint32_t v) {
  const glm::vec3 n = glm::normalize(scene.normals[v]);
  const glm::vec3 o = caster.vertex_origin(v);
  int hit = 0;
  glm::vec3 dirs[kPacketSize];
  bool occ[kPacketSize];
  for (uint32_t first = 0; first < 4096; first += kPacketSize) {
    generate_cosine_directions(n, 3, v, first, kPacketSize, dirs);
    caster.occluded_packet(o, dirs, kPacketSize, INFINITY, occ);
    for (bool b : occ) hit += b;
  }
  return hit / 4096.0;
}

}  // namespace

TEST_CASE("ball bound: at least the exact projected solid angle of a cap, and tight when small") {
  const glm::dvec3 n(0, 1, 0);
  for (double d : {1.5, 3.0, 10.0, 100.0}) {
    const double r = 0.7, sin_a = r / d;
    // A cap around the normal: (1/π)∫ cos over it = sin²α exactly.
    const double exact = sin_a * sin_a;
    const double b = ball_projected_solid_angle_bound({0, d, 0}, r, n);
    CAPTURE(d, exact, b);
    CHECK(b >= exact * (1 - 1e-12));
    CHECK(b <= 2.0 * exact);  // 2(1 − cos α) ≤ 2 sin²α
  }
  // Entirely below the tangent plane: nothing can be hit.
  CHECK(ball_projected_solid_angle_bound({3, -1, 0}, 0.5, n) == 0.0);
  // Inside the ball: no bound.
  CHECK(std::isinf(ball_projected_solid_angle_bound({0.1, 0, 0}, 0.5, n)));
  // Near the horizon the bound carries the small cosine: a ball at elevation 8° (half-angle 4°)
  // gets cos(82° − 4°) ≈ 0.21 of the same ball overhead.
  CHECK(ball_projected_solid_angle_bound({10, 1.4, 0}, 0.7, n) <
        0.22 * ball_projected_solid_angle_bound({0, 10.1, 0}, 0.7, n));
}

TEST_CASE("occlusion bound: never below the occluded fraction measured with rays") {
  const Scene scene = floor_with_ball();
  const VertexRayStarts starts = compute_vertex_ray_starts(scene);
  const OcclusionBounds b = bound_occlusion(scene, starts, 1e30);
  RayCaster caster(scene);
  std::size_t checked = 0, useful = 0;
  for (uint32_t v = 0; v < scene.vertex_count(); v += 7) {
    const double g = measured_g(caster, scene, v);
    CAPTURE(v, g, b.bound[v]);
    REQUIRE(static_cast<double>(b.bound[v]) >= g - 2e-3);
    // The hierarchy's groups are coarser than single triangles, never looser than 3× here.
    const double brute = occlusion_bound_brute_force(scene, v, starts);
    CHECK(static_cast<double>(b.bound[v]) <= 3.0 * brute + 1e-12);
    ++checked;
    useful += b.bound[v] < 0.01f;
  }
  CHECK(checked > 300);
  // Most of the floor is far from the ball: its bound is small (that is what makes it useful).
  CHECK(useful > checked / 2);
}

// The hierarchy's parallel build (large groups' halves split concurrently) against the serial
// reference: the same triangle order and the same nodes, field for field, on a scene large
// enough to split in parallel (a 240×240-cell ground, 115k triangles, beside two objects, so
// that the first splits fall between primitives). Exact equality: the splits are the same
// computations on disjoint ranges, only their numbering is deferred.
TEST_CASE("triangle hierarchy: the parallel build equals the serial one node for node") {
  using prt::bake::HierarchyBuild;
  prt::scene::Scene scene = prt::scene::make_quad(
      {-12.f, 0.f, 12.f}, {24.f, 0.f, 0.f}, {0.f, 0.f, -24.f}, 240, 240, glm::vec3(0.5f), "ground");
  prt::scene::append_scene(
      scene, prt::scene::make_uv_sphere({0.f, 1.f, 0.f}, 1.f, 32, 64, false, glm::vec3(0.5f)));
  prt::scene::append_scene(
      scene, prt::scene::make_box({2.f, 0.f, -1.f}, {3.f, 1.f, 1.f}, 8, false, glm::vec3(0.5f)));
  REQUIRE(scene.triangles.size() > 100000);
  const prt::bake::TriangleHierarchy a =
      prt::bake::build_triangle_hierarchy(scene, HierarchyBuild::Serial);
  const prt::bake::TriangleHierarchy b =
      prt::bake::build_triangle_hierarchy(scene, HierarchyBuild::Parallel);
  REQUIRE(a.order == b.order);
  REQUIRE(a.nodes.size() == b.nodes.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const auto& x = a.nodes[i];
    const auto& y = b.nodes[i];
    differing += x.first != y.first || x.count != y.count || x.size != y.size ||
                 x.second != y.second || x.box_center != y.box_center || x.box_half != y.box_half ||
                 x.ball_center != y.ball_center || x.ball_radius != y.ball_radius;
  }
  CHECK(differing == 0);
}

// The second method: every group's box and ball from a plain pass over its own vertices, the
// formulas of triangle_hierarchy.h (box of the vertices, ball centred on it, radius to the
// farthest vertex). The build derives boxes bottom up and prunes the radius search, which must
// give these values bit for bit, also far from the origin (where rounding is coarsest).
TEST_CASE("triangle hierarchy: every group's box and ball equal a pass over its vertices") {
  for (const glm::vec3 offset : {glm::vec3(0.f), glm::vec3(3.0e4f, -1.7e4f, 5.1e4f)}) {
    Scene scene = floor_with_ball();
    append_scene(scene, make_box({2.f, 0.f, -1.f}, {3.f, 1.f, 1.f}, 8, false, glm::vec3(0.5f)));
    for (glm::vec3& p : scene.positions) p += offset;
    const TriangleHierarchy h = build_triangle_hierarchy(scene);
    REQUIRE(h.nodes.size() > 1000);
    std::size_t differing = 0;
    for (const TriangleHierarchy::Node& node : h.nodes) {
      glm::dvec3 lo(INFINITY), hi(-INFINITY);
      for (uint32_t j = node.first; j < node.first + node.size; ++j)
        for (int k = 0; k < 3; ++k) {
          lo = glm::min(lo, h.vertex(h.order[j], k));
          hi = glm::max(hi, h.vertex(h.order[j], k));
        }
      const glm::dvec3 center = 0.5 * (lo + hi);
      double r2 = 0.0;
      for (uint32_t j = node.first; j < node.first + node.size; ++j)
        for (int k = 0; k < 3; ++k) {
          const glm::dvec3 d = h.vertex(h.order[j], k) - center;
          r2 = std::max(r2, glm::dot(d, d));
        }
      differing += node.box_center != center || node.box_half != 0.5 * (hi - lo) ||
                   node.ball_center != center || node.ball_radius != std::sqrt(r2);
    }
    CHECK(differing == 0);
  }
}
