// Ground-truth integrator (report/ground_truth.h): constant maps in every layout, the AO
// configurations and the spherical-cavity furnace (B = ρf/(1 − ρ(1 − f))), agreement with SH
// relighting for a band-limited map, determinism, and the refinement target.
#include <cmath>
#include <random>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "bake/transfer_baker.h"
#include "numerics/constants.h"
#include "report/ground_truth.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"
#include "sh/projection.h"
#include "support/transfer_references.h"

using prt::report::GroundTruthOptions;
using prt::scene::Scene;

namespace {

using prt::numerics::kPi;

prt::sh::EnvMap constant_map(prt::sh::EnvLayout layout, int w, int h, float value) {
  prt::sh::EnvMap m;
  m.layout = layout, m.width = w, m.height = h;
  m.rgb.assign(3ull * w * h, value);
  return m;
}

// Mean of the red channel and the RMS standard error of that mean over vertices [first, end).
struct Mean {
  double value = 0, se = 0;
};
Mean mean_red(const prt::report::GroundTruthResult& r, std::size_t first, std::size_t end) {
  Mean m;
  double se2 = 0;
  for (std::size_t v = first; v < end; ++v) {
    m.value += r.radiance[3 * v];
    se2 += r.standard_error[3 * v] * r.standard_error[3 * v];
  }
  const double n = static_cast<double>(end - first);
  m.value /= n;
  m.se = std::sqrt(se2) / n;  // vertices are independent
  return m;
}

}  // namespace

TEST_CASE("image_point_direction agrees with prt::sh::direction_to_texel in every layout") {
  // Independent second method: the sh library's inverse mapping must send our continuous
  // image point back to itself (to 1e-6 texel), and texel centres must match texel_direction.
  struct Case {
    prt::sh::EnvLayout layout;
    int w, h;
  };
  const Case cases[] = {{prt::sh::EnvLayout::LatLong, 64, 32},
                        {prt::sh::EnvLayout::Angular, 48, 48},
                        {prt::sh::EnvLayout::Cross, 48, 64},
                        {prt::sh::EnvLayout::Faces, 16, 96}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases) {
    INFO(prt::sh::layout_name(c.layout));
    int tested = 0;
    for (int i = 0; i < 4000; ++i) {
      const double x = u(rng) * c.w, y = u(rng) * c.h;
      double d[3], jac, bx, by;
      if (!prt::report::image_point_direction(c.layout, c.w, c.h, x, y, d, &jac)) continue;
      REQUIRE(std::fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1.0) < 1e-12);
      REQUIRE(jac > 0);
      if (c.layout == prt::sh::EnvLayout::LatLong && (y < 1e-3 || y > c.h - 1e-3)) continue;
      REQUIRE(prt::sh::direction_to_texel(c.layout, c.w, c.h, d, &bx, &by));
      REQUIRE(bx == Approx(x).margin(1e-6));
      REQUIRE(by == Approx(y).margin(1e-6));
      ++tested;
    }
    CHECK(tested > 1000);
    // J = dω/dA integrates to 4π over the image (midpoint rule on an 8× finer grid: 0.5%).
    double total_j = 0;
    const int sub = 8;
    for (int row = 0; row < c.h * sub; ++row)
      for (int col = 0; col < c.w * sub; ++col) {
        double d[3], jac;
        if (prt::report::image_point_direction(c.layout, c.w, c.h, (col + 0.5) / sub,
                                               (row + 0.5) / sub, d, &jac))
          total_j += jac / (sub * sub);
      }
    CHECK(total_j == Approx(4.0 * kPi).epsilon(0.005));
  }
}

TEST_CASE("unoccluded point under a constant white map: B = ρ in every layout") {
  // A single up-facing quad: every vertex sees the full upper hemisphere, B = ρ·1. A wrong light
  // pdf (Jacobian) would bias the MIS estimate, so each layout is checked. Tolerance: 4 standard
  // errors of the mean over the quad's vertices plus 1e-4 for float directions.
  const Scene quad = prt::scene::make_quad(glm::vec3(-1, 0, 1), glm::vec3(2, 0, 0),
                                           glm::vec3(0, 0, -2), 2, 2, glm::vec3(0.5f));
  struct Case {
    prt::sh::EnvLayout layout;
    int w, h;
  };
  for (const Case c :
       {Case{prt::sh::EnvLayout::LatLong, 64, 32}, Case{prt::sh::EnvLayout::Angular, 64, 64},
        Case{prt::sh::EnvLayout::Cross, 48, 64}, Case{prt::sh::EnvLayout::Faces, 16, 96}}) {
    INFO(prt::sh::layout_name(c.layout));
    const prt::sh::EnvMap env = constant_map(c.layout, c.w, c.h, 1.f);
    GroundTruthOptions o;
    o.initial_samples = 2048;
    o.max_samples = 2048;
    const auto r = prt::report::compute_ground_truth(quad, env, o);
    const Mean m = mean_red(r, 0, quad.vertex_count());
    INFO("mean " << m.value << " ± " << m.se);
    CHECK(m.se < 0.01);
    CHECK(m.value == Approx(0.5).margin(4 * m.se + 1e-4));
  }
}

