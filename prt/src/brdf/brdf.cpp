// Directional albedo by stratified importance sampling.
#include "prt/brdf/brdf.h"

#include <algorithm>
#include <cmath>

namespace prt::brdf {

namespace {

// splitmix64 (Steele, Lea & Flood 2014), mapped to [0, 1) with 53 bits.
struct SplitMix64 {
  uint64_t state;
  double next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

}  // namespace

Rgb directional_albedo(const Brdf& brdf, const Vec3& wo, int n, uint64_t seed,
                       double* standard_error) {
  SplitMix64 rng{seed};
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  const int count = std::max(1, n) * std::max(1, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u1 = (i + rng.next()) / n;
      const double u2 = (j + rng.next()) / n;
      const BrdfSample s =
          brdf.sample(wo, std::min(u1, 0x1.fffffffffffffp-1), std::min(u2, 0x1.fffffffffffffp-1));
      if (!(s.pdf > 0.0) || s.wi.z <= 0.0) continue;
      const double w = s.wi.z / s.pdf;
      const double v[3] = {s.f.r * w, s.f.g * w, s.f.b * w};
      for (int c = 0; c < 3; ++c) {
        sum[c] += v[c];
        sum2[c] += v[c] * v[c];
      }
    }
  }
  if (standard_error) {
    // The i.i.d. standard error: an upper bound for stratified sampling.
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c] / count;
      const double var = std::max(0.0, sum2[c] / count - mean * mean);
      worst = std::max(worst, std::sqrt(var / count));
    }
    *standard_error = worst;
  }
  return {sum[0] / count, sum[1] / count, sum[2] / count};
}

}  // namespace prt::brdf
