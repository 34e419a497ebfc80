// The compact gather (bake/compact_gather.h) against the reference path (merged CSR + BiCGSTAB):
// quantisation bounds, the Morton order, the same solution on a small scene within the bound
// the quantisation implies, bit-identical output for any thread count, and the memory budget's
// refusal before the buffers exist.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "../../bake/src/hit_records.h"
#include "../../bake/src/hit_side.h"
#include "../../bake/src/transfer_pass.h"
#include "bake/compact_gather.h"
#include "bake/transfer_baker.h"
#include "numerics/rng.h"
#include "prt/core/half.h"
#include "prt/core/memory_budget.h"
#include "scene/procedural_mesh.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;
using prt::bake::CompactHit;

namespace {

// A grey ground with a sphere and a box standing on it: rays from each hit the others.
prt::scene::Scene small_scene() {
  prt::scene::Scene s = prt::scene::make_quad({-3.f, 0.f, 3.f}, {6.f, 0.f, 0.f}, {0.f, 0.f, -6.f},
                                              16, 16, glm::vec3(0.7f), "ground");
  prt::scene::append_scene(s, prt::scene::make_uv_sphere({-0.8f, 0.8f, 0.f}, 0.8f, 10, 20, false,
                                                         glm::vec3(0.8f, 0.5f, 0.3f), "sphere"));
  prt::scene::append_scene(s, prt::scene::make_box({0.5f, 0.f, -0.6f}, {1.7f, 1.2f, 0.6f}, 4, false,
                                                   glm::vec3(0.9f), "box"));
  return s;
}

// Interreflected transfer of SH order `order` with `samples` rays a vertex, the rest default.
BakeOptions interreflected(int order, int samples) {
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = order;
  o.samples = samples;
  return o;
}

double max_abs(const std::vector<float>& x) {
  double m = 0.0;
  for (float e : x) m = std::max(m, static_cast<double>(std::fabs(e)));
  return m;
}

double max_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, static_cast<double>(std::fabs(a[i] - b[i])));
  return m;
}

}  // namespace

TEST_CASE("quantised barycentrics: weights sum to 65535 and err by at most half a step") {
  prt::numerics::SplitMix64 rng{7};
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    float u = static_cast<float>(rng.uniform()), v = static_cast<float>(rng.uniform());
    if (u + v > 1.f) u = 1.f - u, v = 1.f - v;
    if (i < 4) u = i & 1 ? 1.f : 0.f, v = i & 2 ? 1.f - u : 0.f;  // corners and an edge
    const CompactHit h = prt::bake::quantise_hit(42, u, v);
    REQUIRE(h.triangle == 42);
    REQUIRE(static_cast<int>(h.u) + static_cast<int>(h.v) <= 65535);
    worst = std::max({worst, std::fabs(h.u / 65535.0 - u), std::fabs(h.v / 65535.0 - v)});
  }
  // Half a quantum, plus float's rounding of u and v near 1 (2^-24).
  CHECK(worst <= 0.5 / 65535.0 + 1e-7);
  // u + v rounded above 1 loses the excess from the larger one.
  const CompactHit e = prt::bake::quantise_hit(0, 0.6f, 0.4000001f);
  CHECK(static_cast<int>(e.u) + static_cast<int>(e.v) == 65535);
}

TEST_CASE("Morton order is a permutation that keeps neighbours together") {
  const prt::scene::Scene s = prt::scene::make_quad({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f},
                                                    {0.f, 0.f, 1.f}, 63, 63, glm::vec3(0.5f));
  const std::vector<uint32_t> order = prt::bake::make_morton_order(s.positions);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == i);
  // On a 64 × 64 grid Morton order visits 2 × 2, 4 × 4, ... tiles: consecutive rows are at most
  // a few cells apart on average (row-major order jumps 63 cells at every row end; Morton's
  // mean step is < 2 cells).
  double step = 0.0;
  for (std::size_t r = 1; r < order.size(); ++r)
    step += glm::length(s.positions[order[r]] - s.positions[order[r - 1]]) * 63.0;
  step /= static_cast<double>(order.size() - 1);
  INFO("mean step " << step << " cells");
  CHECK(step < 2.0);
}

