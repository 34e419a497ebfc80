// numerics/hash.h — 64-bit integer hashing: the SplitMix64 finaliser, per-item seeds, and a
// word hash (FNV-1a over 32-bit words, finalised) for fingerprints.
//
// mix64 is the finaliser of SplitMix64 (Steele, Lea & Flood 2014; Stafford's "Mix13" constants):
// a bijection of 64-bit words with full avalanche. splitmix64(x) is the first output of a
// SplitMix64 stream seeded with x (mix64 of x plus the golden-ratio increment), so
// splitmix64(0) = 0xe220a8397b1dcdaf, the reference value of the published generator.
// hash_seed(seed, index) derives the seed of item `index` (a vertex, a patch, a sample) from a
// run's seed; results that depend only on (seed, index) are the same for any thread count.
// hash_values hashes several integers by chaining hash_seed. WordHash is the geometry
// fingerprint's hash: FNV-1a-64 (Fowler–Noll–Vo) over 32-bit words, then mix64; floats enter
// by bit pattern with −0 as +0. None of this is cryptographic.
// References: [17] of docs/REFERENCES.md (SplitMix64); docs/NUMERICS.md.
#pragma once

#include <cstdint>
#include <cstring>

namespace prt::numerics {

// 2⁶⁴/φ rounded to odd: SplitMix64's increment ("golden gamma").
inline constexpr uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ull;

// The SplitMix64 finaliser: a bijection on 64-bit words with good avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// The first output of a SplitMix64 stream seeded with x: mix64(x + golden gamma).
constexpr uint64_t splitmix64(uint64_t x) {
  return mix64(x + kGoldenGamma);
}

// The seed of item `index` under a run's `seed` (the finaliser applied twice, the index spread
// by an odd multiplier first): well distributed bits for consecutive indices and seeds.
constexpr uint64_t hash_seed(uint64_t seed, uint64_t index) {
  return mix64(mix64(seed + kGoldenGamma) ^ (index * 0xd1b54a32d192ed03ull));
}

// A hash of several integers: hash_values(a) = splitmix64(a), hash_values(a, b, …) =
// hash_values(hash_seed(a, b), …), so hash_values(seed, i) = hash_seed(seed, i) for two values.
constexpr uint64_t hash_values(uint64_t a) {
  return splitmix64(a);
}
template <typename... Rest>
constexpr uint64_t hash_values(uint64_t a, uint64_t b, Rest... rest) {
  if constexpr (sizeof...(rest) == 0) {
    return hash_seed(a, b);
  } else {
    return hash_values(hash_seed(a, b), static_cast<uint64_t>(rest)...);
  }
}

// FNV-1a-64 over 32-bit words with the mix64 finaliser: fingerprints of geometry and options.
class WordHash {
 public:
  constexpr void add_word(uint32_t w) { h_ = (h_ ^ w) * 0x100000001b3ull; }
  // Low word first, then the high word.
  constexpr void add_u64(uint64_t v) {
    add_word(static_cast<uint32_t>(v & 0xffffffffu));
    add_word(static_cast<uint32_t>(v >> 32));
  }
  // The bit pattern of v, with −0 entered as +0 (so −0 and +0 hash alike).
  void add_float(float v) {
    uint32_t w;
    std::memcpy(&w, &v, sizeof w);
    add_word(w == 0x80000000u ? 0u : w);
  }
  constexpr uint64_t finish() const { return mix64(h_); }

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;  // the FNV-1a-64 offset basis
};

}  // namespace prt::numerics
