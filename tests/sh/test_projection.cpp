// Tests of sh/projection.h: constant maps in every layout, single bright texels landing where
// the README's conventions say, the separable lat-long path against the direct sum, recovery of a
// known band-limited function, skipped NaN/Inf/negative texels, and reconstruct().
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_map.h"
#include "sh/projection.h"

namespace {

using prt::sh::kPi;
using prt::sh::kY00;
constexpr double kY1 = 0.48860251190291992;   // √(3/4π)

prt::sh::EnvMap make_map(prt::sh::EnvLayout layout, int width, int height, float r, float g, float b) {
  prt::sh::EnvMap env;
  env.layout = layout;
  env.width = width;
  env.height = height;
  env.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < env.rgb.size(); i += 3) {
    env.rgb[i] = r;
    env.rgb[i + 1] = g;
    env.rgb[i + 2] = b;
  }
  return env;
}

void set_texel(prt::sh::EnvMap* env, int col, int row, float r, float g, float b) {
  float* texel = &env->rgb[(static_cast<std::size_t>(row) * env->width + col) * 3];
  texel[0] = r;
  texel[1] = g;
  texel[2] = b;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST_CASE("a constant environment projects to sqrt(4 pi) c in every layout") {
  struct Case {
    prt::sh::EnvLayout layout;
    int width, height;
    double higher_band_tolerance;
  };
  // Band 0 is exact up to the solid angles' exactness (1e-12). Higher bands vanish only as far as
  // the texel-centre quadrature resolves them: the measured worst |c_k|/c_0 for bands 1–3 is
  // 7.8e-4 for lat-long 64x32 (midpoint rule in θ, O(1/H²)) and 5.8e-4 for angular 64² (texels
  // near the rim span large angles); tolerance 2e-3 (2.5x margin). Cube maps are invariant under
  // the cube's rotations, which leave no function of bands 1–3 invariant: those coefficients
  // cancel to rounding (measured 3e-16), so the tolerance there is 1e-13.
  const Case cases[] = {{prt::sh::EnvLayout::LatLong, 64, 32, 2e-3},
                        {prt::sh::EnvLayout::Angular, 64, 64, 2e-3},
                        {prt::sh::EnvLayout::Cross, 48, 64, 1e-13},
                        {prt::sh::EnvLayout::Faces, 16, 96, 1e-13}};
  const float colour[3] = {0.5f, 1.25f, 3.0f};
  for (const Case& c : cases) {
    INFO(prt::sh::layout_name(c.layout));
    const prt::sh::EnvMap env = make_map(c.layout, c.width, c.height, colour[0], colour[1], colour[2]);
    prt::sh::ProjectionStats stats;
    const int order = 4;
    const std::vector<double> coefficients = prt::sh::project(env, order, &stats);
    REQUIRE(coefficients.size() == 3u * 16u);
    CHECK(stats.solid_angle_sum == Approx(4 * kPi).epsilon(1e-12));
    CHECK(stats.skipped_texels() == 0u);
    for (int channel = 0; channel < 3; ++channel) {
      const double c0 = coefficients[channel * 16];
      CHECK(c0 == Approx(std::sqrt(4 * kPi) * colour[channel]).epsilon(1e-12));
      double worst = 0.0;
      for (int k = 1; k < 16; ++k)
        worst = std::max(worst, std::abs(coefficients[channel * 16 + k]));
      INFO("worst higher-band |c_k| / c_0 = " << worst / c0);
      CHECK(worst / c0 < c.higher_band_tolerance);
    }
  }
}

TEST_CASE("a single bright texel lands in the direction the layout's convention says") {
  // Expected directions are the conventions' closed forms (see test_env_map.cpp), not the code's.
  // With one lit texel, L_0 = ω f Y00 and (L_1,1, L_1,−1, L_1,0) = ω f 0.488603 (x, y, z):
  // exact up to rounding, so the direction must match to 1e-12.
  struct Case {
    prt::sh::EnvLayout layout;
    int width, height, col, row;
    double x, y, z;
  };
  const double t = 2.0 / 3.0;
  const Case cases[] = {
      {prt::sh::EnvLayout::LatLong, 5, 3, 2, 1, 1, 0, 0},         // centre column at the horizon: +X
      {prt::sh::EnvLayout::LatLong, 6, 3, 1, 1, 0, 0, -1},        // u = 1/4: −Z
      {prt::sh::EnvLayout::LatLong, 6, 3, 4, 1, 0, 0, 1},         // u = 3/4: +Z
      {prt::sh::EnvLayout::LatLong, 10, 5, 7, 0, 0.0, 0.0, 0.0},  // filled in below (row 0, +Y side)
      {prt::sh::EnvLayout::Angular, 5, 5, 2, 2, 0, 0, -1},        // centre: −Z
      {prt::sh::EnvLayout::Angular, 5, 5, 4, 2, std::sin(0.8 * kPi), 0, -std::cos(0.8 * kPi)},
      {prt::sh::EnvLayout::Angular, 5, 5, 2, 0, 0, std::sin(0.8 * kPi), -std::cos(0.8 * kPi)},
      {prt::sh::EnvLayout::Cross, 9, 12, 4, 10, 0, 0, 1},    // +Z cell centre
      {prt::sh::EnvLayout::Cross, 9, 12, 7, 4, 1, 0, 0},     // +X cell centre
      {prt::sh::EnvLayout::Cross, 9, 12, 3, 9, -t, -t, 1},   // +Z stored upside down
      {prt::sh::EnvLayout::Cross, 9, 12, 3, 0, -t, 1, t},    // +Y
      {prt::sh::EnvLayout::Faces, 3, 18, 2, 14, -t, -t, 1},  // +Z seen from the centre
      {prt::sh::EnvLayout::Faces, 3, 18, 2, 0, 1, t, t},     // +X
  };
  for (Case c : cases) {
    if (c.layout == prt::sh::EnvLayout::LatLong && c.width == 10) {
      // Row 0 of 5 rows: θ = π/10 from +Y; column 7 of 10: φ = 2π(0.75 − 0.5) = π/2 → +Z side.
      c.x = 0.0;
      c.y = std::cos(kPi / 10);
      c.z = std::sin(kPi / 10);
    }
    INFO(prt::sh::layout_name(c.layout)
         << " " << c.width << "x" << c.height << " texel " << c.col << ", " << c.row);
    prt::sh::EnvMap env = make_map(c.layout, c.width, c.height, 0, 0, 0);
    set_texel(&env, c.col, c.row, 1000.0f, 500.0f, 250.0f);
    const double omega = prt::sh::texel_solid_angle(c.layout, c.width, c.height, c.col, c.row);
    REQUIRE(omega > 0);
    const std::vector<double> L = prt::sh::project(env, 2);
    REQUIRE(L.size() == 12u);
    CHECK(L[0] == Approx(omega * 1000.0 * kY00).epsilon(1e-12));
    const double length = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
    const double band1[3] = {L[3], L[1], L[2]};  // (L_1,1, L_1,−1, L_1,0) ∝ (x, y, z)
    const double expected[3] = {c.x / length, c.y / length, c.z / length};
    for (int i = 0; i < 3; ++i) {
      CHECK(band1[i] / (omega * 1000.0 * kY1) == Approx(expected[i]).margin(1e-12));
      // The green channel sees the same direction at half the power.
      CHECK(L[4 + (i == 0   ? 3
                   : i == 1 ? 1
                            : 2)] /
                (omega * 500.0 * kY1) ==
            Approx(expected[i]).margin(1e-12));
    }
  }
}

TEST_CASE("the separable lat-long projection equals the direct sum") {
  std::mt19937 random(12345);
  std::uniform_real_distribution<float> uniform(0.0f, 10.0f);
  struct Case {
    int width, height, order;
  };
  // Includes an odd, non-2:1 map and orders that exercise every band-change matrix up to 16.
  const Case cases[] = {{64, 32, 1}, {64, 32, 3},    {64, 32, 10},
                        {37, 13, 6}, {256, 128, 16}, {1024, 512, 3}};
  for (const Case& c : cases) {
    INFO(c.width << "x" << c.height << " order " << c.order);
    prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::LatLong, c.width, c.height, 0, 0, 0);
    for (float& value : env.rgb) value = uniform(random);
    // A bright sun-like spot too, so high bands are far from zero.
    set_texel(&env, c.width / 3, c.height / 4, 5000.0f, 4000.0f, 3000.0f);
    prt::sh::ProjectionStats fast_stats, direct_stats;
    const std::vector<double> fast = prt::sh::project(env, c.order, &fast_stats);
    const std::vector<double> direct = prt::sh::project_direct(env, c.order, &direct_stats);
    REQUIRE(fast.size() == direct.size());
    REQUIRE(fast.size() == 3u * c.order * c.order);
    // Same sum in a different order and through an orthogonal basis change: rounding only.
    const double scale = max_abs(direct);
    double worst = 0.0;
    for (std::size_t i = 0; i < fast.size(); ++i)
      worst = std::max(worst, std::abs(fast[i] - direct[i]));
    INFO("worst difference relative to the largest coefficient: " << worst / scale);
    CHECK(worst <= 1e-12 * scale);
    // Sums of up to 5e5 terms accumulated in different orders: rounding ~1e-16 per term.
    CHECK(fast_stats.solid_angle_sum == Approx(direct_stats.solid_angle_sum).epsilon(1e-10));
  }
}

