// Ray origins (scene/ray_offset.h, scene/ray_caster.h) in scenes that mix scales: unit objects on
// grounds 1e3 and 1e5 across, at the origin and 1e4 away from it. Every ambient-occlusion closed
// form (wall, well, tangent sphere, spherical cavity) must hold at contact with rays from the
// vertex origins the bakers use. The bakers themselves at contact: tests/bake/
// test_bake_mixed_scale.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "scene/orthonormal_basis.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/ray_offset.h"
#include "support/mixed_scale_scenes.h"
#include "support/transfer_references.h"

using namespace prt::scene;
using prt::test::graded;
using prt::test::graded_grid;
using prt::test::ground;
using prt::test::ground_vertex;
using prt::test::kClosedFormTolerance;
using prt::test::kMixedScaleVariants;
using prt::test::MixedScaleVariant;
using prt::test::occluded_fraction;

namespace {

using prt::numerics::kPi;

// A vertical tube of radius R and height h standing on y = 0 around (cx, cz), normals inward.
Scene tube(float cx, float cz, float R, float h, int segments) {
  Scene s;
  for (int ring = 0; ring < 2; ++ring)
    for (int k = 0; k < segments; ++k) {
      const double phi = 2 * kPi * k / segments;
      const float c = static_cast<float>(std::cos(phi)), sn = static_cast<float>(std::sin(phi));
      s.positions.push_back({cx + R * c, static_cast<float>(ring) * h, cz + R * sn});
      s.normals.push_back({-c, 0.f, -sn});
      s.albedo.push_back(glm::vec3(0.5f));
    }
  const uint32_t S = static_cast<uint32_t>(segments);
  for (uint32_t k = 0; k < S; ++k) {
    const uint32_t a = k, b = (k + 1) % S, c = b + S, d = a + S;
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
  }
  ScenePrimitive p;
  p.name = "tube";
  p.vertex_count = 2 * S;
  p.triangle_count = 2 * S;
  p.albedo = glm::vec3(0.5f);
  s.primitives.push_back(p);
  return s;
}

// Cosine-weighted visible fraction from vertex v through the bakers' origin, with 128 × 128
// jittered strata of the cosine hemisphere (Malley's method; 16384 rays, stratified error ≪ 1e-3
// here).
double stratified_ao(const RayCaster& caster, const Scene& scene, uint32_t v) {
  const glm::vec3 n = glm::normalize(scene.normals[v]);
  glm::vec3 t, b;
  build_orthonormal_basis(n, t, b);
  const glm::vec3 o = caster.vertex_origin(v);
  constexpr int kStrata = 128;
  prt::numerics::SplitMix64 rng{v};
  auto uniform = [&rng] { return static_cast<float>(rng.next_u64() >> 40) * 0x1p-24f; };
  int visible = 0;
  for (int i = 0; i < kStrata; ++i)
    for (int j = 0; j < kStrata; ++j) {
      const glm::vec2 u((static_cast<float>(i) + uniform()) / kStrata,
                        (static_cast<float>(j) + uniform()) / kStrata);
      const prt::numerics::Vec3<float> l =
          prt::numerics::sample_cosine_hemisphere(prt::numerics::Vec2<float>{u.x, u.y});
      const glm::vec3 d = glm::normalize(l.x * t + l.y * b + l.z * n);
      visible += caster.occluded(o, d, 0.f, INFINITY) ? 0 : 1;
    }
  return visible / double(kStrata * kStrata);
}

}  // namespace

TEST_CASE("ray offsets follow the point's rounding and its own triangles, not the scene") {
  // The same unit triangle alone, and beside a ground 1e5 across: the same ε at its vertices.
  Scene small = make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, 1, 1, glm::vec3(0.5f), "unit");
  Scene mixed = small;
  append_scene(mixed, make_quad({-5e4f, -1, -5e4f}, {0, 0, 1e5f}, {1e5f, 0, 0}, 2, 2,
                                glm::vec3(0.5f), "ground"));
  const VertexRayStarts a = compute_vertex_ray_starts(small);
  const VertexRayStarts b = compute_vertex_ray_starts(mixed);
  for (std::size_t v = 0; v < small.vertex_count(); ++v) {
    CHECK(a.offset[v] == b.offset[v]);
    CHECK(a.unreachable_height[v] == b.unreachable_height[v]);
    // Small against the old rule's 1e-4 × the mixed scene's diagonal (14 units).
    CHECK(b.offset[v] < 1e-5f);
    CHECK(a.unreachable_height[v] > 0.0);
  }
  // Far from the origin the float spacing sets the offset: 4 ulps at 1e4 (≈ 4.9e-3).
  const double far = ray_offset(glm::dvec3(1e4, 0, 0), 1.0);
  CHECK(far == Approx(4 * std::ldexp(1e4, -23) + std::ldexp(1.0, -18)).epsilon(1e-12));
  CHECK(far < 5e-3);
  // Hit points: the triangle's own edge and its vertices' spacing count.
  CHECK(triangle_ray_offset(small, 0, glm::dvec3(0.5, 0, -0.5)) ==
        Approx(4 * std::ldexp(1.0, -23) + std::ldexp(std::sqrt(2.0), -18)).epsilon(1e-9));
}

