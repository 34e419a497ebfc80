// Tests of the cube-map geometry and the power-preserving resampling (prt/haar/cube_map.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/haar/cube_map.h"
#include "sh/constants.h"
#include "sh/env_map.h"

namespace {

using prt::sh::kPi;

// The lat-long convention (README.md, "Conventions"), written out independently of sh/: θ from +Y,
// φ = atan2(z, x).
void latlong_direction(int w, int h, int col, int row, double dir[3]) {
  const double theta = kPi * (row + 0.5) / h;
  const double phi = 2.0 * kPi * ((col + 0.5) / w - 0.5);
  dir[0] = std::sin(theta) * std::cos(phi);
  dir[1] = std::cos(theta);
  dir[2] = std::sin(theta) * std::sin(phi);
}

prt::sh::EnvMap random_latlong(int w, int h, uint32_t seed) {
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = w;
  env.height = h;
  env.rgb.resize(static_cast<size_t>(w) * h * 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(0.0f, 5.0f);
  for (float& v : env.rgb) v = dist(rng);
  return env;
}

void check_power_preserved(const prt::CubeResampleStats& st) {
  for (int c = 0; c < 3; ++c) {
    // Power moves through double accumulators; the only loss is the float rounding of each
    // cube texel (relative 2⁻²⁴), so 1e-5 relative (the brief's figure) is generous.
    CHECK(st.cube_power[c] == Approx(st.source_power[c]).epsilon(1e-5));
  }
}

}  // namespace

TEST_CASE("Cube texel solid angles are exact and sum to 4π", "[haar][cube]") {
  for (int n : {8, 32, 128}) {
    const std::vector<double> omega = prt::cube_face_solid_angles(n);
    double sum = 0.0;
    for (double w : omega) sum += w;
    // Telescoping atan2 sums: exact to double rounding.
    CHECK(6.0 * sum == Approx(4.0 * kPi).epsilon(1e-12));
  }
  // Independent check: a texel at N = 8 against midpoint quadrature of dω = da db/(1+a²+b²)^1.5.
  const int n = 8, col = 1, row = 6;
  double quad = 0.0;
  const int m = 400;
  const double step = 2.0 / n;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double a = -1.0 + col * step + (i + 0.5) * step / m;
      const double b = -1.0 + row * step + (j + 0.5) * step / m;
      quad += std::pow(1.0 + a * a + b * b, -1.5) * (step / m) * (step / m);
    }
  // Midpoint rule error ~ h² with h = step/400: far below 1e-7 relative.
  CHECK(prt::cube_texel_solid_angle(n, col, row) == Approx(quad).epsilon(1e-7));
}

TEST_CASE("Cube texel directions and the inverse mapping agree with the face table",
          "[haar][cube]") {
  // Face centres: +X, −X, +Y, −Y, +Z, −Z.
  const double centres[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    double d[3];
    prt::cube_face_point_direction(f, 0.0, 0.0, d);
    for (int k = 0; k < 3; ++k) CHECK(d[k] == Approx(centres[f][k]).margin(1e-15));
  }
  // Face-local a (right) and b (down) per the table: +X (1, −b, a), +Z (−a, −b, 1), +Y (a, 1, −b).
  double d[3];
  prt::cube_face_point_direction(0, 1.0, 0.0, d);  // +X, right edge → +Z
  CHECK(d[2] > 0.7);
  prt::cube_face_point_direction(4, 1.0, 0.0, d);  // +Z, right edge → −X
  CHECK(d[0] < -0.7);
  prt::cube_face_point_direction(2, 0.0, 1.0, d);  // +Y, bottom edge → −Z
  CHECK(d[2] < -0.7);
  prt::cube_face_point_direction(3, 0.0, 1.0, d);  // −Y, bottom edge → +Z
  CHECK(d[2] > 0.7);
  prt::cube_face_point_direction(1, 0.0, -1.0, d);  // −X, top edge → +Y
  CHECK(d[1] > 0.7);
  const int n = 16;
  for (int f = 0; f < 6; ++f)
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        prt::cube_texel_direction(n, f, c, r, d);
        int face = -1, col = -1, row = -1;
        REQUIRE(prt::direction_to_cube_texel(n, d, &face, &col, &row));
        REQUIRE(face == f);
        REQUIRE(col == c);
        REQUIRE(row == r);
      }
  const double zero[3] = {0, 0, 0};
  const double nan[3] = {std::numeric_limits<double>::quiet_NaN(), 0, 1};
  int face, col, row;
  CHECK_FALSE(prt::direction_to_cube_texel(n, zero, &face, &col, &row));
  CHECK_FALSE(prt::direction_to_cube_texel(n, nan, &face, &col, &row));
}

