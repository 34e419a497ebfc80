// numerics/rng.h — the one small random-number stream of prt: SplitMix64 (Steele, Lea & Flood
// 2014, [17] of docs/REFERENCES.md), and the mapping of its 64-bit words to uniform numbers.
//
// SplitMix64 is a Weyl sequence (state += golden gamma) passed through numerics/hash.h's mix64:
// output k (k = 1, 2, …) of the stream seeded with s is mix64(s + k·γ). Period 2⁶⁴, every seed
// valid, passes BigCrush; fast enough for Monte Carlo estimators and test data. A stream is an
// aggregate, SplitMix64{seed}, so it can be seeded per item with hash_seed (numerics/hash.h) and
// results do not depend on the thread that draws them. Not cryptographic.
// Uniform numbers: the top 53 bits of a word, times 2⁻⁵³ — a double in [0, 1) on the 2⁻⁵³ grid
// (never 1). Seed 1234567 gives 6457827717110365317, 3203168211198807973, … (the published
// reference outputs; tests/sh/test_numerics.cpp).
#pragma once

#include <cstdint>

#include "numerics/hash.h"

namespace prt::numerics {

// The top 53 bits of a 64-bit word as a double in [0, 1).
constexpr double unit_double_from_bits(uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

struct SplitMix64 {
  uint64_t state;

  // The next 64-bit word of the stream.
  constexpr uint64_t next_u64() {
    state += kGoldenGamma;
    return mix64(state);
  }
  // The next uniform double in [0, 1) (53 random bits).
  constexpr double uniform() { return unit_double_from_bits(next_u64()); }
};

}  // namespace prt::numerics