TEST_CASE("compact gather: the reference path's solution within the quantisation bound") {
  const prt::scene::Scene s = small_scene();
  BakeOptions o = interreflected(3, 128);
  o.bounce_tolerance = 1e-10;
  const auto compact = bake_transfer(s, o);
  o.dense_gather = true;
  const auto dense = bake_transfer(s, o);
  REQUIRE(compact.stats.compact_gather);
  REQUIRE_FALSE(dense.stats.compact_gather);
  REQUIRE(compact.stats.solver_converged);
  REQUIRE(dense.stats.solver_converged);
  REQUIRE(compact.data.coefficients.size() == dense.data.coefficients.size());
  // The same rays: the hits the compact gather stores are the dense matrix's entries before
  // merging (3 per hit, as one 8-byte hit each).
  CHECK(compact.stats.rays == dense.stats.rays);
  CHECK(compact.stats.back_face_hits == dense.stats.back_face_hits);
  CHECK(3 * compact.stats.matrix_entries >= dense.stats.matrix_entries);
  // Quantisation moves the solution by ≤ 3.1e-5·q/(1 − q)·‖T‖ (compact_gather.h); q ≤ 0.9 here
  // (albedo ≤ 0.9, row sums ≤ 1), so 2.8e-4·‖T‖. Both solves stop at 1e-10 and both store float
  // (2^-24 relative).
  const double t_max = max_abs(dense.data.coefficients);
  const double diff = max_diff(compact.data.coefficients, dense.data.coefficients);
  INFO("max |T| " << t_max << ", max difference " << diff << " (" << diff / t_max
                  << " relative); bounces " << compact.stats.jacobi_bounces);
  CHECK(diff <= (3.1e-5 * 0.9 / 0.1 + 1e-6) * t_max);
  CHECK(diff > 0.0);  // the quantisation is real: the paths differ
  // With no bounce both are the shadowed transfer: bit-identical.
  o.bounces = 0;
  const auto dense0 = bake_transfer(s, o);
  o.dense_gather = false;
  const auto compact0 = bake_transfer(s, o);
  CHECK(dense0.data.coefficients == compact0.data.coefficients);
}

TEST_CASE("compact gather: bit-identical for any thread count") {
  const prt::scene::Scene s = small_scene();
  BakeOptions o = interreflected(2, 64);
  o.bounce_precision = GENERATE(prt::Precision::F32, prt::Precision::F16);
  o.threads = 1;
  const auto one = bake_transfer(s, o);
  o.threads = 2;
  const auto two = bake_transfer(s, o);
  REQUIRE(one.stats.compact_gather);
  CHECK(one.data.coefficients == two.data.coefficients);
  CHECK(one.stats.jacobi_bounces == two.stats.jacobi_bounces);
}

// Binary16 bounces (BakeOptions::bounce_precision F16). Bounce i's input h_i is rounded to half:
// rd(x) = x(1 + δ) + η, |δ| ≤ u = 2^-11, |η| ≤ 2^-25 (half's subnormal half-step). With
// e_i = h_i − A^i D and ‖A‖_max ≤ q: ‖e_0‖ ≤ u‖D‖ + 2^-25 and
//     ‖e_i‖ ≤ q(1 + u)‖e_{i−1}‖ + u·q^i‖D‖ + 2^-25,
// and T_f16 − T = Σ_{i=1..n} e_i (D itself is added exact). The float path obeys the same with
// u = 2^-24 (no subnormals at these sizes), and both round T to float once (2^-24‖T‖).
double bounce_rounding_bound(double u, double eta, double q, int n, double d_max) {
  double e = u * d_max + eta, sum = 0.0, qi = 1.0;
  for (int i = 1; i <= n; ++i) {
    qi *= q;
    e = q * (1 + u) * e + u * qi * d_max + eta;
    sum += e;
  }
  return sum;
}

double rms_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
  return std::sqrt(s / static_cast<double>(a.size()));
}

