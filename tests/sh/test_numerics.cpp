// Tests of prt::numerics (sh/include/numerics/): constants, the SplitMix64 hash and stream
// against their published outputs, the Sobol' matrices against Joe & Kuo's direction numbers
// and the published first points, Owen scrambling's stratification and uniformity, the
// samplers against their densities, and the orthonormal basis. Gauss–Legendre:
// test_gauss_legendre.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "numerics/hash.h"
#include "numerics/low_discrepancy.h"
#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "sh/constants.h"

namespace nm = prt::numerics;

namespace {

// The chi-square quantile of k degrees of freedom at upper-tail probability 0.001 by the
// Wilson–Hilferty approximation (z = 3.0902; within 1% of the exact quantile for k ≥ 10).
double chi_square_0001(int k) {
  const double a = 2.0 / (9.0 * k);
  const double c = 1.0 - a + 3.0902 * std::sqrt(a);
  return k * c * c * c;
}

double chi_square(const std::vector<int>& counts, double expected) {
  double chi2 = 0.0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

}  // namespace

// ---- constants ---------------------------------------------------------------------------------

static_assert(nm::kFourPi == 12.566370614359172954, "nearest double to 4π");
static_assert(nm::kInvTwoPi == 0.15915494309189533577, "nearest double to 1/(2π)");
static_assert(nm::kInvFourPi == 0.079577471545947667884, "nearest double to 1/(4π)");
static_assert(nm::kOneMinusEpsilon == 1.0 - 0x1p-53, "largest double below 1");
static_assert(nm::kOneMinusEpsilonFloat == 1.0f - 0x1p-24f, "largest float below 1");

TEST_CASE("sh's π is numerics' π, the same object", "[numerics][constants]") {
  CHECK(&prt::sh::kPi == &nm::kPi);
  CHECK(&prt::sh::kPiFloat == &nm::kPiFloat);
  CHECK(&prt::sh::kTwoPi == &nm::kTwoPi);
  CHECK(std::nextafter(1.0, 0.0) == nm::kOneMinusEpsilon);
  CHECK(std::nextafter(1.0f, 0.0f) == nm::kOneMinusEpsilonFloat);
  // kTwoPi · u is 2.0 · kPi · u bit for bit (doubling is exact), in float as well.
  CHECK(static_cast<float>(nm::kTwoPi) == 2.f * nm::kPiFloat);
}

// ---- hash and stream -------------------------------------------------------------------------

TEST_CASE("SplitMix64 gives the published outputs", "[numerics][rng]") {
  // Seed 1234567: the five reference outputs of the Rosetta Code task "Pseudo-random
  // numbers/Splitmix64"; seed 0: the first three outputs of Vigna's splitmix64.c, as quoted by
  // many ports (0xe220a8397b1dcdaf, …).
  nm::SplitMix64 a{1234567};
  CHECK(a.next_u64() == 6457827717110365317ull);
  CHECK(a.next_u64() == 3203168211198807973ull);
  CHECK(a.next_u64() == 9817491932198370423ull);
  CHECK(a.next_u64() == 4593380528125082431ull);
  CHECK(a.next_u64() == 16408922859458223821ull);
  nm::SplitMix64 z{0};
  CHECK(z.next_u64() == 0xe220a8397b1dcdafull);
  CHECK(z.next_u64() == 0x6e789e6aa1b965f4ull);
  CHECK(z.next_u64() == 0x06c45d188009454full);
  // splitmix64(x) is the first output of the stream seeded with x.
  CHECK(nm::splitmix64(0) == 0xe220a8397b1dcdafull);
  CHECK(nm::splitmix64(1234567) == 6457827717110365317ull);
  // uniform(): the top 53 bits times 2^-53.
  nm::SplitMix64 b{1234567}, c{1234567};
  CHECK(b.uniform() == static_cast<double>(6457827717110365317ull >> 11) * 0x1p-53);
  c.next_u64();
  CHECK(b.uniform() == static_cast<double>(c.next_u64() >> 11) * 0x1p-53);
  CHECK(nm::unit_double_from_bits(~0ull) < 1.0);
  CHECK(nm::unit_double_from_bits(0) == 0.0);
}

TEST_CASE("mix64 avalanches: each input bit flips each output bit half the time",
          "[numerics][hash]") {
  // 2000 random inputs: the flip rate of each of the 64 × 64 (input bit, output bit) pairs is a
  // binomial proportion with σ = 0.011 if mix64 avalanches; 0.08 is 7σ (a weak mixer such as
  // the identity or a single multiply fails by far more: rates 0 or 1 for many pairs).
  constexpr int kInputs = 2000;
  std::vector<int> flips(64 * 64, 0);
  nm::SplitMix64 rng{42};
  for (int s = 0; s < kInputs; ++s) {
    const uint64_t x = rng.next_u64(), hx = nm::mix64(x);
    for (int i = 0; i < 64; ++i) {
      const uint64_t d = hx ^ nm::mix64(x ^ (1ull << i));
      for (int o = 0; o < 64; ++o) flips[i * 64 + o] += static_cast<int>((d >> o) & 1u);
    }
  }
  double worst = 0.0;
  for (int f : flips) worst = std::max(worst, std::abs(double(f) / kInputs - 0.5));
  INFO("worst deviation of a flip rate from 1/2: " << worst);
  CHECK(worst < 0.08);
  // A bijection: distinct inputs, distinct outputs (on a sample; mix64 is invertible by
  // construction — xor-shifts and odd multiplies).
  std::vector<uint64_t> out;
  for (uint64_t x = 0; x < 100000; ++x) out.push_back(nm::mix64(x));
  std::sort(out.begin(), out.end());
  CHECK(std::adjacent_find(out.begin(), out.end()) == out.end());
}

TEST_CASE("hash_values chains hash_seed, and WordHash is FNV-1a over words, finalised",
          "[numerics][hash]") {
  CHECK(nm::hash_values(7) == nm::splitmix64(7));
  CHECK(nm::hash_values(7, 11) == nm::hash_seed(7, 11));
  CHECK(nm::hash_values(7, 11, 13) == nm::hash_seed(nm::hash_seed(7, 11), 13));
  CHECK(nm::hash_seed(7, 11) != nm::hash_seed(11, 7));
  CHECK(nm::hash_seed(7, 11) != nm::hash_seed(7, 12));
  // Empty: the FNV-1a-64 offset basis, finalised.
  CHECK(nm::WordHash().finish() == nm::mix64(0xcbf29ce484222325ull));
  // One word: (basis ⊕ w) · prime.
  nm::WordHash one;
  one.add_word(0x12345678u);
  CHECK(one.finish() == nm::mix64((0xcbf29ce484222325ull ^ 0x12345678u) * 0x100000001b3ull));
  // add_u64 is the low word, then the high word; −0 hashes as +0, 1 ulp does not.
  nm::WordHash a, b, p, m, u;
  a.add_u64(0x0000000500000003ull);
  b.add_word(3);
  b.add_word(5);
  CHECK(a.finish() == b.finish());
  p.add_float(0.0f);
  m.add_float(-0.0f);
  u.add_float(std::nextafter(0.0f, 1.0f));
  CHECK(p.finish() == m.finish());
  CHECK(p.finish() != u.finish());
}

// ---- Sobol' and Owen scrambling ------------------------------------------------------------

TEST_CASE("Sobol' matrices carry Joe & Kuo's direction numbers", "[numerics][sobol]") {
  // new-joe-kuo-6.21201, restated here from the table (not from the header): dimension d of
  // prt::numerics is their d + 1. v_k = m_k · 2^(31−k) for k < s.
  struct Row {
    int dimension;
    std::vector<uint32_t> m;
  };
  const Row rows[] = {{1, {1}},
                      {2, {1, 3}},
                      {3, {1, 3, 1}},
                      {4, {1, 1, 1}},
                      {6, {1, 3, 5, 13}},
                      {10, {1, 1, 5, 1, 1}},
                      {15, {1, 3, 1, 13, 27, 49}},
                      {20, {1, 3, 7, 13, 13, 15, 69}}};
  for (const Row& r : rows)
    for (std::size_t k = 0; k < r.m.size(); ++k) {
      INFO("dimension " << r.dimension << ", k " << k);
      CHECK(nm::kSobolMatrices.v[r.dimension][k] == r.m[k] << (31 - k));
    }
  // Every generator matrix is upper triangular with a unit diagonal (column k = m_k·2^(31−k),
  // m_k odd: bit 2^(31−k) set, nothing below it): each dimension alone is a (0, 1)-sequence.
  for (int d = 0; d < nm::kSobolDimensions; ++d)
    for (int k = 0; k < 32; ++k) {
      const uint32_t v = nm::kSobolMatrices.v[d][k];
      INFO("dimension " << d << ", k " << k);
      CHECK(((v >> (31 - k)) & 1u) == 1u);
      CHECK((k == 31 || (v & ((1u << (31 - k)) - 1u)) == 0u));
    }
  // Dimension 1 (x + 1) is Pascal's triangle mod 2: v_{k+1} = v_k ⊕ (v_k ≫ 1).
  for (int k = 0; k + 1 < 32; ++k)
    CHECK(nm::kSobolMatrices.v[1][k + 1] ==
          (nm::kSobolMatrices.v[1][k] ^ (nm::kSobolMatrices.v[1][k] >> 1)));
  // sobol_bits computes dimensions 0 and 1 without the table: the same points as the matrices.
  nm::SplitMix64 rng{3};
  for (int s = 0; s < 20000; ++s) {
    const uint32_t i = s < 10000 ? uint32_t(s) : static_cast<uint32_t>(rng.next_u64());
    for (int d : {0, 1, 2}) {
      uint32_t r = 0;
      for (int k = 0; k < 32; ++k)
        if ((i >> k) & 1u) r ^= nm::kSobolMatrices.v[d][k];
      REQUIRE(nm::sobol_bits(i, d) == r);
    }
  }
}

TEST_CASE("unscrambled Sobol' points are the published ones", "[numerics][sobol]") {
  // SciPy's scipy.stats.qmc.Sobol(d=2, scramble=False), first 8 points (Gray-code order, i.e.
  // point i is sobol_bits at index i ⊕ (i ≫ 1)).
  const double expected[8][2] = {{0, 0},         {0.5, 0.5},     {0.75, 0.25},   {0.25, 0.75},
                                 {0.375, 0.375}, {0.875, 0.875}, {0.625, 0.125}, {0.125, 0.625}};
  for (uint32_t i = 0; i < 8; ++i) {
    const uint32_t g = i ^ (i >> 1);
    CHECK(nm::unit_double_from_bits32(nm::sobol_bits(g, 0)) == expected[i][0]);
    CHECK(nm::unit_double_from_bits32(nm::sobol_bits(g, 1)) == expected[i][1]);
  }
  // Dimension 0 is van der Corput: the bit reversal.
  CHECK(nm::sobol_bits(1, 0) == 0x80000000u);
  CHECK(nm::sobol_bits(6, 0) == 0x60000000u);
  CHECK(nm::reverse_bits32(0x12345678u) == 0x1e6a2c48u);
}

TEST_CASE("Owen scrambling keeps the nets' stratification", "[numerics][sobol]") {
  // 2^m points of the scrambled sequence, for several seeds: every dimension has exactly one
  // point in each interval [k/2^m, (k+1)/2^m), and dimensions (0, 1) form a (0, m, 2)-net: one
  // point in each elementary interval 2^-a × 2^-(m−a), a = 0 … m. Blocks other than the first
  // (points 2^m … 2^(m+1) − 1) keep it too.
  const int m = 10, n = 1 << m;
  for (uint64_t seed : {0ull, 1ull, 0x0123456789abcdefull}) {
    for (uint32_t first : {0u, uint32_t(n)}) {
      INFO("seed " << seed << ", first point " << first);
      for (int d = 0; d < nm::kSobolDimensions; ++d) {
        std::vector<int> count(n, 0);
        for (uint32_t i = 0; i < uint32_t(n); ++i)
          ++count[nm::sobol_owen_bits(first + i, d, seed) >> (32 - m)];
        CHECK(std::count(count.begin(), count.end(), 1) == n);
      }
      for (int a = 0; a <= m; ++a) {
        std::vector<int> count(n, 0);
        for (uint32_t i = 0; i < uint32_t(n); ++i) {
          const uint32_t x = nm::sobol_owen_bits(first + i, 0, seed);
          const uint32_t y = nm::sobol_owen_bits(first + i, 1, seed);
          ++count[((a == 0 ? 0u : x >> (32 - a)) << (m - a)) + (a == m ? 0u : y >> (32 - (m - a)))];
        }
        CHECK(std::count(count.begin(), count.end(), 1) == n);
      }
    }
  }
}

TEST_CASE("an Owen-scrambled point is uniform over seeds, and differs from the unscrambled one",
          "[numerics][sobol]") {
  // Point 5 of dimensions 0, 1 and 7 under 16000 seeds, in 32 bins: chi-square against 1/32
  // each, at the 0.1% level (a fixed seed stream: the test is deterministic). Without the
  // scramble the point never moves (χ² ≈ 16000·31).
  const int bins = 32, draws = 16000;
  for (int d : {0, 1, 7}) {
    std::vector<int> count(bins, 0);
    int moved = 0;
    for (int s = 0; s < draws; ++s) {
      const uint64_t seed = nm::hash_seed(99, uint64_t(s));
      const double u = nm::sobol_owen_double(5, d, seed);
      REQUIRE(u >= 0.0);
      REQUIRE(u < 1.0);
      ++count[static_cast<int>(u * bins)];
      moved += nm::sobol_owen_bits(5, d, seed) != nm::sobol_bits(5, d);
    }
    INFO("dimension " << d);
    CHECK(chi_square(count, double(draws) / bins) < chi_square_0001(bins - 1));
    CHECK(moved > draws * 99 / 100);
  }
  // The float conversion stays below 1 for the largest fraction.
  CHECK(nm::unit_float_from_bits32(0xffffffffu) < 1.0f);
  CHECK(nm::unit_float_from_bits32(0x80000000u) == 0.5f);
}

// ---- sampling ----------------------------------------------------------------------------------

namespace {

// N samples of a direction sampler from a SplitMix64 stream, binned into 16 × 16 cells that are
// equally likely under its stated density: `cdf(z)` maps z = cos θ to [0, 1), φ/(2π) the other
// axis. Returns the chi-square statistic (255 degrees of freedom).
template <typename Sampler, typename Cdf>
double direction_chi_square(Sampler sample, Cdf cdf, int n, bool hemisphere) {
  const int side = 16;
  std::vector<int> count(side * side, 0);
  nm::SplitMix64 rng{2024};
  for (int i = 0; i < n; ++i) {
    const double u0 = rng.uniform(), u1 = rng.uniform();
    const nm::Vec3<double> w = sample(nm::Vec2<double>{u0, u1});
    const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    REQUIRE(std::abs(len - 1.0) < 1e-12);
    if (hemisphere) REQUIRE(w.z >= 0.0);
    const double phi = std::atan2(w.y, w.x) + nm::kPi;  // [0, 2π]
    const int a = std::min(side - 1, static_cast<int>(cdf(w.z) * side));
    const int b = std::min(side - 1, static_cast<int>(phi / nm::kTwoPi * side));
    ++count[a * side + b];
  }
  return chi_square(count, double(n) / (side * side));
}

// ∫ pdf dω over the hemisphere (or sphere) by Gauss–Legendre in z × 64 points in φ.
template <typename Pdf>
double integrate_pdf(Pdf pdf, bool hemisphere) {
  std::vector<double> z, w;
  nm::append_gauss_legendre(32, hemisphere ? 0.0 : -1.0, 1.0, &z, &w);
  double sum = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) sum += w[i] * nm::kTwoPi * pdf(z[i]);
  return sum;
}

}  // namespace

