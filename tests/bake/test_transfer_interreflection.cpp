// Interreflected transfer: the spherical-cavity furnace (B = ρf/(1 − ρ(1 − f))),
// the stiff ρ = 0.999 case, monotone bounce energy and Jacobi-vs-Krylov agreement, and the
// solver's gather (y = diag(ρ)·H·x) against a plain loop.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/interreflection_solver.h"
#include "bake/transfer_baker.h"
#include "numerics/rng.h"
#include "scene/procedural_mesh.h"
#include "support/transfer_references.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;

namespace {

constexpr int kRings = 16, kSegments = 32;

struct CavityStats {
  double f_mesh = 0;      // mean exact form factor of the rim polygon from the inner vertices
  double f_analytic = 0;  // (1 − cos a)/2 of the smooth sphere
  double mean_ao = 0;
  double mean_exit = 0;     // mean of T_0·√(4π) over the inner vertices (sky radiance 1)
  double max_ao_error = 0;  // max |AO_v − f_v|
};

// Inner vertices exclude ring 0 (the rim itself, where the opening is seen edge-on).
CavityStats measure_cavity(const prt::scene::Scene& cavity, const prt::bake::BakeResult& r,
                           double half_angle) {
  CavityStats s;
  s.f_analytic = (1.0 - std::cos(half_angle)) / 2.0;
  std::vector<glm::dvec3> rim;
  for (int i = 0; i < kSegments; ++i) rim.push_back(glm::dvec3(cavity.positions[i]));
  const std::size_t V = cavity.positions.size();
  const double sqrt4pi = std::sqrt(4.0 * prt::test::kPi);
  const int K = static_cast<int>(r.data.coefficients_per_channel());
  for (std::size_t v = kSegments; v < V; ++v) {
    const double f = prt::test::polygon_form_factor(glm::dvec3(cavity.positions[v]),
                                                    glm::dvec3(cavity.normals[v]), rim);
    s.f_mesh += f;
    if (!r.data.ao.empty()) {
      s.mean_ao += r.data.ao[v];
      s.max_ao_error = std::max(s.max_ao_error, std::fabs(r.data.ao[v] - f));
    }
    s.mean_exit += r.data.coefficients[v * K] * sqrt4pi;
  }
  const double n = static_cast<double>(V - kSegments);
  s.f_mesh /= n;
  s.mean_ao /= n;
  s.mean_exit /= n;
  return s;
}

double furnace(double rho, double f) {
  return rho * f / (1.0 - rho * (1.0 - f));
}

}  // namespace

TEST_CASE("spherical-cavity furnace: exit radiance is ρf/(1 − ρ(1 − f)) and AO is f") {
  const double a = 50.0 * prt::test::kPi / 180.0;
  for (const double rho : {0.5, 0.9, 0.99}) {
    const prt::scene::Scene cavity = prt::scene::make_spherical_cavity(
        1.f, static_cast<float>(a), kRings, kSegments, glm::vec3(static_cast<float>(rho)));
    BakeOptions o;
    o.kind = prt::TransferKind::Interreflected;
    o.order = 1;
    o.samples = 1024;
    o.ao = true;
    o.bounce_tolerance = 1e-6;
    const auto r = bake_transfer(cavity, o);
    const CavityStats s = measure_cavity(cavity, r, a);
    INFO("rho " << rho << ": f mesh " << s.f_mesh << " (smooth sphere " << s.f_analytic
                << "), mean AO " << s.mean_ao << ", exit " << s.mean_exit << " vs "
                << furnace(rho, s.f_mesh) << "; iterations " << r.stats.solver_iterations
                << ", residual " << r.stats.solver_residual << ", back-face hits "
                << r.stats.back_face_hits << " of " << r.stats.rays);
    REQUIRE(r.stats.solver_converged);
    // Discretisation: the rim is a 32-gon inscribed in the opening circle and the wall is an
    // inscribed polyhedron, so f differs per vertex (by < 2% here) and from the smooth
    // sphere's (1 − cos a)/2 by the polygon-to-circle area ratio (−0.6%). We therefore compare
    // with the mesh's own mean f (exact per vertex by Lambert's formula).
    CHECK(s.f_mesh == Approx(s.f_analytic).epsilon(0.02));
    // AO = f: mean over ~500 inner vertices × 1024 samples (4σ ≈ 0.0009 for f ≈ 0.18), and
    // per vertex within 4σ of 1024 independent samples (0.048).
    CHECK(s.mean_ao == Approx(s.f_mesh).margin(0.002));
    CHECK(s.max_ao_error < 4.0 * std::sqrt(0.25 / 1024));
    // Exit radiance under uniform sky radiance 1 (L_00 = √(4π)): within 1%.
    CHECK(s.mean_exit == Approx(furnace(rho, s.f_mesh)).epsilon(0.01));
  }
}

