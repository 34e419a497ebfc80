// tests/sh/test_polar_axis.cpp — prt::sh::WignerHalfPi and the change of polar axis
// (sh/polar_axis.h) against a closed form, sh::Rotation, the addition theorem and group laws, up
// to l = 1023.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/polar_axis.h"
#include "sh/rotation.h"

namespace {

// d^l_m'm(π/2) by the explicit sum (Edmonds (4.1.23) at β = π/2), in long double: fine for
// small l (its alternating sum cancels badly beyond l ≈ 20).
long double binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0L;
  long double b = 1.0L;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

long double factorial(int n) {
  long double f = 1.0L;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

double wigner_half_pi_closed_form(int l, int mp, int m) {
  long double sum = 0.0L;
  for (int k = 0; k <= 2 * l; ++k)
    sum += ((k % 2) ? -1.0L : 1.0L) * binomial(l + m, k) * binomial(l - m, k + mp - m);
  const long double norm =
      std::sqrt(factorial(l + mp) * factorial(l - mp) / (factorial(l + m) * factorial(l - m)));
  const long double sign = ((mp - m) % 2 != 0) ? -1.0L : 1.0L;
  return static_cast<double>(sign * norm * sum / std::pow(2.0L, l));
}

std::vector<double> random_coefficients(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(n);
  for (double& v : c) v = u(rng);
  return c;
}

}  // namespace

TEST_CASE("d(pi/2) equals the closed-form sum up to l = 12", "[sh][polar_axis]") {
  // The closed form in long double is good to ~1e-15 here; the recurrence to rounding. Any wrong
  // sign or index would be an O(0.1) error.
  prt::sh::WignerHalfPi d;
  double worst = 0.0;
  for (int l = 0; l <= 12; ++l) {
    if (l > 0) d.next();
    REQUIRE(d.band() == l);
    for (int mp = -l; mp <= l; ++mp)
      for (int m = -l; m <= l; ++m)
        worst = std::max(worst, std::abs(d(mp, m) - wigner_half_pi_closed_form(l, mp, m)));
  }
  INFO("worst |recurrence - closed form| = " << worst);
  CHECK(worst < 1e-13);
  CHECK(d(13, 0) == 0.0);  // outside the band
}

TEST_CASE("the rows of d(pi/2) stay orthonormal up to l = 1023", "[sh][polar_axis]") {
  // The recurrence runs from the exponentially small corner inwards (the stable direction):
  // measured worst |Σ_m d_am d_bm − δ_ab| is 2e-15 at l = 200 and 7e-15 at l = 1023 (rows and
  // columns sampled every 37 and 41); 1e-12 is the bound.
  prt::sh::WignerHalfPi d;
  for (int l = 1; l <= 1023; ++l) {
    d.next();
    if (l != 200 && l != 1023) continue;
    double worst = 0.0;
    for (int a = -l; a <= l; a += 37)
      for (int b = a; b <= l; b += 41) {
        double dot = 0.0;
        for (int m = -l; m <= l; ++m) dot += d(a, m) * d(b, m);
        worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
      }
    INFO("l = " << l << ": worst orthonormality error " << worst);
    CHECK(worst < 1e-12);
  }
  // The corner is 2^−l exactly (a product of the top-row factors).
  CHECK(d(1023, 1023) == Approx(std::ldexp(1.0, -1023)).epsilon(1e-12));
}

TEST_CASE("the change of polar axis equals sh::Rotation of P-transpose below order 20",
          "[sh][polar_axis]") {
  // sh::Rotation is accurate to ~1e-14 at these orders, so the two agree to rounding; a wrong
  // Euler factor or sign shows as O(1).
  const int order = 20;
  const std::array<double, 9> p_transpose = {0, 1, 0, 0, 0, 1, 1, 0, 0};  // (x,y,z) → (y,z,x)
  const prt::sh::Rotation rotation(order, p_transpose);
  const std::size_t n2 = order * order;
  const std::vector<double> in = random_coefficients(2 * n2, 3);
  std::vector<double> expected(2 * n2), out(2 * n2), back(2 * n2);
  for (int c = 0; c < 2; ++c) rotation.apply(&in[c * n2], &expected[c * n2]);
  prt::sh::polar_y_to_z(order, 2, in.data(), out.data());
  prt::sh::polar_z_to_y(order, 2, out.data(), back.data());
  for (std::size_t i = 0; i < 2 * n2; ++i) {
    CHECK(out[i] == Approx(expected[i]).margin(1e-13));
    CHECK(back[i] == Approx(in[i]).margin(1e-13));
  }
}

TEST_CASE("the change of polar axis is exact on a delta at order 1024", "[sh][polar_axis]") {
  // Addition theorem: the delta at d0 has +y-polar coefficients Y_j(P d0) and scene
  // coefficients Y_k(d0), both from sh::evaluate (independent of the Wigner recurrence).
  // |Y_lm| ≤ √((2l+1)/4π) ≈ 9 at l = 1023; measured worst error 6e-14 absolute; bound 1e-11.
  const int order = 1024;
  const std::size_t n2 = static_cast<std::size_t>(order) * order;
  double d0[3] = {0.3, -0.55, 0.78};
  const double n = std::sqrt(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]);
  for (double& v : d0) v /= n;
  std::vector<double> primed(n2), expected(n2), out(n2);
  prt::sh::evaluate(order, d0[2], d0[0], d0[1], primed.data());  // Y_j(P d0), P d = (z, x, y)
  prt::sh::evaluate(order, d0[0], d0[1], d0[2], expected.data());
  int bands_seen = 0;
  prt::sh::polar_y_to_z(order, 1, primed.data(), out.data(), [&](int band) {
    CHECK(band == bands_seen);
    ++bands_seen;
  });
  CHECK(bands_seen == order);
  double worst = 0.0;
  for (std::size_t k = 0; k < n2; ++k) worst = std::max(worst, std::abs(out[k] - expected[k]));
  INFO("worst |G(P^T) Y(P d0) - Y(d0)| = " << worst);
  CHECK(worst < 1e-11);
}

TEST_CASE("a change of polar axis there and back keeps every band's norm at order 1024",
          "[sh][polar_axis]") {
  // Orthogonal band matrices: ‖G c‖ = ‖c‖ per band and Gᵀ G c = c. Measured: norms to 7e-15
  // relative, round trip to 2.4e-14 absolute on O(1) coefficients; bounds 1e-10 and 1e-12.
  const int order = 1024;
  const std::size_t n2 = static_cast<std::size_t>(order) * order;
  const std::vector<double> in = random_coefficients(n2, 11);
  std::vector<double> there(n2), back(n2);
  prt::sh::polar_y_to_z(order, 1, in.data(), there.data());
  prt::sh::polar_z_to_y(order, 1, there.data(), back.data());
  double worst_norm = 0.0, worst_back = 0.0;
  for (int l = 0; l < order; ++l) {
    double before = 0.0, after = 0.0;
    for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
      before += in[k] * in[k];
      after += there[k] * there[k];
      worst_back = std::max(worst_back, std::abs(back[k] - in[k]));
    }
    worst_norm = std::max(worst_norm, std::abs(after - before) / before);
  }
  INFO("worst relative band-norm change " << worst_norm << ", worst round trip " << worst_back);
  CHECK(worst_norm < 1e-10);
  CHECK(worst_back < 1e-12);
}
