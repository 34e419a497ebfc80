// Ambient occlusion (cosine-weighted visible fraction) against GUIDE.md's analytic values and
// exact form factors, plus robustness: closed boxes, scale invariance, no self-shadowing acne.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"
#include "support/transfer_references.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;

namespace {

BakeOptions ao_options(int samples) {
  BakeOptions o;
  o.order = 1;
  o.samples = samples;
  o.ao = true;
  o.bent_normals = true;
  return o;
}

// 4 standard errors of a mean of `count` independent Bernoulli(p) visibility samples.
double binomial_bound(double p, double count) {
  return 4.0 * std::sqrt(p * (1 - p) / count);
}

}  // namespace

TEST_CASE("AO beside a wall of height H at distance d") {
  // Floor strip facing +Y (cross(+Z, +X) = +Y): rows z = −1 (d = 2) and z = 0 (d = 1),
  // x ∈ [−2, 2] in 20 steps; vertex (i, j) at index j·2 + i, i = 0 → z = −1, i = 1 → z = 0.
  prt::scene::Scene scene =
      prt::scene::make_quad({-2.f, 0, -1.f}, {0, 0, 1}, {4, 0, 0}, 1, 20, glm::vec3(0.5f), "floor");
  // Wall z = 1, height H = 1, x ∈ [−20, 20]. Edge effect: the cosine-weighted fraction of the
  // infinite wall beyond |x| > L from a probe is ≤ 2∫_L^∞∫_0^H y d /(π x⁴) dy dx = H²d/(3πL³);
  // probes have |x| ≤ 2, so L ≥ 18 and the missing occlusion is < 2e-5 for d ≤ 2.
  prt::scene::append_scene(scene, prt::scene::make_quad({-20.f, 0, 1.f}, {40, 0, 0}, {0, 1, 0}, 8,
                                                        1, glm::vec3(0.5f), "wall"));
  const int samples = 4096;
  const auto result = bake_transfer(scene, ao_options(samples));
  for (int row = 0; row < 2; ++row) {
    const double d = row == 1 ? 1.0 : 2.0, H = 1.0;
    const double occluded = 0.5 * (1.0 - d / std::sqrt(d * d + H * H));  // d = H = 1: 0.146447
    double mean = 0;
    for (int j = 0; j <= 20; ++j)
      mean += 1.0 - result.data.ao[static_cast<std::size_t>(j * 2 + row)];
    mean /= 21;
    // Rays start ε = 1e-4·extent ≈ 4e-3 above the floor, which lowers the wall by 4e-3:
    // −7e-4 on the d = 1 value. Plus 4 standard errors of 21 × 4096 samples (0.005 at d = 1).
    CHECK(mean == Approx(occluded).margin(binomial_bound(occluded, 21.0 * samples) + 1e-3));
  }
  CHECK(1.0 - 0.5 * (1.0 - 1.0 / std::sqrt(2.0)) == Approx(1 - 0.146447).epsilon(1e-6));
}

