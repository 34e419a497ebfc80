// Tests of prt/lighting/sh_lighting.h: projection of a constant map, rotation semantics, windows,
// errors.
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "lighting_fixtures.h"
#include "prt/lighting/sh_lighting.h"
#include "sh/constants.h"

using prt::ShLighting;
using prt::sh::kPi;

namespace {

// Rotation by angle a about the unit axis u (Rodrigues), row-major.
std::array<double, 9> axis_angle(double ux, double uy, double uz, double a) {
  const double c = std::cos(a), s = std::sin(a), t = 1 - c;
  return {t * ux * ux + c,      t * ux * uy - s * uz, t * ux * uz + s * uy,
          t * ux * uy + s * uz, t * uy * uy + c,      t * uy * uz - s * ux,
          t * ux * uz - s * uy, t * uy * uz + s * ux, t * uz * uz + c};
}

std::array<double, 9> transpose(const std::array<double, 9>& m) {
  return {m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]};
}

using prt::test::random_lighting;

}  // namespace

TEST_CASE("a constant map projects to sqrt(4 pi) c in k = 0", "[lighting]") {
  const int w = 256, h = 128, order = 5;
  const float rgb[3] = {1.0f, 2.0f, 0.25f};
  std::vector<float> pixels(3 * w * h);
  for (int i = 0; i < w * h; ++i) {
    for (int c = 0; c < 3; ++c) pixels[3 * i + c] = rgb[c];
  }
  const auto light =
      ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, w, h, pixels.data(), order);
  REQUIRE(light.ok());
  REQUIRE(light->order() == order);
  for (int c = 0; c < 3; ++c) {
    // Exact texel solid angles: only rounding error remains (1e-9 relative in double).
    CHECK(light->coefficients_double(c)[0] == Approx(std::sqrt(4 * kPi) * rgb[c]).epsilon(1e-9));
    CHECK(light->coefficients(c)[0] == Approx(std::sqrt(4 * kPi) * rgb[c]).epsilon(1e-6));
    // Higher bands vanish only to quadrature accuracy: prt::sh::project samples Y at texel centres,
    // which leaks O(1/H²) into the even bands (measured 2.0e-4·c at H = 128 for k = 24; it
    // falls 4× per doubling of H). 5e-4·c fails for any real error in the projection.
    for (int k = 1; k < order * order; ++k) {
      CHECK(std::abs(light->coefficients_double(c)[k]) < 5e-4 * rgb[c]);
    }
  }
  // Errors: a size that does not fit the layout, a NaN texel, a bad order.
  const auto bad_size =
      ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, 63, 32, pixels.data(), 3);
  REQUIRE_FALSE(bad_size.ok());
  CHECK(bad_size.status().message().rfind("lighting: ", 0) == 0);
  pixels[100] = NAN;
  CHECK_FALSE(ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, w, h, pixels.data(), 3).ok());
  CHECK_FALSE(ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, w, h, pixels.data(), 0).ok());
}

TEST_CASE("rotating by M then by its inverse returns the input", "[lighting]") {
  const ShLighting original = random_lighting(5, 3);
  ShLighting light = original;
  const auto m = axis_angle(0.48, 0.6, 0.64, 1.1);  // unit axis
  REQUIRE(light.rotate(m).ok());
  double changed = 0;
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 25; ++k) {
      changed = std::max(
          changed, std::abs(light.coefficients_double(c)[k] - original.coefficients_double(c)[k]));
    }
  }
  CHECK(changed > 0.1);  // the rotation did something
  REQUIRE(light.rotate(transpose(m)).ok());
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 25; ++k) {
      // Ivanic–Ruedenberg in double at order 5: errors ~1e-15; 1e-12 leaves margin.
      REQUIRE(light.coefficients_double(c)[k] ==
              Approx(original.coefficients_double(c)[k]).margin(1e-12));
    }
  }
}

