// Directional albedo by stratified importance sampling.
#include "prt/brdf/brdf.h"

#include <algorithm>
#include <cmath>

#include "numerics/constants.h"
#include "numerics/rng.h"

namespace prt::brdf {

Rgb directional_albedo(const Brdf& brdf, const Vec3& wo, int n, uint64_t seed,
                       double* standard_error) {
  numerics::SplitMix64 rng{seed};
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  const int count = std::max(1, n) * std::max(1, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u1 = (i + rng.uniform()) / n;
      const double u2 = (j + rng.uniform()) / n;
      const BrdfSample s = brdf.sample(wo, std::min(u1, numerics::kOneMinusEpsilon),
                                       std::min(u2, numerics::kOneMinusEpsilon));
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