TEST_CASE("compact gather: binary16 bounces within their rounding bound, far below the noise") {
  const prt::scene::Scene s = small_scene();
  BakeOptions o = interreflected(3, 128);
  o.bounces = 40;  // the same terms on both paths
  const auto f32 = bake_transfer(s, o);
  o.bounce_precision = prt::Precision::F16;
  const auto f16 = bake_transfer(s, o);
  o.bounces = 0;
  const auto direct = bake_transfer(s, o);
  o.bounces = 40;
  o.bounce_precision = prt::Precision::F32;
  o.seed = 2;
  const auto other_seed = bake_transfer(s, o);
  REQUIRE(f16.stats.compact_gather);
  REQUIRE(f16.stats.jacobi_bounces == 40);
  const double d_max = max_abs(direct.data.coefficients);
  const double t_max = max_abs(f32.data.coefficients);
  const double q = 0.9;  // albedo ≤ 0.9, row sums ≤ 1
  const double bound =
      bounce_rounding_bound(std::ldexp(1.0, -11), std::ldexp(1.0, -25), q, 40, d_max) +
      bounce_rounding_bound(std::ldexp(1.0, -24), 0.0, q, 40, d_max) +
      2 * std::ldexp(1.0, -24) * t_max;
  const double diff = max_diff(f16.data.coefficients, f32.data.coefficients);
  const double noise = rms_diff(other_seed.data.coefficients, f32.data.coefficients);
  const double rms = rms_diff(f16.data.coefficients, f32.data.coefficients);
  INFO("max |D| " << d_max << ", max |T| " << t_max << ", max difference " << diff << " (bound "
                  << bound << "), RMS " << rms << " against the seed-to-seed RMS " << noise);
  CHECK(diff <= bound);
  CHECK(diff > 0.0);  // the bounces really were binary16
  // The rounding is ≥ 100× below the Monte Carlo noise of 128 samples (measured: ~10^-4 of it).
  CHECK(rms < 0.01 * noise);
}

namespace {

// A gather over scene s with random hits (0–11 a row, anywhere in the scene) in 64-row blocks.
prt::bake::CompactGather random_gather(const prt::scene::Scene& s, prt::numerics::SplitMix64& rng) {
  const auto V = s.positions.size();
  prt::bake::CompactGather g(prt::bake::make_morton_order(s.positions), s.triangles, 64, 1.0 / 32);
  for (std::size_t b = 0; b < g.blocks(); ++b) {
    prt::bake::CompactGather::Block blk;
    for (std::size_t r = b * 64; r < std::min(V, (b + 1) * 64); ++r) {
      blk.lengths.push_back(static_cast<uint32_t>(rng.uniform() * 12));
      for (uint32_t h = 0; h < blk.lengths.back(); ++h)
        blk.hits.push_back(prt::bake::quantise_hit(
            static_cast<uint32_t>(rng.uniform() * static_cast<double>(s.triangles.size())),
            static_cast<float>(0.5 * rng.uniform()), static_cast<float>(0.5 * rng.uniform())));
    }
    g.set_block(b, std::move(blk));
  }
  return g;
}

}  // namespace

TEST_CASE("compact gather: padded bounce rows give the unpadded products, padding untouched") {
  const prt::scene::Scene s = small_scene();
  const auto V = s.positions.size();
  prt::numerics::SplitMix64 rng{5};
  const prt::bake::CompactGather g = random_gather(s, rng);
  const int C = 3, k = 3 * 9;
  const std::size_t ld = prt::bake::padded_row_elements(k);
  REQUIRE(ld == 32);
  std::vector<double> rho(V * C);
  for (double& r : rho) r = 0.9 * rng.uniform();
  std::vector<float> x(V * k), xp(V * ld, 7.f), y(V * k), yp(V * ld, -3.f);
  for (std::size_t r = 0; r < V; ++r)
    for (int c = 0; c < k; ++c) x[r * k + c] = xp[r * ld + c] = static_cast<float>(rng.uniform());
  g.multiply(rho, C, x.data(), k, y.data());
  g.multiply(rho, C, xp.data(), k, yp.data(), ld);
  int same = 0, padding_kept = 0;
  for (std::size_t r = 0; r < V; ++r) {
    for (int c = 0; c < k; ++c) same += y[r * k + c] == yp[r * ld + c];
    for (std::size_t c = k; c < ld; ++c) padding_kept += yp[r * ld + c] == -3.f;
  }
  CHECK(same == static_cast<int>(V) * k);
  CHECK(padding_kept == static_cast<int>(V * (ld - k)));
}