TEST_CASE("AO beside a unit wall at contact, on grounds 1e3 and 1e5 across, near and far") {
  // Wall z = 1 facing −Z, height H = 1, x ∈ [−50, 50], graded toward its foot. Probes on the
  // floor at x = 0, distance d from the wall: visible ½ + ½·d/√(d² + H²) (d → 0: ½, the
  // infinite wall). The wall's finite length hides < H²d/(3π·50³) ≈ 1e-6.
  const std::vector<float> heights = {0.f,  0.002f, 0.005f, 0.01f, 0.02f, 0.05f,
                                      0.1f, 0.2f,   0.35f,  0.5f,  0.7f,  1.f};
  const float distances[] = {0.01f, 0.1f, 0.5f, 1.f};
  for (const MixedScaleVariant& var : kMixedScaleVariants) {
    Scene s = ground(var.ground_half, {0.f}, {0.99f, 0.9f, 0.5f, 0.f});
    append_scene(s, graded_grid({0, 0, 1}, {0, 1, 0}, heights, {1, 0, 0},
                                graded({0.f}, 3.f, 0.25f, 50.f), glm::vec3(0.5f), "wall"));
    std::vector<uint32_t> probes;
    for (float d : distances) probes.push_back(ground_vertex(s, 0.f, 1.f - d));
    const Scene moved = prt::test::transformed(s, 1.f, var.shift);
    const RayCaster caster(moved);
    for (std::size_t i = 0; i < probes.size(); ++i) {
      const double d = distances[i];
      const double expected = 0.5 + 0.5 * d / std::sqrt(d * d + 1.0);
      INFO(var.label() << ", d = " << d);
      CHECK(stratified_ao(caster, moved, probes[i]) ==
            Approx(expected).margin(kClosedFormTolerance));
    }
  }
}

TEST_CASE("AO of ground points beside a tangent unit sphere, at any scale mix") {
  // Sphere R = 1 resting on the ground at the origin (its −Y pole touches it). Probes at D from
  // the contact point: visible 1 − (R/L)³, L = √(D² + R²). The inscribed polyhedron (96 rings)
  // occludes up to 0.5·(1 − cos(π/96)) ≈ 3e-4 of the hemisphere less.
  const float distances[] = {0.25f, 0.5f, 1.f, 2.f};
  for (const MixedScaleVariant& var : kMixedScaleVariants) {
    Scene s = ground(var.ground_half, {0.f}, {0.25f, 0.5f, 1.f, 2.f});
    append_scene(s, make_uv_sphere({0, 1, 0}, 1.f, 96, 192, false, glm::vec3(0.5f), "sphere"));
    const Scene moved = prt::test::transformed(s, 1.f, var.shift);
    const RayCaster caster(moved);
    for (float D : distances) {
      const double L = std::sqrt(double(D) * D + 1.0);
      INFO(var.label() << ", D = " << D);
      CHECK(stratified_ao(caster, moved, ground_vertex(s, 0.f, D)) ==
            Approx(1.0 - std::pow(1.0 / L, 3.0)).margin(kClosedFormTolerance));
    }
  }
}