TEST_CASE("stiff cavity (ρ = 0.999, small opening) converges in bounded time") {
  // f ≈ 0.011: the Neumann series contracts by ρ(1 − f) ≈ 0.988 per bounce, so plain bounces
  // need ~750 iterations for 1e-4; the Krylov solver must do it in far fewer.
  const double a = 12.0 * prt::test::kPi / 180.0;
  const prt::scene::Scene cavity = prt::scene::make_spherical_cavity(
      1.f, static_cast<float>(a), kRings, kSegments, glm::vec3(0.999f));
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 2;
  o.samples = 512;
  o.bounce_tolerance = 1e-4;
  o.max_solver_iterations = 400;
  const auto start = std::chrono::steady_clock::now();
  const auto r = bake_transfer(cavity, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO("iterations " << r.stats.solver_iterations << ", residual " << r.stats.solver_residual
                     << ", " << seconds << " s");
  CHECK(r.stats.solver_converged);
  CHECK(r.stats.solver_residual <= 1e-4);
  CHECK(r.stats.solver_iterations < 150);
  CHECK(seconds < 10.0);
  const CavityStats s = measure_cavity(cavity, r, a);
  // At ρ = 0.999 the answer hinges on the 1% absorption budget, so MC noise in the hit
  // fractions (f ≈ 0.011 from 512 samples) matters more: 3%.
  CHECK(s.mean_exit == Approx(furnace(0.999, s.f_mesh)).epsilon(0.03));
}

TEST_CASE("bounce energy never grows, and explicit bounces converge to the Krylov solution") {
  const double a = 30.0 * prt::test::kPi / 180.0;
  const prt::scene::Scene cavity = prt::scene::make_spherical_cavity(
      1.f, static_cast<float>(a), kRings, kSegments, glm::vec3(0.9f));
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 3;
  o.samples = 256;
  o.bounces = 300;  // 0.9^300 ≈ 2e-14: converged
  const auto jacobi = bake_transfer(cavity, o);
  const std::vector<double>& e = jacobi.stats.bounce_energy;
  REQUIRE(e.size() == 300);
  REQUIRE(e[0] > 0.0);
  for (std::size_t i = 1; i < e.size(); ++i) {
    INFO("bounce " << i + 1);
    // Row sums of H are hit fractions ≤ 1, so ‖ρH x‖_max ≤ ρ‖x‖_max.
    REQUIRE(e[i] <= 0.9 * e[i - 1] * (1 + 1e-9) + 1e-300);
  }
  o.bounces = -1;
  o.bounce_tolerance = 1e-9;
  const auto krylov = bake_transfer(cavity, o);
  REQUIRE(krylov.stats.solver_converged);
  double max_t = 0, max_diff = 0;
  for (std::size_t i = 0; i < krylov.data.coefficients.size(); ++i) {
    max_t = std::max(max_t, static_cast<double>(std::fabs(krylov.data.coefficients[i])));
    max_diff = std::max(max_diff, static_cast<double>(std::fabs(krylov.data.coefficients[i] -
                                                                jacobi.data.coefficients[i])));
  }
  // Same H (same seed), two solvers: agreement to float storage precision.
  CHECK(max_diff < 1e-5 * max_t);
  // Zero bounces is the shadowed transfer itself.
  o.bounces = 0;
  const auto direct = bake_transfer(cavity, o);
  o.kind = prt::TransferKind::Shadowed;
  const auto shadowed = bake_transfer(cavity, o);
  CHECK(direct.data.coefficients == shadowed.data.coefficients);
}

TEST_CASE("stiff box with a small opening: Krylov beats bounces and agrees with them") {
  // A closed box (inward normals) with the central 2×2 cells of its top face removed:
  // opening 0.44 of a 24 area, so f ≈ 0.02 and ρ(1 − f) ≈ 0.98 at ρ = 0.999. Unlike the
  // sphere, whose gather kernel is constant (rank one: Krylov solves it in one step), the box
  // has a genuinely non-symmetric, spread-out H.
  prt::scene::Scene box =
      prt::scene::make_box({-1.f, -1.f, -1.f}, {1.f, 1.f, 1.f}, 6, true, glm::vec3(0.999f));
  std::vector<glm::uvec3> kept;
  for (const glm::uvec3& t : box.triangles) {
    const glm::vec3 c = (box.positions[t.x] + box.positions[t.y] + box.positions[t.z]) / 3.f;
    if (c.y > 0.999f && std::fabs(c.x) < 0.35f && std::fabs(c.z) < 0.35f) continue;
    kept.push_back(t);
  }
  REQUIRE(kept.size() + 8 == box.triangles.size());
  box.triangles = kept;
  box.primitives[0].triangle_count = static_cast<uint32_t>(kept.size());
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 2;
  o.samples = 256;
  o.bounce_tolerance = 1e-6;
  o.max_solver_iterations = 400;
  const auto krylov = bake_transfer(box, o);
  INFO("Krylov: " << krylov.stats.solver_iterations << " iterations, residual "
                  << krylov.stats.solver_residual);
  REQUIRE(krylov.stats.solver_converged);
  CHECK(krylov.stats.solver_iterations > 1);  // not a trivial system
  // Plain bounces contract by ~0.98 per bounce: ~700 bounces to reach 1e-6; we run 4000
  // (0.98^4000 ≈ 1e-35) as the reference and require the Krylov solve to take < 150.
  CHECK(krylov.stats.solver_iterations < 150);
  o.bounces = 4000;
  const auto bounces = bake_transfer(box, o);
  double max_t = 0, max_diff = 0;
  for (std::size_t i = 0; i < krylov.data.coefficients.size(); ++i) {
    max_t = std::max(max_t, static_cast<double>(std::fabs(bounces.data.coefficients[i])));
    max_diff = std::max(max_diff, static_cast<double>(std::fabs(krylov.data.coefficients[i] -
                                                                bounces.data.coefficients[i])));
  }
  // Residual 1e-6 with a condition number of ~1/(1 − 0.98) = 50: error ≲ 5e-5 relative.
  CHECK(max_diff < 1e-4 * max_t);
  // Energy: the interreflected DC transfer far exceeds the direct one at ρ = 0.999.
  o.kind = prt::TransferKind::Shadowed;
  const auto direct = bake_transfer(box, o);
  double sum_direct = 0, sum_inter = 0;
  for (std::size_t v = 0; v < box.positions.size(); ++v) {
    sum_direct += direct.data.coefficients[v * 4];
    sum_inter += krylov.data.coefficients[v * 4];
  }
  INFO("back-face hits " << krylov.stats.back_face_hits << " of " << krylov.stats.rays
                         << ", entries " << krylov.stats.matrix_entries << ", direct " << sum_direct
                         << ", interreflected " << sum_inter);
  CHECK(sum_inter > 10.0 * sum_direct);
}

// multiply_gather runs a clone of its row loop chosen at load time (AVX2 where the CPU has it,
// 4 doubles per instruction). Against a plain scalar loop over the same CSR matrix, for column
// counts that are and are not multiples of 4 (the clone's tail), rows with no entries and
// repeated columns. The build is ISO C++ (CMAKE_CXX_EXTENSIONS OFF: no floating-point
// contraction), so every clone adds the same products in the same order and the results must be
// bit-identical — the same file on every CPU. A wrong column, weight or tail is off by O(1).
TEST_CASE("the solver's gather equals a plain loop for any column count") {
  prt::numerics::SplitMix64 rng{1};
  auto next = [&] { return rng.uniform(); };
  const std::size_t rows = 300;
  prt::bake::SparseTransferMatrix h;
  for (std::size_t v = 0; v < rows; ++v) {
    const int entries = v % 7 == 0 ? 0 : static_cast<int>(next() * 40);
    for (int e = 0; e < entries; ++e) {
      h.columns.push_back(static_cast<uint32_t>(next() * rows));
      h.weights.push_back(static_cast<float>(next() / 40.0));
    }
    h.row_offsets.push_back(h.columns.size());
  }
  std::vector<double> rho(rows);
  for (double& r : rho) r = next();
  for (int k : {1, 3, 4, 9, 16, 25, 37, 144}) {
    std::vector<double> x(rows * k), y(rows * k, -1.0);
    for (double& e : x) e = 2.0 * next() - 1.0;
    prt::bake::multiply_gather(h, rho, x.data(), k, y.data());
    double worst = 0.0;
    for (std::size_t v = 0; v < rows; ++v)
      for (int c = 0; c < k; ++c) {
        double sum = 0.0, magnitude = 0.0;
        for (uint64_t e = h.row_offsets[v]; e < h.row_offsets[v + 1]; ++e) {
          const double term = static_cast<double>(h.weights[e]) * x[h.columns[e] * k + c];
          sum += term;
          magnitude += std::fabs(term);
        }
        const double expected = rho[v] * sum;
        const double scale = rho[v] * magnitude;
        const double error = std::fabs(y[v * k + c] - expected);
        if (scale == 0.0)
          REQUIRE(y[v * k + c] == 0.0);
        else
          worst = std::max(worst, error / scale);
      }
    INFO("k = " << k << ": worst relative difference " << worst);
    CHECK(worst == 0.0);
  }
}