TEST_CASE("compact gather: binary16 rows give the float rows' products, rounded once to half") {
  // half -> float is exact and both kernels sum the same doubles in the same order, so the
  // binary16 product (inline F16C where the CPU has it) is the float product of the same values,
  // rounded to half: bit for bit. Columns 27 (3 vectors of 8 and a tail of 3) and 75 (C·K of an
  // order-5 colour bake: 9 vectors and a tail of 3), rows packed (ld = k) and padded.
  const prt::scene::Scene s = small_scene();
  const auto V = s.positions.size();
  prt::numerics::SplitMix64 rng{11};
  const prt::bake::CompactGather g = random_gather(s, rng);
  const int C = 3;
  const int k = GENERATE(27, 75);
  const bool padded = GENERATE(false, true);
  const std::size_t ld = padded ? prt::bake::padded_row_elements(k) : static_cast<std::size_t>(k);
  std::vector<double> rho(V * C);
  for (double& r : rho) r = 0.9 * rng.uniform();
  std::vector<uint16_t> xh(V * ld, 0), yh(V * ld, 0);
  std::vector<float> xf(V * ld, 0.f), yf(V * ld, 0.f);
  for (std::size_t i = 0; i < xh.size(); ++i) {
    // Values over 12 binades, signed, so rounding and the subnormal-free range are both exercised.
    const double m = (rng.uniform() - 0.3) * std::exp2(-12.0 * rng.uniform());
    xh[i] = prt::float_to_half(static_cast<float>(m));
    xf[i] = prt::half_to_float(xh[i]);
  }
  g.multiply(rho, C, xh.data(), k, yh.data(), ld);
  g.multiply(rho, C, xf.data(), k, yf.data(), ld);
  int same = 0, nonzero = 0;
  for (std::size_t r = 0; r < V; ++r)
    for (int c = 0; c < k; ++c) {
      same += yh[r * ld + c] == prt::float_to_half(yf[r * ld + c]);
      nonzero += yf[r * ld + c] != 0.f;
    }
  INFO("k " << k << ", ld " << ld << ", F16C " << prt::cpu_has_f16c());
  CHECK(same == static_cast<int>(V) * k);
  CHECK(nonzero > static_cast<int>(V) * k / 2);  // the products are not trivially zero
}

TEST_CASE("compact gather: the bounce count is bounded independently of the mesh") {
  // Neumann bounces stop once the residual bound e_n·q ≤ tol·‖D‖; e_n ≤ q^n‖D‖, so at most
  // ⌈log(tol)/log q⌉ bounces (q ≤ ρ_max = 0.8 here: 42 at tol 1e-4), whatever V is. Refining the
  // mesh 4× changes the count only by what the geometry at the contact does (a few bounces).
  std::vector<int> bounces;
  for (int seg : {8, 16, 32}) {
    prt::scene::Scene s = prt::scene::make_quad({-3.f, 0.f, 3.f}, {6.f, 0.f, 0.f}, {0.f, 0.f, -6.f},
                                                2 * seg, 2 * seg, glm::vec3(0.7f), "ground");
    prt::scene::append_scene(s, prt::scene::make_uv_sphere({0.f, 1.f, 0.f}, 1.f, seg, 2 * seg,
                                                           false, glm::vec3(0.8f), "sphere"));
    BakeOptions o = interreflected(2, 64);
    const auto r = bake_transfer(s, o);
    REQUIRE(r.stats.solver_converged);
    REQUIRE(r.stats.solver_iterations == 0);  // no Krylov fallback
    bounces.push_back(r.stats.jacobi_bounces);
  }
  INFO("bounces " << bounces[0] << ", " << bounces[1] << ", " << bounces[2]);
  const int bound = static_cast<int>(std::ceil(std::log(1e-4) / std::log(0.8)));
  for (int b : bounces) CHECK(b <= bound);
  CHECK(std::abs(bounces[2] - bounces[0]) <= 8);
}