TEST_CASE("direction samplers match their densities, which integrate to 1",
          "[numerics][sampling]") {
  // Chi-square over 256 cells equally likely under the stated pdf (64000 samples, 250 per
  // cell), rejected at the 0.1% level: a sampler off by a few percent in any region fails
  // (e.g. cosine samples against the uniform pdf give χ² in the thousands). Densities: their
  // integral over the domain by quadrature, to 1e-12.
  const int n = 64000;
  const double limit = chi_square_0001(255);
  const double cosine =
      direction_chi_square([](nm::Vec2<double> u) { return nm::sample_cosine_hemisphere(u); },
                           [](double z) { return z * z; }, n, true);  // P(cos θ ≤ z) = z²
  const double hemisphere =
      direction_chi_square([](nm::Vec2<double> u) { return nm::sample_uniform_hemisphere(u); },
                           [](double z) { return z; }, n, true);
  const double sphere =
      direction_chi_square([](nm::Vec2<double> u) { return nm::sample_uniform_sphere(u); },
                           [](double z) { return 0.5 * (z + 1.0); }, n, false);
  const double wrong =
      direction_chi_square([](nm::Vec2<double> u) { return nm::sample_cosine_hemisphere(u); },
                           [](double z) { return z; }, n, true);
  INFO("chi-square: cosine " << cosine << ", hemisphere " << hemisphere << ", sphere " << sphere
                             << ", cosine against the uniform pdf " << wrong << "; limit "
                             << limit);
  CHECK(cosine < limit);
  CHECK(hemisphere < limit);
  CHECK(sphere < limit);
  CHECK(wrong > 10 * limit);
  CHECK(integrate_pdf([](double z) { return nm::cosine_hemisphere_pdf(z); }, true) ==
        Approx(1.0).epsilon(1e-12));
  CHECK(integrate_pdf([](double) { return nm::uniform_hemisphere_pdf<double>(); }, true) ==
        Approx(1.0).epsilon(1e-12));
  CHECK(integrate_pdf([](double) { return nm::uniform_sphere_pdf<double>(); }, false) ==
        Approx(1.0).epsilon(1e-12));
  CHECK(nm::cosine_hemisphere_pdf(-0.5) == 0.0);
}

