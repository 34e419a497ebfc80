// tests/sh/test_zonal.cpp — clamped cosine, spherical caps, zonal rotation.
#include <array>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"
#include "sh_core_quadrature.h"

namespace {

using prt::sh::kPi;

// Legendre polynomial P_l(t) by Bonnet's recurrence (test-side, independent of the library).
double legendre(int l, double t) {
  double p0 = 1.0, p1 = t;
  if (l == 0) return p0;
  for (int k = 1; k < l; ++k) {
    const double p2 = ((2 * k + 1) * t * p1 - k * p0) / (k + 1);
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// Closed form of the indicator of the cap of half-angle α about +z:
// c_l = 2π·√((2l+1)/4π)·(P_{l−1}(cos α) − P_{l+1}(cos α))/(2l+1), c_0 = √π·(1 − cos α).
double cap_coefficient(int l, double alpha) {
  const double t = std::cos(alpha);
  if (l == 0) return std::sqrt(kPi) * (1.0 - t);
  return 2.0 * kPi * std::sqrt((2 * l + 1) / (4 * kPi)) *
         (legendre(l - 1, t) - legendre(l + 1, t)) / (2 * l + 1);
}

// Projects the cap indicator (about `axis`) with prt::sh::evaluate by an exact quadrature over the
// cap (Gauss–Legendre in cos of the angle to the axis on [cos α, 1] × uniform φ): the integrand
// Y_lm restricted to the cap is a polynomial, so the rule is exact for nt ≥ order, nphi > order.
std::vector<double> project_cap(int order, double alpha, std::array<double, 3> axis) {
  const sh_test::Quadrature q =
      sh_test::make_zone_quadrature(order + 2, 2 * order + 2, std::cos(alpha), 1.0, axis);
  std::vector<double> c(order * order, 0.0), y(order * order);
  for (std::size_t p = 0; p < q.weights.size(); ++p) {
    prt::sh::evaluate(order, q.directions[p][0], q.directions[p][1], q.directions[p][2], y.data());
    for (int k = 0; k < order * order; ++k) c[k] += q.weights[p] * y[k];
  }
  return c;
}

}  // namespace

TEST_CASE("clamped-cosine factors and zonal coefficients match the closed forms", "[sh][zonal]") {
  // Exact rational multiples of π (Ramamoorthi & Hanrahan 2001); 1e-15 relative is a couple of
  // ulps.
  const double a[11] = {kPi,      2 * kPi / 3, kPi / 4,    0, -kPi / 24,     0,
                        kPi / 64, 0,           -kPi / 128, 0, 7 * kPi / 1536};
  // The zonal coefficients to 7 digits: within 5e-8 (half a unit of the last digit).
  const double z[11] = {0.8862269, 1.0233267, 0.4954159,  0, -0.1107784, 0,
                        0.0499271, 0,         -0.0285469, 0, 0.0185081};
  for (int l = 0; l <= 10; ++l) {
    INFO("l=" << l);
    REQUIRE(prt::sh::clamped_cosine_band_factor(l) == Approx(a[l]).epsilon(1e-15).margin(1e-300));
    REQUIRE(prt::sh::clamped_cosine_zonal_coefficient(l) == Approx(z[l]).margin(5e-8));
  }
  REQUIRE(prt::sh::clamped_cosine_band_factor(-1) == 0.0);
}

TEST_CASE("clamped-cosine factors equal a numerical projection, to high l", "[sh][zonal]") {
  // z_l = 2π ∫_0^1 t·P̄_l(t) dt with P̄_l = √((2l+1)/4π)·P_l; Gauss–Legendre with 80 nodes on
  // [0, 1] integrates t·P_l exactly for l ≤ 158, so agreement is to roundoff: 1e-13 absolute.
  std::vector<double> nodes, weights;
  sh_test::gauss_legendre(80, &nodes, &weights);
  for (int l = 0; l <= 150; ++l) {
    double integral = 0.0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const double t = 0.5 + 0.5 * nodes[i];
      integral += 0.5 * weights[i] * t * legendre(l, t);
    }
    const double expected = 2.0 * kPi * std::sqrt((2 * l + 1) / (4 * kPi)) * integral;
    INFO("l=" << l);
    REQUIRE(prt::sh::clamped_cosine_zonal_coefficient(l) == Approx(expected).margin(1e-13));
  }
  // Far beyond: |A_l| ~ l^(−5/2) stays finite and non-zero for even l (no factorial overflow).
  const double a4000 = prt::sh::clamped_cosine_band_factor(4000);
  REQUIRE(std::isfinite(a4000));
  REQUIRE(a4000 != 0.0);
  // Asymptotically A_l ≈ 2π(−1)^(l/2−1)/l² · √(2/(πl)); within 0.1 % at l = 4000.
  REQUIRE(a4000 ==
          Approx(-2 * kPi / (4000.0 * 4000.0) * std::sqrt(2 / (kPi * 4000))).epsilon(1e-3));
}

TEST_CASE("spherical-cap coefficients by quadrature match the closed form", "[sh][zonal]") {
  const int order = 12;
  // α = π/6: the 7-digit values (±5e-8) and the closed form c_l for all l < 12 (1e-13).
  const std::vector<double> c = project_cap(order, kPi / 6, {0, 0, 1});
  const double reference_cap[5] = {0.2374638, 0.3837475, 0.4290428, 0.4030015, 0.3237870};
  for (int l = 0; l < order; ++l) {
    INFO("l=" << l);
    if (l < 5) REQUIRE(c[l * (l + 1)] == Approx(reference_cap[l]).margin(5e-8));
    REQUIRE(c[l * (l + 1)] == Approx(cap_coefficient(l, kPi / 6)).margin(1e-13));
    for (int m = 1; m <= l; ++m) {  // zonal about +z: every m ≠ 0 term vanishes
      REQUIRE(c[l * (l + 1) + m] == Approx(0.0).margin(1e-13));
      REQUIRE(c[l * (l + 1) - m] == Approx(0.0).margin(1e-13));
    }
  }
  // The hemisphere.
  const std::vector<double> h = project_cap(order, kPi / 2, {0, 0, 1});
  const double reference_hemisphere[4] = {std::sqrt(kPi), 1.5349901, 0.0, -0.5861840};
  for (int l = 0; l < 4; ++l)
    REQUIRE(h[l * (l + 1)] == Approx(reference_hemisphere[l]).margin(5e-8));
  for (int l = 0; l < order; ++l) {
    REQUIRE(h[l * (l + 1)] == Approx(cap_coefficient(l, kPi / 2)).margin(1e-13));
  }
}

TEST_CASE("rotate_zonal equals projecting the rotated zonal function", "[sh][zonal]") {
  // The cap of half-angle 0.4 about an oblique axis: rotate_zonal of the closed-form zonal
  // coefficients vs an exact quadrature over the rotated cap (1e-13: roundoff of the sums).
  const int order = 10;
  const double alpha = 0.4;
  const double n = std::sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.9 * 0.9);
  const std::array<double, 3> axis = {-0.3 / n, 0.5 / n, 0.9 / n};
  std::vector<double> zonal(order), out(order * order);
  for (int l = 0; l < order; ++l) zonal[l] = cap_coefficient(l, alpha);
  prt::sh::rotate_zonal(order, zonal.data(), axis[0], axis[1], axis[2], out.data());
  const std::vector<double> projected = project_cap(order, alpha, axis);
  for (int k = 0; k < order * order; ++k) {
    INFO("k=" << k);
    REQUIRE(out[k] == Approx(projected[k]).margin(1e-13));
  }
  // Float overload: 1e-6 (float rounding of O(1) values).
  std::vector<float> zonal_f(zonal.begin(), zonal.end()), out_f(order * order);
  prt::sh::rotate_zonal(order, zonal_f.data(), float(axis[0]), float(axis[1]), float(axis[2]),
                   out_f.data());
  for (int k = 0; k < order * order; ++k)
    REQUIRE(double(out_f[k]) == Approx(projected[k]).margin(1e-6));
}