TEST_CASE("AO at the bottom of a well is R²/(R²+h²)") {
  const float R = 1.f, h = 1.5f;
  const int segments = 64;
  const prt::scene::Scene well = prt::scene::make_well(R, h, segments, 4, glm::vec3(0.5f));
  const prt::scene::ScenePrimitive* bottom = nullptr;
  for (const auto& p : well.primitives)
    if (p.name == "well_bottom") bottom = &p;
  REQUIRE(bottom != nullptr);
  const std::size_t centre = bottom->first_vertex;
  REQUIRE(well.positions[centre].x == Approx(0.0).margin(1e-6));
  REQUIRE(well.positions[centre].y == Approx(-h));
  const int samples = 4096;
  const auto result = bake_transfer(well, ao_options(samples));
  // Exact reference for the mesh: the opening is the inscribed 64-gon at y = 0 (the wall's top
  // circle), whose form factor from any bottom point is given by Lambert's formula (the prism
  // is convex, so nothing else blocks the view). From the centre it differs from the disc's
  // R²/(R²+h²) = 0.3077 by the polygon's smaller area (−0.1%).
  std::vector<glm::dvec3> rim;
  for (std::size_t v = 0; v < bottom->first_vertex; ++v)
    if (std::fabs(well.positions[v].y) < 1e-6f) rim.push_back(glm::dvec3(well.positions[v]));
  REQUIRE(rim.size() == static_cast<std::size_t>(segments));
  const double disc = R * R / (R * R + h * h);
  auto reference = [&](std::size_t v) {
    return prt::test::polygon_form_factor(glm::dvec3(well.positions[v]), {0, 1, 0}, rim);
  };
  CHECK(reference(centre) == Approx(disc).epsilon(0.003));
  CHECK(result.data.ao[centre] ==
        Approx(reference(centre)).margin(binomial_bound(reference(centre), samples)));
  // Every bottom vertex off the wall (radius < R) against its own exact value; the mean
  // deviation over ~190 vertices × 4096 samples must be within 4σ ≈ 0.002.
  double mean_dev = 0;
  int count = 0;
  for (std::size_t v = bottom->first_vertex; v < bottom->first_vertex + bottom->vertex_count; ++v) {
    if (glm::length(glm::vec2(well.positions[v].x, well.positions[v].z)) > 0.99f * R) continue;
    const double ref = reference(v);
    CHECK(result.data.ao[v] == Approx(ref).margin(binomial_bound(ref, samples)));
    mean_dev += result.data.ao[v] - ref;
    ++count;
  }
  REQUIRE(count > 100);
  CHECK(std::fabs(mean_dev / count) < binomial_bound(disc, 1.0 * count * samples));
  // The bent normal of the bottom centre points straight up (the opening is symmetric).
  CHECK(result.data.bent_normals[3 * centre + 1] == Approx(1.0).margin(1e-3));
}

TEST_CASE("AO of a ground point beside a tangent sphere is 1 − (R/L)³") {
  const float R = 1.f;
  // Ground facing +Y: vertex (i, j) at z = −3 + 0.5 i, x = −3 + 0.5 j, index j·13 + i.
  prt::scene::Scene scene = prt::scene::make_quad({-3.f, 0, -3.f}, {0, 0, 6}, {6, 0, 0}, 12, 12,
                                                  glm::vec3(0.5f), "ground");
  const std::size_t ground = scene.positions.size();
  prt::scene::append_scene(
      scene, prt::scene::make_uv_sphere({0, R, 0}, R, 48, 96, false, glm::vec3(0.5f), "sphere"));
  const int samples = 1024;
  const auto result = bake_transfer(scene, ao_options(samples));
  // The sphere lies entirely above every ground point's horizon, so its form factor is
  // cos θ·(R/L)² = (R/L)³ (θ from the normal to the centre, cos θ = R/L).
  // The inscribed polyhedron (radial deficit ≤ R(1 − cos(π/48)) = 2.1e-3 R) occludes up to
  // ~0.5% less; we allow 0.005 × occlusion on top of the sampling bound.
  double mean_dev = 0, mean_occ = 0;
  int count = 0;
  for (std::size_t v = 0; v < ground; ++v) {
    const double D = std::hypot(scene.positions[v].x, scene.positions[v].z);
    if (D < 0.5) continue;  // at the contact point the sphere touches the vertex
    const double L = std::sqrt(D * D + R * R), occ = std::pow(R / L, 3.0);
    INFO("ground vertex at D = " << D);
    CHECK(result.data.ao[v] ==
          Approx(1.0 - occ).margin(binomial_bound(1.0 - occ, samples) + 0.005 * occ));
    mean_dev += result.data.ao[v] - (1.0 - occ);
    mean_occ += occ;
    ++count;
  }
  REQUIRE(count == 168);
  // Mean over 168 vertices: 4σ of 168 × 1024 samples (≤ 0.005) plus the polyhedron deficit.
  CHECK(std::fabs(mean_dev / count) <
        binomial_bound(0.5, 168.0 * samples) + 0.005 * mean_occ / count);
  // GUIDE.md's example: D = 1 from the contact point, L = √2: visible 1 − 2^(−3/2) = 0.646447.
  CHECK(1.0 - std::pow(1.0 / std::sqrt(2.0), 3.0) == Approx(0.646447).epsilon(1e-6));
}