TEST_CASE("Resampling lat-long to cube preserves power at any resolution", "[haar][cube]") {
  for (int w : {16, 64, 256}) {
    const prt::sh::EnvMap env = random_latlong(w, w / 2, 11u + w);
    for (int n : {8, 32, 128}) {
      prt::CubeResampleStats st;
      const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, n, &st);
      REQUIRE(cube.ok());
      INFO("lat-long " << w << "x" << w / 2 << " -> cube " << n
                       << ", S² = " << st.subsamples_per_texel);
      CHECK(st.skipped_texels == 0);
      check_power_preserved(st);
      // An independent total: Σ L·Ω with the exact lat-long row weights (cos θ0 − cos θ1)·2π/W.
      double source = 0.0;
      for (int r = 0; r < w / 2; ++r) {
        const double band =
            (std::cos(kPi * r / (w / 2)) - std::cos(kPi * (r + 1) / (w / 2))) * 2 * kPi / w;
        for (int c = 0; c < w; ++c) source += env.rgb[3 * (static_cast<size_t>(r) * w + c)] * band;
      }
      CHECK(st.cube_power[0] == Approx(source).epsilon(1e-5));
    }
  }
}

TEST_CASE("Resampling angular and cross maps preserves power", "[haar][cube]") {
  for (prt::sh::EnvLayout layout : {prt::sh::EnvLayout::Angular, prt::sh::EnvLayout::Cross}) {
    prt::sh::EnvMap env;
    env.layout = layout;
    env.width = layout == prt::sh::EnvLayout::Angular ? 64 : 48;
    env.height = 64;
    env.rgb.resize(static_cast<size_t>(env.width) * env.height * 3);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> dist(0.0f, 2.0f);
    for (float& v : env.rgb) v = dist(rng);
    prt::CubeResampleStats st;
    const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, 16, &st);
    REQUIRE(cube.ok());
    check_power_preserved(st);
    // And the source power is Σ L·Ω with sh's exact texel solid angles (which sum to 4π).
    const std::vector<double> omega = prt::sh::texel_solid_angles(layout, env.width, env.height);
    double source = 0.0;
    for (size_t t = 0; t < omega.size(); ++t) source += env.rgb[3 * t + 1] * omega[t];
    CHECK(st.cube_power[1] == Approx(source).epsilon(1e-5));
  }
}

TEST_CASE("A faces-layout map resamples to the identical cube", "[haar][cube]") {
  // sh's Faces layout uses the same face table; every sub-texel of a source texel must land in
  // the cube texel with the same (face, col, row), so the cube equals the map.
  const int n = 16;
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::Faces;
  env.width = n;
  env.height = 6 * n;
  env.rgb.resize(static_cast<size_t>(n) * 6 * n * 3);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> dist(0.0f, 1.0f);
  for (float& v : env.rgb) v = dist(rng);
  const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, n);
  REQUIRE(cube.ok());
  for (size_t i = 0; i < env.rgb.size(); ++i) {
    // Power (double) divided by the same exact solid angle: only rounding differs.
    REQUIRE(cube->rgb[i] == Approx(env.rgb[i]).epsilon(1e-5));
  }
}