TEST_CASE("convolve_zonal with the clamped cosine gives irradiance", "[sh][zonal]") {
  // Radiance 1 + 0.5·x (+ a band-2 term): each band is scaled by A_l; the irradiance at the
  // normal +x is π·1 + (2π/3)·0.5 from bands 0 and 1 (exact; 1e-14 relative for roundoff).
  const int order = 3;
  std::vector<double> a(order), c(order * order, 0.0), y(order * order);
  for (int l = 0; l < order; ++l) a[l] = prt::sh::clamped_cosine_band_factor(l);
  const double y00 = 0.5 / std::sqrt(kPi), y1 = std::sqrt(3 / (4 * kPi));
  c[0] = 1.0 / y00;  // constant 1
  c[3] = 0.5 / y1;   // 0.5·x
  c[5] = 7.0;        // a band-2 coefficient, to check its factor π/4
  std::vector<double> e = c;
  prt::sh::convolve_zonal(order, a.data(), e.data());
  REQUIRE(e[0] == Approx(c[0] * kPi).epsilon(1e-15));
  REQUIRE(e[3] == Approx(c[3] * 2 * kPi / 3).epsilon(1e-15));
  REQUIRE(e[5] == Approx(c[5] * kPi / 4).epsilon(1e-15));
  e[5] = 0.0;
  prt::sh::evaluate(order, 1.0, 0.0, 0.0, y.data());
  double irradiance = 0.0;
  for (int k = 0; k < order * order; ++k) irradiance += e[k] * y[k];
  REQUIRE(irradiance == Approx(kPi + 2 * kPi / 3 * 0.5).epsilon(1e-14));
  // Float overload: float rounding, 1e-6 relative.
  std::vector<float> f(c.begin(), c.end());
  prt::sh::convolve_zonal(order, a.data(), f.data());
  REQUIRE(double(f[3]) == Approx(c[3] * 2 * kPi / 3).epsilon(1e-6));
}