TEST_CASE("rotation moves a band-1 lobe from d to M d", "[lighting]") {
  // Band 1 holds (y, z, x) of a linear lobe: L1,-1 ∝ y, L1,0 ∝ z, L1,1 ∝ x.
  const double d[3] = {0.0, 0.0, 1.0};  // +z
  std::vector<double> c(3 * 4, 0.0);
  for (int ch = 0; ch < 3; ++ch) {
    c[ch * 4 + 1] = d[1];
    c[ch * 4 + 2] = d[2];
    c[ch * 4 + 3] = d[0];
  }
  auto light = ShLighting::from_coefficients(2, c.data());
  REQUIRE(light.ok());
  const auto m = axis_angle(1.0, 0.0, 0.0, kPi / 2);  // +z -> −y about +x
  REQUIRE(light->rotate(m).ok());
  const double md[3] = {m[2], m[5], m[8]};  // M·(0, 0, 1)
  for (int ch = 0; ch < 3; ++ch) {
    CHECK(light->coefficients_double(ch)[1] == Approx(md[1]).margin(1e-12));
    CHECK(light->coefficients_double(ch)[2] == Approx(md[2]).margin(1e-12));
    CHECK(light->coefficients_double(ch)[3] == Approx(md[0]).margin(1e-12));
  }
  CHECK(md[1] == Approx(-1.0));
  // A reflection or a non-orthonormal matrix is refused and leaves the lighting as it was.
  const ShLighting before = *light;
  CHECK_FALSE(light->rotate({-1, 0, 0, 0, 1, 0, 0, 0, 1}).ok());
  CHECK_FALSE(light->rotate({2, 0, 0, 0, 1, 0, 0, 0, 1}).ok());
  CHECK_FALSE(light->rotate({NAN, 0, 0, 0, 1, 0, 0, 0, 1}).ok());
  for (int k = 0; k < 12; ++k) {
    CHECK(light->coefficients_double(k / 4)[k % 4] == before.coefficients_double(k / 4)[k % 4]);
  }
}

TEST_CASE("a Laplacian window scales band l by 1/(1 + lambda l^2 (l+1)^2)", "[lighting]") {
  const ShLighting original = random_lighting(4, 6);
  ShLighting light = original;
  const double lambda = 0.01;
  REQUIRE(light.apply_window(prt::sh::Window::Laplacian, lambda).ok());
  for (int c = 0; c < 3; ++c) {
    for (int l = 0; l < 4; ++l) {
      const double h = 1.0 / (1.0 + lambda * l * l * (l + 1) * (l + 1));  // Sloan 2008
      for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
        REQUIRE(light.coefficients_double(c)[k] ==
                Approx(h * original.coefficients_double(c)[k]).epsilon(1e-12));
        REQUIRE(light.coefficients(c)[k] == static_cast<float>(light.coefficients_double(c)[k]));
      }
    }
  }
  CHECK_FALSE(light.apply_window(prt::sh::Window::Hanning, NAN).ok());
  // None leaves everything as it was.
  ShLighting same = original;
  REQUIRE(same.apply_window(prt::sh::Window::None, 0).ok());
  for (int k = 0; k < 16; ++k)
    CHECK(same.coefficients_double(1)[k] == original.coefficients_double(1)[k]);
}

TEST_CASE("lighting from coefficients validates its input", "[lighting]") {
  const float zeros[3 * 4] = {};
  CHECK(ShLighting::from_coefficients(2, zeros).ok());
  CHECK_FALSE(ShLighting::from_coefficients(0, zeros).ok());
  CHECK_FALSE(ShLighting::from_coefficients(65, zeros).ok());
  CHECK_FALSE(ShLighting::from_coefficients(2, static_cast<const float*>(nullptr)).ok());
  float bad[3 * 4] = {};
  bad[7] = INFINITY;
  CHECK_FALSE(ShLighting::from_coefficients(2, bad).ok());
  const ShLighting black;
  CHECK(black.order() == 1);
  CHECK(black.coefficients(2)[0] == 0.0f);
}