TEST_CASE("projection recovers a band-limited function in every layout") {
  // f(d) = Σ c_k Y_k(d) over bands 0..3 with a sign pattern that would expose any mirrored axis
  // or swapped m; c_0 is large enough that f > 0, so no texel is skipped. The projection returns
  // c up to the texel-centre quadrature error, O(1/N²): measured worst |L_k − c_k| / c_0 is 2.1e-4
  // (lat-long 128x64), 1.6e-4 (angular 128²) and 3.6e-5 (cube faces, s = 32); tolerance 1e-3.
  // A mirrored axis or a swapped ±m would give errors of order |c_k| / c_0 ≳ 1e-2.
  const int order = 4;
  std::vector<double> c(16);
  for (int k = 0; k < 16; ++k) c[k] = ((k * 7) % 5 - 2) * 0.3 + (k % 2 ? 0.1 : -0.15);
  c[0] = 12.0;  // keeps f > 0 (asserted per texel below)
  struct Case {
    prt::sh::EnvLayout layout;
    int width, height;
  };
  const Case cases[] = {{prt::sh::EnvLayout::LatLong, 128, 64},
                        {prt::sh::EnvLayout::Angular, 128, 128},
                        {prt::sh::EnvLayout::Cross, 96, 128},
                        {prt::sh::EnvLayout::Faces, 32, 192}};
  for (const Case& cs : cases) {
    INFO(prt::sh::layout_name(cs.layout));
    prt::sh::EnvMap env = make_map(cs.layout, cs.width, cs.height, 0, 0, 0);
    double basis[16];
    for (int row = 0; row < cs.height; ++row) {
      for (int col = 0; col < cs.width; ++col) {
        double dir[3];
        if (!prt::sh::texel_direction(cs.layout, cs.width, cs.height, col, row, dir)) continue;
        prt::sh::evaluate(order, dir[0], dir[1], dir[2], basis);
        double f = 0.0;
        for (int k = 0; k < 16; ++k) f += c[k] * basis[k];
        REQUIRE(f > 0.0);
        set_texel(&env, col, row, static_cast<float>(f), static_cast<float>(2 * f), 0.0f);
      }
    }
    prt::sh::ProjectionStats stats;
    const std::vector<double> L = prt::sh::project(env, order, &stats);
    REQUIRE(L.size() == 48u);
    CHECK(stats.skipped_texels() == 0u);
    double worst = 0.0;
    for (int k = 0; k < 16; ++k) {
      worst = std::max(worst, std::abs(L[k] - c[k]));
      CHECK(L[k] == Approx(c[k]).margin(1e-3 * c[0]));
      CHECK(L[16 + k] == Approx(2 * c[k]).margin(2e-3 * c[0]));
      CHECK(std::abs(L[32 + k]) < 1e-12);
    }
    INFO("worst |L_k - c_k| / c_0 = " << worst / c[0]);
    CHECK(worst / c[0] < 1e-3);
  }
}