TEST_CASE("AO is zero everywhere inside a closed box with inward normals") {
  const prt::scene::Scene box =
      prt::scene::make_box({-1.f, -2.f, -1.5f}, {1.f, 0.5f, 3.f}, 6, true, glm::vec3(0.5f));
  const auto result = bake_transfer(box, ao_options(256));
  std::size_t leaks = 0;
  for (float ao : result.data.ao) leaks += ao != 0.f;
  // Every vertex, including those on edges and corners: no ray may escape.
  CHECK(leaks == 0);
  // Shadowed transfer is then exactly zero too.
  for (float t : result.data.coefficients) REQUIRE(t == 0.f);
}

TEST_CASE("AO is scale invariant and flat planes have no self-shadowing acne") {
  // A plane alone: every vertex sees the whole hemisphere, exactly, at any scale and far from
  // the origin (where float spacing is coarse).
  const prt::scene::Scene plane = prt::scene::make_quad({-1.f, 0, -1.f}, {0, 0, 2}, {2, 0, 0}, 16,
                                                        16, glm::vec3(0.5f), "plane");
  for (const float s : {1e-3f, 1.f, 1e4f}) {
    for (const float offset : {0.f, 3e3f}) {
      const auto r =
          bake_transfer(prt::test::transformed(plane, s, glm::vec3(offset * s)), ao_options(256));
      std::size_t bad = 0;
      for (float ao : r.data.ao) bad += ao != 1.f;
      INFO("scale " << s << ", offset " << offset * s);
      CHECK(bad == 0);
    }
  }
  // Plane + box + sphere: AO at 1e-3 and 1e4 must match the unit-scale bake. Identical
  // directions are cast, so only rays grazing an edge may flip: allow 2/N per vertex and a
  // tiny mean difference.
  prt::scene::Scene scene = plane;
  prt::scene::append_scene(scene, prt::scene::make_box({-0.3f, 0, -0.3f}, {0.3f, 0.4f, 0.3f}, 3,
                                                       false, glm::vec3(0.5f), "box"));
  prt::scene::append_scene(scene, prt::scene::make_uv_sphere({0.6f, 0.2f, 0.5f}, 0.2f, 16, 32,
                                                             false, glm::vec3(0.5f), "sphere"));
  const auto ref = bake_transfer(scene, ao_options(256));
  double occluded_sum = 0;
  for (float ao : ref.data.ao) occluded_sum += 1.0 - ao;
  REQUIRE(occluded_sum > 10.0);  // the scene does occlude
  for (const float s : {1e-3f, 1e4f}) {
    const auto r = bake_transfer(prt::test::transformed(scene, s), ao_options(256));
    double max_diff = 0, mean_diff = 0;
    for (std::size_t v = 0; v < ref.data.ao.size(); ++v) {
      const double diff = std::fabs(r.data.ao[v] - ref.data.ao[v]);
      max_diff = std::max(max_diff, diff);
      mean_diff += diff / static_cast<double>(ref.data.ao.size());
    }
    INFO("scale " << s);
    CHECK(max_diff <= 2.0 / 256);
    CHECK(mean_diff < 1e-3);
  }
}

TEST_CASE("edge vertices of a box (faces not sharing vertices) are not self-occluded") {
  // A vertex on a box edge lies in the plane of the neighbouring face; a ray leaving it would
  // hit that face at t = 0 unless the origin is nudged into its own face. On an outward box,
  // the top face (+Y) sees the whole sky from every vertex, corners and edges included.
  const prt::scene::Scene box =
      prt::scene::make_box({-1.f, -1.f, -1.f}, {1.f, 1.f, 1.f}, 4, false, glm::vec3(0.5f));
  const auto result = bake_transfer(box, ao_options(256));
  std::size_t top = 0, bad = 0;
  for (std::size_t v = 0; v < box.positions.size(); ++v) {
    if (box.normals[v].y < 0.5f) continue;
    ++top;
    bad += result.data.ao[v] != 1.f;
  }
  CHECK(top == 25);
  CHECK(bad == 0);
  // Every face of a lone convex box sees nothing but sky: AO 1 everywhere.
  for (std::size_t v = 0; v < box.positions.size(); ++v) REQUIRE(result.data.ao[v] == 1.f);
}
