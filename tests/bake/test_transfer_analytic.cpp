// Baker tests against analytic transfer: the unshadowed (clamped-cosine) transfer vector, and
// shadowed bakes of unoccluded vertices, which must reproduce it within Monte Carlo error.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"
#include "support/transfer_references.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;
using prt::test::kPi;

namespace {

// (1/π) ∫ max(n·ω, 0) Y_k(ω) dω by the midpoint rule in the frame of n (θ ∈ [0, π/2] only,
// where the integrand is smooth, so the kink at the horizon costs nothing). An independent
// second method for rotate_zonal(clamped cosine).
std::vector<double> integrate_clamped_cosine(int order, glm::dvec3 n) {
  const int K = order * order, nt = 400, np = 800;
  glm::dvec3 t = std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  t = glm::normalize(t - n * glm::dot(n, t));
  const glm::dvec3 b = glm::cross(n, t);
  std::vector<double> sum(K, 0.0), y(K);
  const double dt = 0.5 * kPi / nt, dp = 2 * kPi / np;
  for (int i = 0; i < nt; ++i) {
    const double th = (i + 0.5) * dt;
    for (int j = 0; j < np; ++j) {
      const double ph = (j + 0.5) * dp;
      const glm::dvec3 w = std::cos(th) * n + std::sin(th) * (std::cos(ph) * t + std::sin(ph) * b);
      prt::sh::evaluate(order, w.x, w.y, w.z, y.data());
      const double weight = std::cos(th) * std::sin(th) * dt * dp / kPi;
      for (int k = 0; k < K; ++k) sum[k] += weight * y[k];
    }
  }
  return sum;
}

}  // namespace

TEST_CASE("unshadowed transfer equals the clamped cosine rotated to the normal") {
  // One vertex per normal; tiny triangles (never hit: unshadowed casts no rays).
  const std::vector<glm::dvec3> normals = {{0, 1, 0},
                                           {0, -1, 0},
                                           {1, 0, 0},
                                           {0, 0, 1},
                                           glm::normalize(glm::dvec3(1, 2, -3)),
                                           glm::normalize(glm::dvec3(-0.3, 0.1, 0.9))};
  prt::scene::Scene scene;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const glm::vec3 base(3.f * static_cast<float>(i), 0.f, 0.f);
    const auto v0 = static_cast<uint32_t>(scene.positions.size());
    for (const glm::vec3 d : {glm::vec3(0), glm::vec3(0.01f, 0, 0), glm::vec3(0, 0.01f, 0)}) {
      scene.positions.push_back(base + d);
      scene.normals.push_back(glm::vec3(normals[i]));
      scene.albedo.push_back(glm::vec3(0.5f));
    }
    scene.triangles.push_back({v0, v0 + 1, v0 + 2});
  }
  BakeOptions options;
  options.kind = prt::TransferKind::Unshadowed;
  options.order = 5;
  const auto result = bake_transfer(scene, options);
  REQUIRE(result.data.channels == 1);
  REQUIRE(result.stats.rays == 0);
  const int K = 25;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const std::vector<double> ref = integrate_clamped_cosine(5, glm::dvec3(scene.normals[3 * i]));
    for (int k = 0; k < K; ++k) {
      // Midpoint rule with 400 × 800 nodes on a smooth integrand: error ~1e-6; the baker
      // stores floats (relative 6e-8).
      CHECK(result.data.coefficients[3 * i * K + k] == Approx(0.5 * ref[k]).margin(2e-6));
    }
  }
  // The clamped cosine's zonal coefficients for n = +Y (vertex 0): Y_{1,-1}(+Y) = √(3/4π) and
  // Y_{2,0}(+Y) = −√(5/4π)/2, so T_1 = ρ/π · 1.0233267 and T_6 = −ρ/π · 0.4954159 / 2.
  CHECK(result.data.coefficients[0] == Approx(0.5 / kPi * 0.8862269).epsilon(1e-6));
  CHECK(result.data.coefficients[1] == Approx(0.5 / kPi * 1.0233267).epsilon(1e-6));
  CHECK(result.data.coefficients[2] == Approx(0.0).margin(1e-7));
  CHECK(result.data.coefficients[6] == Approx(-0.5 / kPi * 0.4954159 / 2).epsilon(1e-6));
}

// Monte Carlo bound for a shadowed bake of an unoccluded vertex: T_k is the mean of
// ρ·Y_k(ω_s) over N cosine-distributed ω_s, so its standard error is ≤ ρ·max|Y_k|/√N; for
// l ≤ 2, max|Y_k| = 0.6308 (Y20 at the poles). We allow 4 such standard errors (the Owen-
// scrambled Sobol' points do far better than independent samples, so this never flakes).
double mc_bound(double rho, int samples) {
  return 4.0 * rho * 0.6308 / std::sqrt(samples);
}