TEST_CASE("disc and triangle samplers are uniform", "[numerics][sampling]") {
  // Discs: chi-square over 16 × 16 cells equal in area (r² and φ), 0.1% level; the pdf 1/π
  // times the disc's area π is 1. Triangle: the barycentric moments E[b_i] = 1/3,
  // E[b_i²] = 1/6, E[b_i b_j] = 1/12 within 5 standard errors (σ ≤ 0.0012 at 64000 samples).
  const int n = 64000, side = 16;
  for (bool concentric : {true, false}) {
    std::vector<int> count(side * side, 0);
    nm::SplitMix64 rng{7};
    for (int i = 0; i < n; ++i) {
      const nm::Vec2<double> u{rng.uniform(), rng.uniform()};
      const nm::Vec2<double> p =
          concentric ? nm::sample_uniform_disk_concentric(u) : nm::sample_uniform_disk_polar(u);
      const double r2 = p.x * p.x + p.y * p.y;
      REQUIRE(r2 <= 1.0 + 1e-12);
      const double phi = std::atan2(p.y, p.x) + nm::kPi;
      ++count[std::min(side - 1, int(r2 * side)) * side +
              std::min(side - 1, int(phi / nm::kTwoPi * side))];
    }
    INFO("concentric " << concentric);
    CHECK(chi_square(count, double(n) / (side * side)) < chi_square_0001(side * side - 1));
  }
  CHECK(nm::uniform_disk_pdf<double>() * nm::kPi == Approx(1.0).epsilon(1e-15));
  CHECK(nm::sample_uniform_disk_concentric(nm::Vec2<double>{0.5, 0.5}).x == 0.0);

  nm::SplitMix64 rng{11};
  double m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0}, m01 = 0.0;
  for (int i = 0; i < n; ++i) {
    const nm::Vec3<double> b =
        nm::sample_uniform_triangle(nm::Vec2<double>{rng.uniform(), rng.uniform()});
    const double c[3] = {b.x, b.y, b.z};
    REQUIRE(std::abs(c[0] + c[1] + c[2] - 1.0) < 1e-15);
    for (int k = 0; k < 3; ++k) {
      REQUIRE(c[k] >= 0.0);
      m1[k] += c[k] / n;
      m2[k] += c[k] * c[k] / n;
    }
    m01 += c[0] * c[1] / n;
  }
  const double tol = 5 * std::sqrt(1.0 / 18.0 / n) + 1e-12;  // σ of b_i: √(1/18)/√n
  for (int k = 0; k < 3; ++k) {
    CHECK(std::abs(m1[k] - 1.0 / 3.0) < tol);
    CHECK(std::abs(m2[k] - 1.0 / 6.0) < tol);
  }
  CHECK(std::abs(m01 - 1.0 / 12.0) < tol);
  CHECK(nm::uniform_triangle_pdf(0.25) == 4.0);
}

