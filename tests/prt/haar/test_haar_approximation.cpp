// Tests of non-linear and linear Haar lighting approximation (prt/haar/approximation.h).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/haar/approximation.h"
#include "sh/constants.h"

namespace {

prt::WaveletCube random_wavelets(int n, uint32_t seed) {
  prt::WaveletCube w;
  w.size = n;
  w.rgb.resize(static_cast<size_t>(6) * n * n * 3);
  std::mt19937 rng(seed);
  std::normal_distribution<float> dist(0.0f, 1.0f);
  for (float& v : w.rgb) v = dist(rng);
  return w;
}

// Area weight by brute force: ∫|ψ_q| dω = Σ_t |ψ_q(t)|·ω_t (independent of the library's
// summed-area table).
std::vector<double> brute_force_weights(int n) {
  std::vector<double> w(static_cast<size_t>(n) * n, 0.0);
  for (int q = 0; q < n * n; ++q)
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        w[q] +=
            std::fabs(prt::evaluate_haar_basis(n, q, r, c)) * prt::cube_texel_solid_angle(n, c, r);
  return w;
}

// Reference selection: sort everything by (score desc, index asc), take the first k.
std::vector<uint32_t> reference_selection(const prt::WaveletCube& w, int64_t k) {
  const int n2 = w.size * w.size;
  const std::vector<double> weights = brute_force_weights(w.size);
  const size_t total = static_cast<size_t>(6) * n2;
  std::vector<double> score(total);
  for (size_t i = 0; i < total; ++i) {
    double m = 0.0;
    for (int c = 0; c < 3; ++c) m = std::max(m, static_cast<double>(std::fabs(w.rgb[3 * i + c])));
    score[i] = m * weights[i % n2];
  }
  std::vector<uint32_t> order(total);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return score[a] != score[b] ? score[a] > score[b] : a < b;
  });
  order.resize(static_cast<size_t>(std::min<int64_t>(k, total)));
  std::sort(order.begin(), order.end());
  return order;
}

}  // namespace

TEST_CASE("Area weights equal the integral of |basis| over exact texel solid angles",
          "[haar][approximation]") {
  for (int n : {8, 16}) {
    const std::vector<double> fast = prt::haar_area_weights(n);
    const std::vector<double> slow = brute_force_weights(n);
    // Both sum the same exact solid angles in different orders: double rounding only.
    for (size_t q = 0; q < fast.size(); ++q) REQUIRE(fast[q] == Approx(slow[q]).epsilon(1e-12));
    // The scaling function covers the face (4π/6) with amplitude 1/N.
    CHECK(fast[0] == Approx(4.0 * prt::sh::kPi / 6.0 / n).epsilon(1e-12));
  }
}

TEST_CASE("Non-linear selection keeps the largest area-weighted terms", "[haar][approximation]") {
  const prt::WaveletCube w = random_wavelets(8, 21);
  for (int64_t k : {1, 10, 100, 383, 384, 1000}) {
    const prt::SparseLighting s = prt::select_nonlinear(w, k);
    const std::vector<uint32_t> expected = reference_selection(w, k);
    INFO("K = " << k);
    REQUIRE(s.index == expected);
    REQUIRE(s.rgb.size() == 3 * s.index.size());
    for (size_t j = 0; j < s.index.size(); ++j)
      for (int c = 0; c < 3; ++c) REQUIRE(s.rgb[3 * j + c] == w.rgb[3 * s.index[j] + c]);
  }
  CHECK(prt::select_nonlinear(w, 0).index.empty());
  CHECK(prt::select_nonlinear(w, -5).index.empty());
}