TEST_CASE("shadowed bake of an isolated quad's centre equals the unshadowed transfer") {
  // 2×2 grid on a unit quad facing +Y (cross(+Z, +X) = +Y); vertex 4 is the centre.
  prt::scene::Scene quad =
      prt::scene::make_quad({-0.5f, 0, -0.5f}, {0, 0, 1}, {1, 0, 0}, 2, 2, glm::vec3(0.6f), "quad");
  REQUIRE(quad.normals[4].y == Approx(1.0));
  BakeOptions options;
  options.order = 3;
  options.samples = 16384;
  options.ao = true;
  const auto shadowed = bake_transfer(quad, options);
  options.kind = prt::TransferKind::Unshadowed;
  const auto unshadowed = bake_transfer(quad, options);
  const double bound = mc_bound(0.6, 16384);
  for (int k = 0; k < 9; ++k)
    CHECK(shadowed.data.coefficients[4 * 9 + k] ==
          Approx(unshadowed.data.coefficients[4 * 9 + k]).margin(bound));
  // A coplanar quad never occludes its own vertices.
  for (float ao : shadowed.data.ao) CHECK(ao == 1.0f);
}

TEST_CASE("a vertex in the middle of a large plane: shadowed equals unshadowed") {
  prt::scene::Scene plane = prt::scene::make_quad({-50.f, 0, -50.f}, {0, 0, 100}, {100, 0, 0}, 10,
                                                  10, glm::vec3(0.3f, 0.3f, 0.3f), "plane");
  const std::size_t centre = 5 * 11 + 5;
  REQUIRE(plane.positions[centre].x == Approx(0.0).margin(1e-5));
  BakeOptions options;
  options.order = 3;
  options.samples = 4096;
  const auto shadowed = bake_transfer(plane, options);
  options.kind = prt::TransferKind::Unshadowed;
  const auto unshadowed = bake_transfer(plane, options);
  const double bound = mc_bound(0.3, 4096);  // = 0.012
  for (int k = 0; k < 9; ++k)
    CHECK(shadowed.data.coefficients[centre * 9 + k] ==
          Approx(unshadowed.data.coefficients[centre * 9 + k]).margin(bound));
  // Averaged over all 121 independently scrambled vertices the error shrinks by √121.
  for (int k = 0; k < 9; ++k) {
    double mean_diff = 0;
    for (std::size_t v = 0; v < plane.positions.size(); ++v)
      mean_diff += shadowed.data.coefficients[v * 9 + k] - unshadowed.data.coefficients[v * 9 + k];
    mean_diff /= static_cast<double>(plane.positions.size());
    CHECK(std::fabs(mean_diff) < bound / 11.0);
  }
}

TEST_CASE("sampling: Owen-scrambled Sobol' points form (0,m,2)-nets and are cosine distributed") {
  // Every elementary interval of area 2^-m (2^a × 2^(m−a) cells) holds exactly one of the first
  // 2^m points: the property that makes the sequence low-discrepancy, kept by Owen scrambling.
  const int m = 8, n = 1 << m;
  for (uint64_t vertex : {0ull, 1ull, 977ull}) {
    const uint64_t seed = prt::bake::hash_seed(7, vertex);
    for (int a = 0; a <= m; ++a) {
      std::vector<int> count(n, 0);
      for (int i = 0; i < n; ++i) {
        const glm::vec2 u = prt::bake::sample_sobol_2d(static_cast<uint32_t>(i), seed);
        const int cx = static_cast<int>(u.x * static_cast<float>(1 << a));
        const int cy = static_cast<int>(u.y * static_cast<float>(1 << (m - a)));
        ++count[(cx << (m - a)) | cy];
      }
      for (int c : count) REQUIRE(c == 1);
    }
  }
  // Cosine-weighted directions: E[cos θ] = 2/3, E[cos² θ] = 1/2, mean tangent part 0.
  const glm::vec3 normal = glm::normalize(glm::vec3(0.2f, -0.9f, 0.4f));
  std::vector<glm::vec3> dirs(4096);
  prt::bake::generate_cosine_directions(normal, 3, 11, 0, 4096, dirs.data());
  double c1 = 0, c2 = 0;
  glm::dvec3 mean(0.0);
  for (const glm::vec3& d : dirs) {
    REQUIRE(glm::length(d) == Approx(1.0).epsilon(1e-5));
    const double c = glm::dot(d, normal);
    REQUIRE(c >= 0.0);
    c1 += c;
    c2 += c * c;
    mean += glm::dvec3(d) - c * glm::dvec3(normal);
  }
  // Independent samples would give standard errors 0.0037 and 0.0039; QMC does better.
  CHECK(c1 / 4096 == Approx(2.0 / 3.0).margin(0.004));
  CHECK(c2 / 4096 == Approx(0.5).margin(0.004));
  CHECK(glm::length(mean / 4096.0) < 0.01);
  // Duff et al.'s basis is orthonormal even at n = −Z, where naive versions divide by zero.
  for (const glm::vec3 axis : {glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), normal}) {
    glm::vec3 t, b;
    prt::bake::build_orthonormal_basis(axis, t, b);
    CHECK(glm::dot(t, b) == Approx(0.0).margin(1e-6));
    CHECK(glm::dot(t, axis) == Approx(0.0).margin(1e-6));
    CHECK(glm::length(glm::cross(t, b) - axis) < 1e-5);
  }
  CHECK(prt::bake::round_up_to_packet(1) == 16);
  CHECK(prt::bake::round_up_to_packet(256) == 256);
  CHECK(prt::bake::round_up_to_packet(257) == 272);
}
