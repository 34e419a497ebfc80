// numerics/low_discrepancy.h — the Sobol' sequence in base 2, up to kSobolDimensions
// dimensions, randomised by a hash-based Owen (nested uniform) scramble.
//
// Generator matrices: dimension 0 is the van der Corput sequence (the identity matrix, i.e. the
// bit reversal of the index); dimensions 1 … 20 use the primitive polynomials and initial
// direction numbers of Joe & Kuo's new-joe-kuo-6.21201 table (their d = 2 … 21; [90] of
// docs/REFERENCES.md), expanded by Bratley & Fox's recurrence
//   v_k = v_{k−s} ⊕ (v_{k−s} ≫ s) ⊕ ⊕_{l=1}^{s−1} a_l · v_{k−l},  v_k = m_k · 2^{31−k} for k < s,
// where a_l is bit s−1−l of a. Point i is ⊕ v_k over the set bits k of i (no Gray code), as
// 32-bit fixed-point fractions. Dimension 1 is the Pascal matrix mod 2; dimensions (0, 1) form
// a (0, 2)-sequence: every aligned block of 2^m points is a (0, m, 2)-net.
//
// Scramble: owen_scramble is the Laine–Karras style permutation of Burley ([10], [91]) with
// Vegdahl's constants: on the bit-reversed value, x += seed and multiplications by constants
// that carry only toward higher bits, then reversed back, so each output bit is flipped by a
// function of the seed and of the more significant input bits alone — a nested scramble. It
// keeps every elementary interval's count (the nets stay nets) and makes each point uniform on
// the 2⁻³² grid. Per dimension d the 32-bit scramble seed is owen_seed(seed, d): the low and high
// halves of the 64-bit seed for d = 0, 1, of hash_seed(seed, d/2) (numerics/hash.h) after that.
//
// Conversions: a 32-bit fraction x becomes the float min(x·2⁻³², 1 − 2⁻²⁴) (float rounding could
// reach 1) or the exact double x·2⁻³², both in [0, 1).
// Hot-path functions are constexpr/inline here (the bakers call them per ray).
#pragma once

#include <algorithm>
#include <cstdint>

#include "numerics/constants.h"
#include "numerics/hash.h"

namespace prt::numerics {

inline constexpr int kSobolDimensions = 21;

// x with its 32 bits in reverse order.
constexpr uint32_t reverse_bits32(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

namespace detail {

// Degree s, coefficients a and initial direction numbers m_1 … m_s of one primitive polynomial.
struct SobolPolynomial {
  int s;
  uint32_t a;
  uint32_t m[7];
};

// Joe & Kuo, new-joe-kuo-6.21201, d = 2 … 21.
inline constexpr SobolPolynomial kJoeKuo[kSobolDimensions - 1] = {
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}},
    {5, 13, {1, 1, 1, 3, 11}},
    {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}},
    {6, 13, {1, 1, 1, 15, 21, 21}},
    {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}},
    {6, 22, {1, 3, 1, 15, 13, 25}},
    {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},
};

struct SobolMatrices {
  uint32_t v[kSobolDimensions][32];
};

constexpr SobolMatrices make_sobol_matrices() {
  SobolMatrices r{};
  for (int k = 0; k < 32; ++k) r.v[0][k] = 1u << (31 - k);
  for (int d = 1; d < kSobolDimensions; ++d) {
    const SobolPolynomial& p = kJoeKuo[d - 1];
    uint32_t* v = r.v[d];
    for (int k = 0; k < 32; ++k) {
      if (k < p.s) {
        v[k] = p.m[k] << (31 - k);
        continue;
      }
      uint32_t value = v[k - p.s] ^ (v[k - p.s] >> p.s);
      for (int l = 1; l < p.s; ++l)
        if ((p.a >> (p.s - 1 - l)) & 1u) value ^= v[k - l];
      v[k] = value;
    }
  }
  return r;
}

}  // namespace detail

// The generator matrices, column k of dimension d as the 32-bit fraction v[d][k].
inline constexpr detail::SobolMatrices kSobolMatrices = detail::make_sobol_matrices();

// Unscrambled coordinate `dimension` (0 ≤ dimension < kSobolDimensions) of Sobol' point `index`.
constexpr uint32_t sobol_bits(uint32_t index, int dimension) {
  if (dimension == 0) return reverse_bits32(index);
  if (dimension == 1) {
    // Pascal's matrix mod 2 (= kSobolMatrices.v[1]) built on the fly, column k + 1 being
    // column k ⊕ (column k ≫ 1): no table loads in the bakers' 2-D loop.
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
      if (index & 1u) r ^= v;
    return r;
  }
  uint32_t r = 0;
  for (int k = 0; index != 0; ++k, index >>= 1)
    if (index & 1u) r ^= kSobolMatrices.v[dimension][k];
  return r;
}

// The hash-based Owen scramble of a 32-bit fraction x under a 32-bit seed.
constexpr uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  x = reverse_bits32(x);
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return reverse_bits32(x);
}

// The 32-bit scramble seed of `dimension` under a 64-bit sequence seed (see above).
constexpr uint32_t owen_seed(uint64_t seed, int dimension) {
  const uint64_t word =
      dimension < 2 ? seed : hash_seed(seed, static_cast<uint64_t>(dimension / 2));
  return static_cast<uint32_t>(word >> (32 * (dimension & 1)));
}

// Coordinate `dimension` of point `index` of the Owen-scrambled Sobol' sequence of `seed`.
constexpr uint32_t sobol_owen_bits(uint32_t index, int dimension, uint64_t seed) {
  return owen_scramble(sobol_bits(index, dimension), owen_seed(seed, dimension));
}

// A 32-bit fraction as a float in [0, 1).
inline float unit_float_from_bits32(uint32_t x) {
  return std::min(static_cast<float>(x) * 0x1p-32f, kOneMinusEpsilonFloat);
}

// A 32-bit fraction as the exact double x·2⁻³² in [0, 1).
constexpr double unit_double_from_bits32(uint32_t x) {
  return static_cast<double>(x) * 0x1p-32;
}

// Owen-scrambled Sobol' coordinates in [0, 1).
inline float sobol_owen_float(uint32_t index, int dimension, uint64_t seed) {
  return unit_float_from_bits32(sobol_owen_bits(index, dimension, seed));
}
constexpr double sobol_owen_double(uint32_t index, int dimension, uint64_t seed) {
  return unit_double_from_bits32(sobol_owen_bits(index, dimension, seed));
}

}  // namespace prt::numerics