TEST_CASE("NaN and Inf texels are skipped, negative channels clamped to 0, and all counted") {
  // The texel policy of sh/env_check.h: the negative texel {1, -0.5, 1} is used as {1, 0, 1}
  // (per channel), not dropped whole; the reference map holds exactly that.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  struct Case {
    prt::sh::EnvLayout layout;
    int width, height;
  };
  const Case cases[] = {{prt::sh::EnvLayout::LatLong, 32, 16},
                        {prt::sh::EnvLayout::Angular, 24, 24},
                        {prt::sh::EnvLayout::Cross, 24, 32},
                        {prt::sh::EnvLayout::Faces, 8, 48}};
  for (const Case& c : cases) {
    INFO(prt::sh::layout_name(c.layout));
    prt::sh::EnvMap bad = make_map(c.layout, c.width, c.height, 1.0f, 2.0f, 3.0f);
    prt::sh::EnvMap clean = bad;
    // Pick texels on the sphere (the centre row of the map is on the sphere in every layout).
    const int row = c.height / 2;
    double omega_skipped = 0.0;
    const int cols[6] = {c.width / 2,     c.width / 2 + 1, c.width / 2 - 1,
                         c.width / 2 + 2, c.width / 2 - 2, c.width / 2 - 3};
    const float bad_values[6][3] = {{nan, 1, 1},  {1, 1, nan},   {inf, 1, 1},
                                    {1, -inf, 1}, {1, -0.5f, 1}, {nan, inf, -1}};
    for (int i = 0; i < 6; ++i) {
      double dir[3];
      REQUIRE(prt::sh::texel_direction(c.layout, c.width, c.height, cols[i], row, dir));
      set_texel(&bad, cols[i], row, bad_values[i][0], bad_values[i][1], bad_values[i][2]);
      if (i == 4) {  // {1, -0.5, 1}: clamped per channel, still used
        set_texel(&clean, cols[i], row, 1, 0, 1);
        continue;
      }
      set_texel(&clean, cols[i], row, 0, 0, 0);
      omega_skipped += prt::sh::texel_solid_angle(c.layout, c.width, c.height, cols[i], row);
    }
    for (int path = 0; path < 2; ++path) {
      prt::sh::ProjectionStats stats;
      const std::vector<double> L =
          path == 0 ? prt::sh::project(bad, 3, &stats) : prt::sh::project_direct(bad, 3, &stats);
      const std::vector<double> expected = prt::sh::project_direct(clean, 3);
      REQUIRE(L.size() == expected.size());
      CHECK(stats.nan_texels == 3u);  // NaN wins over Inf and negative in the same texel
      CHECK(stats.inf_texels == 2u);
      CHECK(stats.negative_texels == 1u);
      CHECK(stats.skipped_texels() == 5u);
      CHECK(stats.solid_angle_sum == Approx(4 * kPi - omega_skipped).epsilon(1e-12));
      for (std::size_t i = 0; i < L.size(); ++i) {
        CHECK(std::isfinite(L[i]));
        CHECK(L[i] == Approx(expected[i]).margin(1e-12 * max_abs(expected)));
      }
    }
  }
}

