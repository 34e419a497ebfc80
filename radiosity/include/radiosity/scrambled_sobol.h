// radiosity/scrambled_sobol.h — the first four dimensions of the Sobol' sequence in base 2,
// randomised by a hashed nested scramble: the ray form factors' 4-D samples (point on the
// sending patch × direction; radiosity/form_factors.h, RaySampling::Sobol). Header-only.
//
// Generator matrices: dimension 0 is the van der Corput sequence (the identity); dimensions 1–3
// use the primitive polynomials and initial direction numbers of Joe & Kuo ([90] of
// docs/REFERENCES.md; their d = 2, 3, 4: (s, a, m) = (1, 0, {1}), (2, 1, {1, 3}),
// (3, 1, {1, 3, 1})) and Bratley & Fox's recurrence
//   v_k = v_{k−s} ⊕ (v_{k−s} ≫ s) ⊕ ⊕_{l=1}^{s−1} a_l · v_{k−l},
// where a_l is bit s−1−l of a. Point n is ⊕ v_k over the set bits k of n, 32 bits per coordinate.
//
// Randomisation: a nested scramble in the manner of Owen, computed by a hash as Burley ([91])
// describes it: each coordinate's bits are reversed, mapped by
//   x ← x + r;  then x ← x ⊕ (x · c) for a few even constants c,
// and reversed back. Multiplying by an even constant carries only toward higher bits, so after
// the reversal each bit is flipped by a function of the more significant bits alone (a nested
// scramble: the net's strata are permuted, never broken), and x + r with r a uniformly random
// 32-bit word (one per dimension, drawn per row) followed by bijections makes every point
// uniformly distributed on the 2⁻³² grid of [0, 1)⁴ (centred in its cell, never 0 or 1): the
// estimator stays unbiased. A set of 2^m points keeps the net's stratification: every 1-D
// projection has exactly one point in each interval [k/2^m, (k+1)/2^m), and dimensions (0, 1)
// form a (0, m, 2)-net. The constants are this file's own (odd multiples of 2, arbitrary).
#pragma once

#include <array>
#include <cstdint>

namespace prt::radiosity {

class ScrambledSobol4 {
 public:
  static constexpr int kDimensions = 4;

  // `seeds`: the row's four random words (e.g. from PatchRandom).
  explicit ScrambledSobol4(const std::array<uint32_t, kDimensions>& seeds) : seeds_(seeds) {}

  // Coordinates of point n in [0, 1).
  std::array<double, kDimensions> point(uint32_t n) const {
    std::array<uint32_t, kDimensions> x{};
    const Matrices& v = matrices();
    for (int k = 0; n != 0; ++k, n >>= 1)
      if (n & 1u)
        for (int d = 0; d < kDimensions; ++d) x[d] ^= v[d][k];
    std::array<double, kDimensions> u;
    for (int d = 0; d < kDimensions; ++d)
      u[d] = (double(scramble(x[d], seeds_[d])) + 0.5) * 0x1p-32;
    return u;
  }

  static uint32_t reverse_bits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
  }

  // The nested scramble of one coordinate (see above).
  static uint32_t scramble(uint32_t x, uint32_t seed) {
    x = reverse_bits(x);
    x += seed;
    x ^= x * 0x9E3779B8u;
    x ^= x * 0x85EBCA6Cu;
    x ^= x * 0xC2B2AE3Au;
    x ^= x * 0x27D4EB2Eu;
    return reverse_bits(x);
  }

 private:
  using Matrices = std::array<std::array<uint32_t, 32>, kDimensions>;

  static Matrices make_matrices() {
    struct Polynomial {
      int s;
      uint32_t a;
      std::array<uint32_t, 3> m;
    };
    const Polynomial polynomials[3] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
    Matrices v{};
    for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
    for (int d = 1; d < kDimensions; ++d) {
      const Polynomial& p = polynomials[d - 1];
      for (int k = 0; k < 32; ++k) {
        if (k < p.s) {
          v[d][k] = p.m[k] << (31 - k);
          continue;
        }
        uint32_t value = v[d][k - p.s] ^ (v[d][k - p.s] >> p.s);
        for (int l = 1; l < p.s; ++l)
          if ((p.a >> (p.s - 1 - l)) & 1u) value ^= v[d][k - l];
        v[d][k] = value;
      }
    }
    return v;
  }

  static const Matrices& matrices() {
    static const Matrices v = make_matrices();
    return v;
  }

  std::array<uint32_t, kDimensions> seeds_;
};

}  // namespace prt::radiosity