TEST_CASE("AO configuration: a floor point beside a wall sees ρ·(1 − occluded fraction)") {
  // A point at distance d from a wall of height H = 1 loses ½(1 − d/√(d²+H²)) of its
  // cosine-weighted sky (0.146447 at d = 1). The wall here is 40 long (long walls inflate the
  // ray caster's offset ε = 1e-4·extent), so the exact reference is Lambert's polygon form
  // factor of the finite wall; it is itself checked against the infinite-wall formula (within
  // 1.5%: the ends of a 40-long wall subtend little). The wall is black and bounces are off,
  // so B = ρ·(1 − F). Tolerance: 4 SE + 1e-3 (the ray origin sits ε ≈ 4e-3 off the vertex).
  Scene scene = prt::scene::make_quad(glm::vec3(-0.5f, 0, 0.5f), glm::vec3(1, 0, 0),
                                      glm::vec3(0, 0, -1), 1, 1, glm::vec3(0.6f), "floor");
  prt::scene::append_scene(
      scene, prt::scene::make_quad(glm::vec3(1.5f, 0, -20), glm::vec3(0, 0, 40), glm::vec3(0, 1, 0),
                                   1, 1, glm::vec3(0.0f), "wall"));
  const std::vector<glm::dvec3> wall = {{1.5, 0, -20}, {1.5, 0, 20}, {1.5, 1, 20}, {1.5, 1, -20}};
  const prt::sh::EnvMap env = constant_map(prt::sh::EnvLayout::LatLong, 64, 32, 1.f);
  GroundTruthOptions o;
  o.max_bounces = 0;
  o.initial_samples = 16384;
  o.max_samples = 16384;
  const auto r = prt::report::compute_ground_truth(scene, env, o);
  // Floor vertices 0..3 at x = −0.5 (d = 2) and x = 0.5 (d = 1).
  for (int v = 0; v < 4; ++v) {
    const double d = 1.5 - scene.positions[v].x;
    const double infinite = 0.5 * (1.0 - d / std::sqrt(d * d + 1.0));
    const double occluded =
        prt::test::polygon_form_factor(glm::dvec3(scene.positions[v]), glm::dvec3(0, 1, 0), wall);
    CHECK(occluded == Approx(infinite).epsilon(0.015));
    const double expected = 0.6 * (1.0 - occluded);
    INFO("vertex " << v << " d " << d << ": " << r.radiance[3 * v] << " ± "
                   << r.standard_error[3 * v] << " vs " << expected);
    CHECK(r.standard_error[3 * v] < 0.01);
    CHECK(r.radiance[3 * v] == Approx(expected).margin(4 * r.standard_error[3 * v] + 1e-3));
  }
}

TEST_CASE("spherical-cavity furnace with interreflection: B = ρf/(1 − ρ(1 − f))") {
  // Inside a sphere with an opening under uniform radiance 1, every point sees the opening
  // with the same cosine-weighted fraction f (a property of the sphere); with interreflection
  // B = ρf/(1 − ρ(1 − f)).
  // f of the mesh is taken per vertex by Lambert's exact polygon formula (the rim is a 32-gon,
  // the wall an inscribed polyhedron: f varies by < 2% between vertices). Tolerance: 4 SE of the
  // mean over inner vertices plus 1.5% for the polyhedral wall (a vertex's indirect light comes
  // from the faceted wall, not the smooth sphere the formula assumes).
  constexpr int kRings = 12, kSegments = 32;
  const double a = 50.0 * kPi / 180.0;
  for (const double rho : {0.5, 0.9}) {
    INFO("rho " << rho);
    const Scene cavity = prt::scene::make_spherical_cavity(1.f, static_cast<float>(a), kRings,
                                                           kSegments, glm::vec3(float(rho)));
    std::vector<glm::dvec3> rim;
    for (int i = 0; i < kSegments; ++i) rim.push_back(glm::dvec3(cavity.positions[i]));
    double f = 0;
    for (std::size_t v = kSegments; v < cavity.vertex_count(); ++v)
      f += prt::test::polygon_form_factor(glm::dvec3(cavity.positions[v]),
                                          glm::dvec3(cavity.normals[v]), rim);
    f /= static_cast<double>(cavity.vertex_count() - kSegments);
    const prt::sh::EnvMap env = constant_map(prt::sh::EnvLayout::LatLong, 32, 16, 1.f);
    GroundTruthOptions o;
    o.initial_samples = 512;
    o.max_samples = 512;
    const auto r = prt::report::compute_ground_truth(cavity, env, o);
    const Mean m = mean_red(r, kSegments, cavity.vertex_count());
    const double expected = rho * f / (1.0 - rho * (1.0 - f));
    INFO("f " << f << ": mean " << m.value << " ± " << m.se << " vs " << expected);
    CHECK(m.value == Approx(expected).margin(4 * m.se + 0.015 * expected));
    // Without interreflection the same cavity gives ρ·f (direct light only).
    o.max_bounces = 0;
    const auto direct = prt::report::compute_ground_truth(cavity, env, o);
    const Mean md = mean_red(direct, kSegments, cavity.vertex_count());
    CHECK(md.value == Approx(rho * f).margin(4 * md.se + 0.005 * rho * f));
  }
}