TEST_CASE("Non-linear selection breaks ties by the lower wavelet index", "[haar][approximation]") {
  // All coefficients 1: scores equal the area weights. The scaling and the three level-0
  // details of each face all cover the whole face with amplitude 1/N, so those 24 tie for the
  // top; K = 5 must take face 0's four and face 1's scaling coefficient (index N² = 64).
  prt::WaveletCube w;
  w.size = 8;
  w.rgb.assign(static_cast<size_t>(6) * 64 * 3, 1.0f);
  const prt::SparseLighting s = prt::select_nonlinear(w, 5);
  CHECK(s.index == std::vector<uint32_t>{0, 1, 2, 3, 64});
  // Same answer on a repeated call (deterministic), and the reference agrees.
  CHECK(prt::select_nonlinear(w, 5).index == s.index);
  CHECK(reference_selection(w, 5) == s.index);
  // A colour-only coefficient counts by its largest channel: a blue-only term outranks a
  // uniformly dimmer grey one at the same weight.
  w.rgb.assign(w.rgb.size(), 0.0f);
  w.rgb[3 * 70 + 2] = 2.0f;                      // face 1, q = 6: blue 2
  w.rgb[3 * 71 + 0] = w.rgb[3 * 71 + 1] = 1.5f;  // face 1, q = 7: grey-ish 1.5
  CHECK(prt::select_nonlinear(w, 1).index == std::vector<uint32_t>{70});
}

TEST_CASE("Linear selection keeps the coarsest terms", "[haar][approximation]") {
  const prt::WaveletCube w = random_wavelets(16, 4);
  const uint32_t n2 = 256;
  const prt::SparseLighting six = prt::select_linear(w, 6);
  CHECK(six.index == std::vector<uint32_t>{0, n2, 2 * n2, 3 * n2, 4 * n2, 5 * n2});
  for (int64_t k : {6, 24, 30, 100, 6 * 256}) {
    const prt::SparseLighting s = prt::select_linear(w, k);
    REQUIRE(static_cast<int64_t>(s.index.size()) == k);
    // Every kept term is at least as coarse as every dropped one (scaling counted as coarser
    // than level 0 details).
    const auto rank = [&](uint32_t i) {
      const int q = static_cast<int>(i % n2);
      const prt::HaarCoefficientInfo info = prt::describe_haar_coefficient(16, q);
      return info.band < 0 ? -1 : info.level;
    };
    const std::set<uint32_t> kept(s.index.begin(), s.index.end());
    int worst_kept = -2, best_dropped = 100;
    for (uint32_t i = 0; i < 6 * n2; ++i) {
      if (kept.count(i)) {
        worst_kept = std::max(worst_kept, rank(i));
      } else {
        best_dropped = std::min(best_dropped, rank(i));
      }
    }
    INFO("K = " << k);
    CHECK(worst_kept <= best_dropped);
  }
  // K = 30: all 24 of level ≤ 0, then face 0's first six level-1 terms (q = 4..9).
  const prt::SparseLighting s30 = prt::select_linear(w, 30);
  for (uint32_t q = 4; q < 10; ++q)
    CHECK(std::binary_search(s30.index.begin(), s30.index.end(), q));
}

TEST_CASE("Non-linear approximation beats linear on a small bright light",
          "[haar][approximation]") {
  // A sun in one texel: the non-linear choice should capture (almost) all its power with few
  // terms; the linear one with the same K cannot. This is the point of Ng et al.
  const int n = 32;
  prt::CubeMap cube = prt::make_black_cube_map(n);
  for (float& v : cube.rgb) v = 0.1f;
  float* sun = &cube.rgb[3 * (4 * n * n + 5 * n + 20)];
  sun[0] = sun[1] = sun[2] = 1e4f;
  const prt::WaveletCube w = *prt::transform_cube(cube);
  const auto energy_kept = [&](const prt::SparseLighting& s) {
    double e = 0.0;
    for (float v : s.rgb) e += static_cast<double>(v) * v;
    return e;
  };
  double total = 0.0;
  for (float v : w.rgb) total += static_cast<double>(v) * v;
  const double nonlinear = energy_kept(prt::select_nonlinear(w, 100));
  const double linear = energy_kept(prt::select_linear(w, 100));
  // The sun's energy is spread over the log2(N)+1 = 6 coefficients covering it (× 3 bands
  // per level); the 100 largest must hold essentially all of it, linear well below half.
  CHECK(nonlinear > 0.999 * total);
  CHECK(linear < 0.5 * total);
}
