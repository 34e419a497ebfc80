// Tests of the 2D non-standard Haar transform (prt/haar/transform.h).
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/haar/transform.h"

namespace {

std::vector<float> random_face(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(-10.0f, 10.0f);
  std::vector<float> x(static_cast<size_t>(n) * n);
  for (float& v : x) v = dist(rng);
  return x;
}

}  // namespace

TEST_CASE("Haar round trip is lossless to float precision, N = 8..128", "[haar][transform]") {
  for (int n = 8; n <= 128; n *= 2) {
    const std::vector<float> x = random_face(n, 1234u + n);
    std::vector<float> c = x;
    prt::forward_haar_2d(c.data(), n);
    std::vector<float> y = c;
    prt::inverse_haar_2d(y.data(), n);
    double max_abs = 0.0, max_err = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      max_abs = std::max(max_abs, static_cast<double>(std::fabs(x[i])));
      max_err = std::max(max_err, static_cast<double>(std::fabs(x[i] - y[i])));
    }
    // The transform runs in double; only the float coefficients (relative 2⁻²⁴ each) and the
    // float output are rounded. Orthonormality turns coefficient errors into a texel error of
    // at most 2⁻²⁴·‖x‖₂ ≤ 2⁻²⁴·N·max|x|, so N float ulps of max|x| (2⁻²³·max|x| each) bound it.
    const double tolerance = n * std::ldexp(max_abs, -23);
    INFO("N = " << n << ", max error " << max_err << ", tolerance " << tolerance);
    CHECK(max_err <= tolerance);
    // The coefficients must actually differ from the input (the transform did something).
    CHECK(c != x);
  }
}

TEST_CASE("Haar transform is orthonormal: energy preserved", "[haar][transform]") {
  for (int n = 8; n <= 128; n *= 2) {
    const std::vector<float> x = random_face(n, 99u + n);
    std::vector<float> c = x;
    prt::forward_haar_2d(c.data(), n);
    double ex = 0.0, ec = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      ex += static_cast<double>(x[i]) * x[i];
      ec += static_cast<double>(c[i]) * c[i];
    }
    // Each coefficient carries a relative float rounding ≤ 2⁻²⁴, so Σc² is within ~2⁻²³
    // relative of Σx²; 1e-6 leaves margin and still catches any missing 1/2 factor.
    INFO("N = " << n);
    CHECK(std::fabs(ec - ex) <= 1e-6 * ex);
  }
}

TEST_CASE("Fast Haar transform matches projection onto the slow basis functions",
          "[haar][transform]") {
  for (int n : {8, 16}) {
    const std::vector<float> x = random_face(n, 7u + n);
    std::vector<float> c = x;
    prt::forward_haar_2d(c.data(), n);
    double norm = 0.0;
    for (float v : x) norm += static_cast<double>(v) * v;
    norm = std::sqrt(norm);
    for (int q = 0; q < n * n; ++q) {
      double reference = 0.0;
      for (int r = 0; r < n; ++r)
        for (int col = 0; col < n; ++col)
          reference += prt::evaluate_haar_basis(n, q, r, col) * x[static_cast<size_t>(r) * n + col];
      // |c_q| ≤ ‖x‖₂; float rounding of c_q is ≤ 2⁻²⁴·‖x‖₂; 4× for margin.
      INFO("N = " << n << ", q = " << q);
      REQUIRE(std::fabs(c[q] - reference) <= 4.0 * std::ldexp(norm, -24));
    }
  }
}

TEST_CASE("Slow Haar basis functions are orthonormal and laid out coarse to fine",
          "[haar][transform]") {
  const int n = 8;
  for (int p = 0; p < n * n; ++p) {
    for (int q = p; q < n * n; ++q) {
      double dot = 0.0;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          dot += prt::evaluate_haar_basis(n, p, r, c) * prt::evaluate_haar_basis(n, q, r, c);
      // Values are ±1/s with s a power of two: the sums are exact in double.
      REQUIRE(dot == Approx(p == q ? 1.0 : 0.0).margin(1e-12));
    }
  }
  const prt::HaarCoefficientInfo scaling = prt::describe_haar_coefficient(n, 0);
  CHECK(scaling.band == -1);
  CHECK(scaling.support_size == n);
  // q = 1..3: level 0, the whole face; q = 4..15: level 1, 4×4 blocks; q = 63: finest diagonal.
  CHECK(prt::describe_haar_coefficient(n, 2).band == 1);
  CHECK(prt::describe_haar_coefficient(n, 2).support_size == 8);
  const prt::HaarCoefficientInfo q7 = prt::describe_haar_coefficient(n, 7);  // band 0, (1, 1)
  CHECK(q7.level == 1);
  CHECK(q7.band == 0);
  CHECK(q7.support_row == 4);
  CHECK(q7.support_col == 4);
  const prt::HaarCoefficientInfo last = prt::describe_haar_coefficient(n, 63);
  CHECK(last.level == 2);
  CHECK(last.band == 2);
  CHECK(last.support_size == 2);
  CHECK(last.support_row == 6);
  CHECK(last.support_col == 6);
}

TEST_CASE("Cube transform round trips all faces and channels", "[haar][transform]") {
  const int n = 16;
  prt::CubeMap cube = prt::make_black_cube_map(n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> dist(0.0f, 100.0f);
  for (float& v : cube.rgb) v = dist(rng);
  const prt::Result<prt::WaveletCube> w = prt::transform_cube(cube);
  REQUIRE(w.ok());
  // The scaling coefficient of face f, channel c is (Σ face texels)/N.
  for (int face = 0; face < 6; ++face) {
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (int t = 0; t < n * n; ++t) sum += cube.rgb[3 * (face * n * n + t) + c];
      CHECK(w->rgb[3 * (face * n * n) + c] == Approx(sum / n).epsilon(1e-6));
    }
  }
  const prt::Result<prt::CubeMap> back = prt::inverse_transform_cube(*w);
  REQUIRE(back.ok());
  for (size_t i = 0; i < cube.rgb.size(); ++i) {
    // N = 16 float ulps of max|x| = 100 (see the round-trip test).
    REQUIRE(std::fabs(back->rgb[i] - cube.rgb[i]) <= 16 * std::ldexp(100.0, -23));
  }
  prt::CubeMap bad = cube;
  bad.size = 12;
  CHECK_FALSE(prt::transform_cube(bad).ok());
}