TEST_CASE("band-limited environment: ground truth matches SH relighting of a shadowed bake") {
  // A positive lat-long map made from order-3 SH coefficients; a box on a floor casts shadows.
  // With bounces off the ground truth is Σ_k T_k L_k for the shadowed transfer exactly (up to
  // the map's pixelisation, whose bands ≥ 3 are ~1e-4 of the total). The bake's own MC error is
  // estimated independently from two bakes with different seeds (RMS difference / √2); the
  // relative RMS difference must lie within 4× the combined RMS error.
  const double coeffs[9] = {2.0, 0.4, 0.5, -0.3, 0.15, -0.1, 0.2, 0.1, -0.15};
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong, env.width = 256, env.height = 128;
  env.rgb.resize(3ull * env.width * env.height);
  for (int row = 0; row < env.height; ++row)
    for (int col = 0; col < env.width; ++col) {
      double d[3], y[9];
      REQUIRE(prt::sh::texel_direction(env.layout, env.width, env.height, col, row, d));
      prt::sh::evaluate(3, d[0], d[1], d[2], y);
      double value = 0;
      for (int k = 0; k < 9; ++k) value += coeffs[k] * y[k];
      REQUIRE(value > 0);  // positive map
      float* p = &env.rgb[3 * (static_cast<std::size_t>(row) * env.width + col)];
      p[0] = static_cast<float>(value), p[1] = static_cast<float>(0.8 * value),
      p[2] = static_cast<float>(0.6 * value);
    }
  Scene scene = prt::scene::make_quad(glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4),
                                      8, 8, glm::vec3(0.7f), "floor");
  prt::scene::append_scene(
      scene, prt::scene::make_box(glm::vec3(-0.5f, 0, -0.5f), glm::vec3(0.5f, 1, 0.5f), 2, false,
                                  glm::vec3(0.7f)));
  const std::vector<double> light = prt::sh::project(env, 3);
  REQUIRE(light.size() == 27);
  prt::bake::BakeOptions bo;
  bo.kind = prt::TransferKind::Shadowed;
  bo.order = 3;
  bo.samples = 8192;
  const auto shade = [&](uint64_t seed) {
    bo.seed = seed;
    const auto baked = prt::bake::bake_transfer(scene, bo);
    const auto& d = baked.data;
    std::vector<double> b(3 * scene.vertex_count());
    for (std::size_t v = 0; v < scene.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c) {
        const int tc = d.channels == 3 ? c : 0;
        double s = 0;
        for (int k = 0; k < 9; ++k)
          s += d.coefficients[(v * d.channels + tc) * 9 + k] * light[c * 9 + k];
        b[3 * v + c] = s;
      }
    return b;
  };
  const std::vector<double> b1 = shade(1), b2 = shade(2);
  GroundTruthOptions o;
  o.max_bounces = 0;
  o.initial_samples = 16384;
  o.max_samples = 16384;
  const auto gt = prt::report::compute_ground_truth(scene, env, o);
  double diff2 = 0, ref2 = 0, seed2 = 0, se2 = 0;
  for (std::size_t i = 0; i < b1.size(); ++i) {
    diff2 += (b1[i] - gt.radiance[i]) * (b1[i] - gt.radiance[i]);
    seed2 += (b1[i] - b2[i]) * (b1[i] - b2[i]) / 2.0;
    se2 += gt.standard_error[i] * gt.standard_error[i];
    ref2 += gt.radiance[i] * gt.radiance[i];
  }
  const double rel = std::sqrt(diff2 / ref2), bake_err = std::sqrt(seed2 / ref2),
               gt_err = std::sqrt(se2 / ref2);
  INFO("relative RMS difference " << rel << "; bake MC error " << bake_err << ", GT SE " << gt_err);
  CHECK(gt_err < 0.02);
  CHECK(rel < 4.0 * std::sqrt(bake_err * bake_err + gt_err * gt_err) + 1e-3);
  // And it must be able to fail: a map scaled by 1.05 is rejected.
  double diff2_scaled = 0;
  for (std::size_t i = 0; i < b1.size(); ++i)
    diff2_scaled += (1.05 * b1[i] - gt.radiance[i]) * (1.05 * b1[i] - gt.radiance[i]);
  CHECK(std::sqrt(diff2_scaled / ref2) > 4.0 * std::sqrt(bake_err * bake_err + gt_err * gt_err));
}

