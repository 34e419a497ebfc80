// sample_rng.h — the random stream of the report's Monte Carlo ground truths (internal).
#pragma once

#include <cstdint>

namespace prt::report::detail {

// SplitMix64 stream seeded per (item, sample), e.g. hash_seed(hash_seed(seed, vertex), sample):
// uniform doubles in [0, 1) with 53 random bits. The same seed gives the same stream on any
// thread, which is what makes the ground truths bit-identical for any thread count.
struct SampleRng {
  uint64_t state;
  double next() {
    state += 0x9e3779b97f4a7c15ull;
    uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

}  // namespace prt::report::detail