TEST_CASE("reconstruct evaluates an expansion with the closed-form basis functions") {
  // Unit coefficient vectors reproduce the closed-form basis functions of sh/basis.h.
  const double dir[3] = {0.3, -0.5, 0.8};
  const double n = std::sqrt(0.09 + 0.25 + 0.64);
  const double x = 0.3 / n, y = -0.5 / n, z = 0.8 / n;
  const double expected[9] = {0.282095,
                              0.488603 * y,
                              0.488603 * z,
                              0.488603 * x,
                              1.092548 * x * y,
                              1.092548 * y * z,
                              0.315392 * (3 * z * z - 1),
                              1.092548 * x * z,
                              0.546274 * (x * x - y * y)};
  for (int k = 0; k < 9; ++k) {
    // Two channels: channel 1 holds twice the unit vector.
    std::vector<double> coefficients(18, 0.0);
    coefficients[k] = 1.0;
    coefficients[9 + k] = 2.0;
    double out[2];
    prt::sh::reconstruct(coefficients.data(), 2, 3, dir, out);
    // The closed forms' constants have 6-7 significant digits.
    CHECK(out[0] == Approx(expected[k]).margin(2e-6));
    CHECK(out[1] == Approx(2 * expected[k]).margin(4e-6));
  }
  const double zero[3] = {0, 0, 0};
  std::vector<double> coefficients(9, 1.0);
  double out[1] = {42};
  prt::sh::reconstruct(coefficients.data(), 1, 3, zero, out);
  CHECK(out[0] == 0.0);
}