TEST_CASE("ground truth is deterministic per seed, for any thread count and schedule") {
  const Scene scene = prt::scene::make_box(glm::vec3(-1), glm::vec3(1), 2, true, glm::vec3(0.5f));
  Scene open = scene;
  open.triangles.resize(open.triangles.size() - 4);  // drop part of one face: light gets in
  const prt::sh::EnvMap env = constant_map(prt::sh::EnvLayout::LatLong, 32, 16, 2.f);
  GroundTruthOptions o;
  o.initial_samples = 64;
  o.max_samples = 256;
  o.target_relative_se = 1e-9;  // run to max_samples
  o.threads = 1;
  const auto one = prt::report::compute_ground_truth(open, env, o);
  o.threads = 2;
  o.initial_samples = 32;  // different doubling schedule: 32, 64, 128, 256
  const auto two = prt::report::compute_ground_truth(open, env, o);
  REQUIRE(one.samples_per_vertex == 256);
  REQUIRE(two.samples_per_vertex == 256);
  // Per-sample values are identical; only the order of the pass sums differs (≤ 1e-12).
  for (std::size_t i = 0; i < one.radiance.size(); ++i)
    REQUIRE(one.radiance[i] == Approx(two.radiance[i]).epsilon(1e-12));
  CHECK_FALSE(one.reached_target);
  // Same schedule, other thread count: bit-identical.
  o.initial_samples = 64;
  o.threads = 2;
  const auto same = prt::report::compute_ground_truth(open, env, o);
  for (std::size_t i = 0; i < one.radiance.size(); ++i)
    REQUIRE(one.radiance[i] == same.radiance[i]);
  o.initial_samples = 32;
  o.seed = 99;
  const auto other = prt::report::compute_ground_truth(open, env, o);
  bool differs = false;
  for (std::size_t i = 0; i < one.radiance.size(); ++i)
    differs |= one.radiance[i] != other.radiance[i];
  CHECK(differs);
}

TEST_CASE("refinement doubles samples until the relative RMS standard error meets the target") {
  Scene scene = prt::scene::make_quad(glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4),
                                      4, 4, glm::vec3(0.7f), "floor");
  prt::scene::append_scene(
      scene, prt::scene::make_box(glm::vec3(-0.5f, 0, -0.5f), glm::vec3(0.5f, 1, 0.5f), 1, false,
                                  glm::vec3(0.7f)));
  // A small bright "sun" texel over a dim sky: a hard case for plain cosine sampling.
  prt::sh::EnvMap env = constant_map(prt::sh::EnvLayout::LatLong, 64, 32, 0.2f);
  float* sun = &env.rgb[3 * (8 * 64 + 40)];
  sun[0] = sun[1] = sun[2] = 5000.f;
  GroundTruthOptions o;
  o.initial_samples = 16;
  o.target_relative_se = 0.02;
  const auto r = prt::report::compute_ground_truth(scene, env, o);
  INFO("samples " << r.samples_per_vertex << ", s " << r.relative_rms_se);
  CHECK(r.reached_target);
  CHECK(r.relative_rms_se <= 0.02);
  CHECK(r.samples_per_vertex >= 16);
  CHECK(r.rays > 0);
  for (double x : r.radiance) REQUIRE(std::isfinite(x));
  // NaN and Inf texels are skipped and counted, not propagated.
  sun[0] = NAN;
  env.rgb[0] = INFINITY;
  o.target_relative_se = 0.05;
  const auto bad = prt::report::compute_ground_truth(scene, env, o);
  CHECK(bad.skipped_texels == 2);
  for (double x : bad.radiance) REQUIRE(std::isfinite(x));
  // Albedo ≥ 1 is refused.
  Scene white = scene;
  white.albedo[0] = glm::vec3(1.f);
  CHECK_THROWS_AS(prt::report::compute_ground_truth(white, env, o), prt::bake::BakeError);
}