TEST_CASE("A single bright lat-long texel lands on the cube texel in its direction",
          "[haar][cube]") {
  const int w = 128, h = 64, n = 32;
  struct Case {
    int col, row, face;  // expected face from the convention's direction and the face table
  };
  // Centre column = +X; u = 0.75 → +Z; u = 0.25 → −Z; row 0 → +Y; last row → −Y; u = 0 → −X.
  for (const Case& k : {Case{64, 31, 0}, Case{96, 33, 4}, Case{32, 30, 5}, Case{17, 0, 2},
                        Case{80, 63, 3}, Case{1, 32, 1}, Case{90, 20, 4}}) {
    prt::sh::EnvMap env;
    env.layout = prt::sh::EnvLayout::LatLong;
    env.width = w;
    env.height = h;
    env.rgb.assign(static_cast<size_t>(w) * h * 3, 0.01f);
    float* bright = &env.rgb[3 * (static_cast<size_t>(k.row) * w + k.col)];
    bright[0] = bright[1] = bright[2] = 1e5f;
    prt::CubeResampleStats st;
    const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, n, &st);
    REQUIRE(cube.ok());
    check_power_preserved(st);
    // The brightest cube texel.
    size_t best = 0;
    for (size_t t = 0; t < static_cast<size_t>(cube->texel_count()); ++t)
      if (cube->rgb[3 * t] > cube->rgb[3 * best]) best = t;
    const int face = static_cast<int>(best / (n * n));
    const int row = static_cast<int>(best % (n * n)) / n, col = static_cast<int>(best % n);
    double expected[3], got[3];
    latlong_direction(w, h, k.col, k.row, expected);
    prt::cube_texel_direction(n, face, col, row, got);
    const double cosine = expected[0] * got[0] + expected[1] * got[1] + expected[2] * got[2];
    INFO("source texel (" << k.col << ", " << k.row << ") -> face " << face << " (" << col << ", "
                          << row << ")");
    CHECK(face == k.face);
    // The brightest cube texel holds most of the source texel's sub-samples, so its centre is
    // within half a cube-texel diagonal (≤ √2/N = 0.044 rad) plus half a source-texel diagonal
    // (≤ 0.035 rad at the equator) of the source direction: 0.08 rad; 0.12 leaves margin, and a
    // wrong face or a mirrored axis is off by far more.
    CHECK(std::acos(std::min(1.0, cosine)) < 0.12);
  }
}

TEST_CASE("Resampling skips and counts NaN, Inf and negative texels", "[haar][cube]") {
  prt::sh::EnvMap env = random_latlong(32, 16, 5);
  env.rgb[0] = std::numeric_limits<float>::quiet_NaN();
  env.rgb[3 * 40 + 1] = std::numeric_limits<float>::infinity();
  env.rgb[3 * 77 + 2] = -1.0f;
  prt::CubeResampleStats st;
  const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, 8, &st);
  REQUIRE(cube.ok());
  CHECK(st.skipped_texels == 3);
  for (float v : cube->rgb) REQUIRE(std::isfinite(v));
  check_power_preserved(st);
  CHECK_FALSE(prt::resample_to_cube(env, 12).ok());   // not a power of two
  CHECK_FALSE(prt::resample_to_cube(env, 256).ok());  // too large
  env.rgb.pop_back();
  CHECK_FALSE(prt::resample_to_cube(env, 8).ok());  // inconsistent rgb size
}

TEST_CASE("Upsampling a coarse constant map leaves no holes", "[haar][cube]") {
  // A 16×8 lat-long map of constant radiance 1 into a 64² cube (each source texel covers
  // ~100 cube texels): with ~8 sub-samples across each cube texel, every cube texel receives
  // 1 ± (1/8 per axis ⇒ ≲ 25%) of its share; without the adaptive S it would hold 0 or ≫ 1.
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = 16;
  env.height = 8;
  env.rgb.assign(16 * 8 * 3, 1.0f);
  prt::CubeResampleStats st;
  const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, 64, &st);
  REQUIRE(cube.ok());
  check_power_preserved(st);
  CHECK(st.cube_power[0] == Approx(4.0 * kPi).epsilon(1e-5));
  float lo = 1e30f, hi = 0.0f;
  for (float v : cube->rgb) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  INFO("cube texel range [" << lo << ", " << hi << "], S² = " << st.subsamples_per_texel);
  CHECK(lo > 0.7f);
  CHECK(hi < 1.3f);
}