TEST_CASE("AO at the bottom of a unit well and inside a unit cavity, at any scale mix") {
  // Well: a tube R = 1, h = 1.5 standing on the ground around (−10, 0); the ground vertex at its
  // centre sees the sky with R²/(R²+h²) (the inscribed 256-gon: −0.01% of that).
  // Cavity: the inside of a unit sphere centred 3 above the ground at (10, 0), open at the top
  // with half-angle 60°: every inner point sees the opening with f = (1 − cos 60°)/2 = 0.25
  // (the inscribed 128-gon opening: −0.04% of f).
  for (const MixedScaleVariant& var : kMixedScaleVariants) {
    Scene s = ground(var.ground_half, {-10.f}, {0.f});
    append_scene(s, tube(-10.f, 0.f, 1.f, 1.5f, 256));
    const std::size_t cavity_first = s.vertex_count();
    Scene cavity =
        make_spherical_cavity(1.f, static_cast<float>(kPi / 3), 32, 128, glm::vec3(0.5f));
    append_scene(s, prt::test::transformed(cavity, 1.f, {10.f, 3.f, 0.f}));
    const Scene moved = prt::test::transformed(s, 1.f, var.shift);
    const RayCaster caster(moved);
    INFO(var.label());
    CHECK(stratified_ao(caster, moved, ground_vertex(s, -10.f, 0.f)) ==
          Approx(1.0 / (1.0 + 1.5 * 1.5)).margin(kClosedFormTolerance));
    // The bottom pole (last vertex), a vertex half-way up, and one next to the rim.
    for (const std::size_t v :
         {s.vertex_count() - 1, cavity_first + 16 * 128 + 5, cavity_first + 128 + 77}) {
      INFO("cavity vertex " << v - cavity_first);
      CHECK(stratified_ao(caster, moved, static_cast<uint32_t>(v)) ==
            Approx(0.25).margin(kClosedFormTolerance));
    }
  }
}

TEST_CASE("vertices of huge tilted triangles see their whole hemisphere") {
  // A ground 1e5 across in 2 × 2 quads (one vertex at the centre), tilted so that no coordinate is
  // exact, at the origin and 1e4 away: the plane-distance error of Embree's triangle test grows
  // with the triangle (the 2^-18·L term of ε), so an offset from the point's rounding alone would
  // let rays from the inner vertices re-hit their own triangles.
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.9f, 0.2f));
  const glm::vec3 u = glm::normalize(glm::cross(n, glm::vec3(0, 0, 1)));
  const glm::vec3 v = glm::cross(u, n);
  for (const glm::vec3 shift : {glm::vec3(0.f), glm::vec3(1e4f, 3e3f, -1e4f)}) {
    const Scene plane = prt::test::transformed(
        make_quad(-5e4f * (u + v), 1e5f * u, 1e5f * v, 2, 2, glm::vec3(0.5f), "tilted"), 1.f,
        shift);
    const RayCaster caster(plane);
    for (uint32_t vtx = 0; vtx < plane.vertex_count(); ++vtx) {
      CAPTURE(shift.x, vtx);
      REQUIRE(occluded_fraction(caster, plane, vtx, 4096) == 0.0);
    }
  }
}

TEST_CASE("a RayCaster for some vertices starts their rays where the whole one does, bit for bit") {
  // Sharp box edges (nudged starts), a far ground 1e4 across (the largest ε is its vertices'),
  // and a vertex on no triangle (ε = 4·U alone).
  Scene s = make_box({0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, 3, false, glm::vec3(0.5f), "box");
  append_scene(s, make_quad({-5e3f, -1, -5e3f}, {0, 0, 1e4f}, {1e4f, 0, 0}, 3, 3, glm::vec3(0.5f),
                            "ground"));
  s.positions.push_back({7e3f, 2.f, 0.f});
  s.normals.push_back({0.f, 1.f, 0.f});
  s.albedo.push_back(glm::vec3(0.5f));
  const RayCaster all(s);
  const VertexRayStarts& starts = all.vertex_ray_starts();
  float largest = 0.f;
  for (const float eps : starts.offset) largest = std::max(largest, eps);
  // Exact: the same float, found without per-vertex arrays.
  CHECK(max_vertex_ray_offset(s) == static_cast<double>(largest));
  CHECK(all.max_ray_offset() == static_cast<double>(largest));
  // Every other vertex, backwards (a shard's rows are a permutation's slice).
  std::vector<uint32_t> some;
  for (uint32_t v = static_cast<uint32_t>(s.positions.size()); v-- > 0;)
    if (v % 2 == 0) some.push_back(v);
  const RayCaster part(s, some.data(), some.size());
  CHECK(part.max_ray_offset() == all.max_ray_offset());
  CHECK(part.vertex_ray_starts().offset.empty());
  int nudged = 0;
  for (const uint32_t v : some) {
    const glm::vec3 a = all.vertex_origin(v), b = part.vertex_origin(v);
    INFO("vertex " << v);
    CHECK(a.x == b.x);
    CHECK(a.y == b.y);
    CHECK(a.z == b.z);
    const glm::vec3 straight = s.positions[v] + starts.offset[v] * glm::normalize(s.normals[v]);
    nudged += a != straight;
  }
  CHECK(nudged > 0);  // the comparison covers the tangential nudge, not only ε·n
}