TEST_CASE("float and double samplers agree, and the basis is right-handed orthonormal",
          "[numerics][sampling]") {
  nm::SplitMix64 rng{5};
  for (int i = 0; i < 1000; ++i) {
    const double u0 = rng.uniform(), u1 = rng.uniform();
    const nm::Vec3<double> d = nm::sample_cosine_hemisphere(nm::Vec2<double>{u0, u1});
    const nm::Vec3<float> f = nm::sample_cosine_hemisphere(
        nm::Vec2<float>{static_cast<float>(u0), static_cast<float>(u1)});
    CHECK(std::abs(d.x - f.x) < 1e-5);
    CHECK(std::abs(d.y - f.y) < 1e-5);
    CHECK(std::abs(d.z - f.z) < 2e-3);  // √(1 − r²) loses precision near the rim in float
  }
  // Random unit normals, and the poles (the branch of Duff et al.'s construction).
  std::vector<nm::Vec3<double>> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  for (int i = 0; i < 200; ++i)
    normals.push_back(nm::sample_uniform_sphere(nm::Vec2<double>{rng.uniform(), rng.uniform()}));
  for (const nm::Vec3<double>& n : normals) {
    nm::Vec3<double> t, b;
    nm::build_orthonormal_basis(n, &t, &b);
    const auto dot = [](const nm::Vec3<double>& p, const nm::Vec3<double>& q) {
      return p.x * q.x + p.y * q.y + p.z * q.z;
    };
    CHECK(std::abs(dot(t, t) - 1.0) < 1e-14);
    CHECK(std::abs(dot(b, b) - 1.0) < 1e-14);
    CHECK(std::abs(dot(t, b)) < 1e-14);
    CHECK(std::abs(dot(t, n)) < 1e-14);
    CHECK(std::abs(dot(b, n)) < 1e-14);
    // t × b = n (right-handed).
    const nm::Vec3<double> c{t.y * b.z - t.z * b.y, t.z * b.x - t.x * b.z, t.x * b.y - t.y * b.x};
    CHECK(dot(c, n) == Approx(1.0).epsilon(1e-14));
  }
}
