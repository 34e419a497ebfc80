// Non-linear and linear Haar lighting approximation; see prt/haar/approximation.h.
#include "prt/haar/approximation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace prt {

std::vector<double> haar_area_weights(int size) {
  const std::vector<double> omega = cube_face_solid_angles(size);
  // Summed-area table of texel solid angles, so each support's solid angle is 4 lookups.
  const int n = size;
  std::vector<double> sat(static_cast<size_t>(n + 1) * (n + 1), 0.0);
  for (int r = 0; r < n; ++r) {
    double row_sum = 0.0;
    for (int c = 0; c < n; ++c) {
      row_sum += omega[static_cast<size_t>(r) * n + c];
      sat[static_cast<size_t>(r + 1) * (n + 1) + c + 1] =
          sat[static_cast<size_t>(r) * (n + 1) + c + 1] + row_sum;
    }
  }
  std::vector<double> weights(static_cast<size_t>(n) * n);
  for (int q = 0; q < n * n; ++q) {
    const HaarCoefficientInfo info = describe_haar_coefficient(n, q);
    const int r0 = info.support_row, c0 = info.support_col, s = info.support_size;
    const auto at = [&](int r, int c) { return sat[static_cast<size_t>(r) * (n + 1) + c]; };
    const double support = at(r0 + s, c0 + s) - at(r0, c0 + s) - at(r0 + s, c0) + at(r0, c0);
    weights[q] = support / s;
  }
  return weights;
}

double haar_selection_score(double area_weight, const float rgb[3]) noexcept {
  double m = 0.0;
  for (int c = 0; c < 3; ++c) {
    if (std::isfinite(rgb[c])) m = std::max(m, static_cast<double>(std::fabs(rgb[c])));
  }
  return area_weight * m;
}

namespace {

bool is_consistent(const WaveletCube& w) {
  return is_valid_cube_size(w.size) &&
         w.rgb.size() == static_cast<size_t>(w.coefficient_count()) * 3;
}

// Builds the sparse vector from chosen indices (sorted here), zeroing non-finite values.
SparseLighting gather_terms(const WaveletCube& lighting, std::vector<uint32_t> chosen) {
  std::sort(chosen.begin(), chosen.end());
  SparseLighting out;
  out.size = lighting.size;
  out.rgb.reserve(chosen.size() * 3);
  for (uint32_t i : chosen) {
    for (int c = 0; c < 3; ++c) {
      const float v = lighting.rgb[3 * static_cast<size_t>(i) + c];
      out.rgb.push_back(std::isfinite(v) ? v : 0.0f);
    }
  }
  out.index = std::move(chosen);
  return out;
}

}  // namespace

SparseLighting select_nonlinear(const WaveletCube& lighting, int64_t k) {
  if (!is_consistent(lighting)) return SparseLighting{lighting.size, {}, {}};
  const int64_t total = lighting.coefficient_count();
  k = std::clamp<int64_t>(k, 0, total);
  const int n2 = lighting.size * lighting.size;
  const std::vector<double> weights = haar_area_weights(lighting.size);
  std::vector<double> score(static_cast<size_t>(total));
  for (int64_t i = 0; i < total; ++i) {
    score[i] = haar_selection_score(weights[i % n2], &lighting.rgb[3 * static_cast<size_t>(i)]);
  }
  std::vector<uint32_t> order(static_cast<size_t>(total));
  std::iota(order.begin(), order.end(), 0u);
  // A strict total order (score descending, then index ascending) makes the set unique.
  const auto before = [&](uint32_t x, uint32_t y) {
    return score[x] != score[y] ? score[x] > score[y] : x < y;
  };
  if (k < total) std::nth_element(order.begin(), order.begin() + k, order.end(), before);
  order.resize(static_cast<size_t>(k));
  return gather_terms(lighting, std::move(order));
}

SparseLighting select_linear(const WaveletCube& lighting, int64_t k) {
  if (!is_consistent(lighting)) return SparseLighting{lighting.size, {}, {}};
  const int64_t total = lighting.coefficient_count();
  k = std::clamp<int64_t>(k, 0, total);
  const uint32_t n2 = static_cast<uint32_t>(lighting.size) * lighting.size;
  // Walk levels coarse to fine; within a level, face by face, q ascending.
  std::vector<uint32_t> chosen;
  chosen.reserve(static_cast<size_t>(k));
  // The scaling coefficients [0, 1) first, then level j = [4^j, 4^(j+1)).
  uint32_t level_begin = 0, level_end = 1;
  while (static_cast<int64_t>(chosen.size()) < k && level_begin < n2) {
    for (uint32_t face = 0; face < kCubeFaceCount; ++face) {
      for (uint32_t q = level_begin; q < level_end; ++q) {
        if (static_cast<int64_t>(chosen.size()) == k) break;
        chosen.push_back(face * n2 + q);
      }
    }
    level_begin = level_end;
    level_end *= 4;
  }
  return gather_terms(lighting, std::move(chosen));
}

SparseLighting keep_all_terms(const WaveletCube& lighting) {
  if (!is_consistent(lighting)) return SparseLighting{lighting.size, {}, {}};
  std::vector<uint32_t> all(static_cast<size_t>(lighting.coefficient_count()));
  std::iota(all.begin(), all.end(), 0u);
  return gather_terms(lighting, std::move(all));
}

}  // namespace prt