TEST_CASE("projection refuses invalid input") {
  const prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::Angular, 8, 8, 1, 1, 1);
  CHECK(prt::sh::project(env, 0).empty());
  CHECK(prt::sh::project(env, prt::sh::kMaxOrder + 1).empty());
  prt::sh::EnvMap wrong_aspect = make_map(prt::sh::EnvLayout::Angular, 8, 6, 1, 1, 1);
  CHECK(prt::sh::project(wrong_aspect, 3).empty());
  prt::sh::EnvMap short_data = env;
  short_data.rgb.pop_back();
  CHECK(prt::sh::project(short_data, 3).empty());
  prt::sh::EnvMap empty;
  CHECK(prt::sh::project(empty, 3).empty());
  CHECK_FALSE(prt::sh::project(env, 3).empty());
}

TEST_CASE("the separable lat-long projection equals the direct sum at high orders") {
  // Orders past the old 32 limit, on maps small enough for the direct sum. The sizes make the
  // separable path fold frequencies: W/2 < order (the sums for m > W/2 come from A_(W−m)) and
  // order > W (from A_(m−W)), with odd W and odd H (an unpaired equator row), down to 1×1.
  // The two paths add the same terms in different orders and the separable one runs three
  // recurrences (Legendre in l, Wigner d(π/2), exponentials by index): measured worst difference
  // ≤ 3.6e-15 of the largest coefficient; bound 1e-12.
  std::mt19937 random(777);
  std::uniform_real_distribution<float> uniform(0.0f, 10.0f);
  struct Case {
    int width, height, order;
  };
  const Case cases[] = {{37, 19, 8},     {96, 48, 33}, {45, 21, 33}, {30, 15, 40}, {160, 80, 64},
                        {200, 100, 128}, {1, 1, 5},    {2, 1, 6},    {3, 2, 7}};
  for (const Case& c : cases) {
    INFO(c.width << "x" << c.height << " order " << c.order);
    prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::LatLong, c.width, c.height, 0, 0, 0);
    for (float& value : env.rgb) value = uniform(random);
    set_texel(&env, c.width / 3, c.height / 4, 5000.0f, 4000.0f, 3000.0f);
    if (c.width > 1) set_texel(&env, 1, 0, 800.0f, 900.0f, 1000.0f);  // next to the pole
    const std::vector<double> fast = prt::sh::project(env, c.order);
    const std::vector<double> direct = prt::sh::project_direct(env, c.order);
    REQUIRE(fast.size() == direct.size());
    REQUIRE(fast.size() == 3u * c.order * c.order);
    const double scale = max_abs(direct);
    double worst = 0.0;
    for (std::size_t i = 0; i < fast.size(); ++i)
      worst = std::max(worst, std::abs(fast[i] - direct[i]));
    INFO("worst difference relative to the largest coefficient: " << worst / scale);
    CHECK(worst <= 1e-12 * scale);
  }
}