TEST_CASE("hit records judge the side and renumber the triangle as the scene-based test") {
  // The sampling pass's one-read hit test (hit_records.h) must agree with hit_side.h on every
  // triangle and direction, including a degenerate triangle (no front) and one whose winding
  // disagrees with its vertex normals; and give the same CompactHit as gather_front_hit_compact.
  prt::scene::Scene s = small_scene();
  const auto V = static_cast<uint32_t>(s.positions.size());
  s.positions.push_back({0.f, 2.f, 0.f});
  s.positions.push_back({1.f, 2.f, 0.f});
  s.positions.push_back({2.f, 2.f, 0.f});  // collinear: n_g = 0
  for (int i = 0; i < 3; ++i) s.normals.push_back({0.f, 1.f, 0.f});
  s.triangles.push_back({V, V + 1, V + 2});
  const glm::uvec3 flipped = s.triangles[0];
  s.triangles.push_back({flipped.x, flipped.z, flipped.y});  // same facet, other winding
  s.albedo.resize(s.positions.size(), glm::vec3(0.5f));
  const prt::bake::CompactGather gather(prt::bake::make_morton_order(s.positions), s.triangles, 64,
                                        1.0 / 64);
  const std::vector<prt::bake::detail::HitRecord> records =
      prt::bake::detail::make_hit_records(s, gather);
  REQUIRE(records.size() == s.triangles.size());
  prt::numerics::SplitMix64 rng{11};
  int fronts = 0, backs = 0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) {
    for (int i = 0; i < 64; ++i) {
      const glm::vec3 d(static_cast<float>(2 * rng.uniform() - 1),
                        static_cast<float>(2 * rng.uniform() - 1),
                        static_cast<float>(2 * rng.uniform() - 1));
      const float u = static_cast<float>(0.5 * rng.uniform()),
                  v = static_cast<float>(0.5 * rng.uniform());
      prt::scene::RayCaster::Hit hit;
      hit.hit = true;
      hit.triangle = t;
      hit.u = u;
      hit.v = v;
      std::vector<CompactHit> by_scene, by_record;
      const bool a = prt::bake::detail::gather_front_hit_compact(s, hit, d, gather, by_scene);
      const bool b =
          prt::bake::detail::gather_front_hit_record(records.data(), t, u, v, d, by_record);
      REQUIRE(a == prt::bake::detail::ray_hits_front_side(s, t, d));
      REQUIRE(a == b);
      REQUIRE(by_scene.size() == by_record.size());
      if (a) {
        REQUIRE(by_scene[0].triangle == by_record[0].triangle);
        REQUIRE(by_scene[0].u == by_record[0].u);
        REQUIRE(by_scene[0].v == by_record[0].v);
      }
      (a ? fronts : backs) += 1;
    }
  }
  CHECK(records[s.triangles.size() - 2].front == glm::vec3(0.f));  // degenerate
  CHECK(records.back().front == records[0].front);  // the orientation follows the normals
  CHECK(fronts > 1000);
  CHECK(backs > 1000);
}

TEST_CASE("a bake over its memory limit stops before it allocates, with one line") {
  prt::scene::Scene s = small_scene();
  s.source_path = "small.glb";
  BakeOptions o = interreflected(5, 64);
  // The coefficients alone: V × 3 channels × 25 × 4 bytes; a limit below that fails first.
  const uint64_t coefficients = s.positions.size() * 3 * 25 * 4;
  o.memory_limit = coefficients / 2;
  try {
    (void)bake_transfer(s, o);
    FAIL("no MemoryBudgetExceeded");
  } catch (const prt::MemoryBudgetExceeded& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.rfind("small.glb: the transfer coefficients", 0) == 0);
    CHECK(what.find('\n') == std::string::npos);
  }
  // Unlimited, the bake records the largest total it charged; one byte less fails at the last
  // charge, a block of the gather matrix in the sampling pass.
  o.memory_limit = 0;
  const auto r = bake_transfer(s, o);
  const uint64_t peak = r.stats.budget_peak_bytes;
  CHECK(peak > coefficients);
  o.memory_limit = peak - 1;
  try {
    (void)bake_transfer(s, o);
    FAIL("no MemoryBudgetExceeded");
  } catch (const prt::MemoryBudgetExceeded& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("the gather matrix") != std::string::npos);
  }
  o.memory_limit = peak;
  CHECK(bake_transfer(s, o).data.coefficients == r.data.coefficients);
}