TEST_CASE("a single texel projects to omega v Y_k(direction) up to l = 1000") {
  // Closed form: one lit texel of value v gives L_k = ω v Y_k(d_texel) for every k (sh::evaluate
  // at the texel's centre direction, independent of the separable path's recurrences). |Y_lm| is
  // at most √((2l+1)/4π) ≈ 9 at l = 1000. Measured worst |L_k/(ω v) − Y_k|: 1.1e-13 at order
  // 201 and 4.3e-13 at order 1001 (texels at mid-latitude and next to the poles, where sin^m θ
  // underflows); bound 1e-11.
  struct Case {
    int width, height, col, row, order;
  };
  const Case cases[] = {
      {64, 32, 17, 9, 201}, {64, 32, 40, 0, 201}, {50, 25, 7, 12, 1001}, {64, 32, 45, 31, 1001}};
  for (const Case& c : cases) {
    INFO(c.width << "x" << c.height << " texel " << c.col << ", " << c.row << " order " << c.order);
    prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::LatLong, c.width, c.height, 0, 0, 0);
    set_texel(&env, c.col, c.row, 3.0f, 0.0f, 1.5f);
    const double omega = prt::sh::texel_solid_angle(env.layout, c.width, c.height, c.col, c.row);
    double dir[3];
    REQUIRE(prt::sh::texel_direction(env.layout, c.width, c.height, c.col, c.row, dir));
    const std::size_t n2 = static_cast<std::size_t>(c.order) * c.order;
    std::vector<double> y(n2);
    prt::sh::evaluate(c.order, dir[0], dir[1], dir[2], y.data());
    std::uint64_t last_done = 0, total = 0;
    int calls = 0;
    const std::vector<double> L =
        prt::sh::project(env, c.order, nullptr, [&](std::uint64_t done, std::uint64_t all) {
          CHECK(done >= last_done);
          CHECK(done <= all);
          last_done = done;
          total = all;
          ++calls;
        });
    REQUIRE(L.size() == 3 * n2);
    CHECK(calls > 2);
    CHECK(last_done == total);  // the last report is complete
    double worst = 0.0, green = 0.0;
    for (std::size_t k = 0; k < n2; ++k) {
      worst = std::max(worst, std::abs(L[k] / (omega * 3.0) - y[k]));
      worst = std::max(worst, std::abs(L[2 * n2 + k] / (omega * 1.5) - y[k]));
      green = std::max(green, std::abs(L[n2 + k]));
    }
    CHECK(green == 0.0);  // the unlit channel
    INFO("worst |L_k / (omega v) - Y_k| = " << worst);
    CHECK(worst < 1e-11);
  }
}

TEST_CASE("a constant map projects to sqrt(4 pi) c at order 1001") {
  // Band 0 is the sum of the exact solid angles (rounding); every coefficient must stay finite
  // through 1001 bands of recurrences.
  const prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::LatLong, 80, 40, 0.5f, 2.0f, 7.0f);
  const int order = 1001;
  const std::size_t n2 = static_cast<std::size_t>(order) * order;
  prt::sh::ProjectionStats stats;
  const std::vector<double> L = prt::sh::project(env, order, &stats);
  REQUIRE(L.size() == 3 * n2);
  CHECK(L[0] == Approx(std::sqrt(4 * kPi) * 0.5).epsilon(1e-12));
  CHECK(L[n2] == Approx(std::sqrt(4 * kPi) * 2.0).epsilon(1e-12));
  CHECK(L[2 * n2] == Approx(std::sqrt(4 * kPi) * 7.0).epsilon(1e-12));
  CHECK(stats.solid_angle_sum == Approx(4 * kPi).epsilon(1e-12));
  bool finite = true;
  for (double v : L) finite = finite && std::isfinite(v);
  CHECK(finite);
}

TEST_CASE("the direct sum reports progress in texels on the sphere") {
  // An angular map's rows hold different numbers of texels on the disc: progress counts them,
  // so it is proportional to the work; it ends at the number of texels with a solid angle.
  const prt::sh::EnvMap env = make_map(prt::sh::EnvLayout::Angular, 24, 24, 1, 1, 1);
  std::uint64_t on_sphere = 0;
  for (int row = 0; row < 24; ++row)
    for (int col = 0; col < 24; ++col)
      on_sphere += prt::sh::texel_solid_angle(env.layout, 24, 24, col, row) > 0.0;
  std::vector<std::uint64_t> seen;
  std::uint64_t total = 0;
  const std::vector<double> L =
      prt::sh::project(env, 4, nullptr, [&](std::uint64_t done, std::uint64_t all) {
        seen.push_back(done);
        total = all;
      });
  REQUIRE(L.size() == 48u);
  REQUIRE(seen.size() == 24u);  // once per row
  CHECK(total == on_sphere);
  CHECK(seen.back() == on_sphere);
  for (std::size_t i = 1; i < seen.size(); ++i) CHECK(seen[i] > seen[i - 1]);
  CHECK(seen.front() < seen[12] - seen[11]);  // the top row holds fewer texels than the middle
}
