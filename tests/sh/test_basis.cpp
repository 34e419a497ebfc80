// tests/sh/test_basis.cpp — prt::sh::evaluate against independent references.
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh_core_quadrature.h"

namespace {

using prt::sh::kPi;

struct Direction {
  double x, y, z;
};

Direction from_angles(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

std::vector<Direction> random_directions(int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), a(0.0, 2.0 * kPi);
  std::vector<Direction> d;
  for (int i = 0; i < count; ++i) {
    const double z = u(rng), phi = a(rng), r = std::sqrt(1.0 - z * z);
    d.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return d;
}

// Independent long-double reference, angle-based: cos θ = z, sin θ = hypot(x, y) (normalised),
// φ = atan2(y, x); fully normalised P̄_lm(cos θ) (with the sin^m θ factor inside) by the
// recurrence over m (sectoral P̄_mm = √((2m+1)/2m)·sin θ·P̄_{m−1,m−1}) and then over l with
// explicit square-root ratios; Y_l,±m = √2·P̄_lm·cos(mφ) / sin(mφ) from cosl/sinl.
struct Reference {
  int order;
  std::vector<long double> y;         // Y_lm, index l(l+1)+m
  std::vector<long double> legendre;  // P̄_l|m| for every index (the same for ±m)
  std::vector<long double> trig;      // |cos mφ| or |sin mφ| (1 for m = 0)
};

Reference reference_sh(int order, double xd, double yd, double zd) {
  const long double x = xd, y = yd, z = zd;
  const long double r = sqrtl(x * x + y * y + z * z);
  const long double ct = z / r, st = hypotl(x, y) / r, phi = atan2l(y, x);
  const long double pi = prt::sh::kPiLong;
  Reference ref{order, std::vector<long double>(order * order),
                std::vector<long double>(order * order), std::vector<long double>(order * order)};
  auto put = [&](int l, int m, long double p) {
    const int k = l * (l + 1);
    if (m == 0) {
      ref.y[k] = p;
      ref.legendre[k] = p;
      ref.trig[k] = 1;
      return;
    }
    const long double c = cosl(m * phi), s = sinl(m * phi);
    ref.y[k + m] = sqrtl(2.0L) * p * c;
    ref.y[k - m] = sqrtl(2.0L) * p * s;
    ref.legendre[k + m] = ref.legendre[k - m] = p;
    ref.trig[k + m] = fabsl(c);
    ref.trig[k - m] = fabsl(s);
  };
  long double pmm = 1 / sqrtl(4 * pi);
  for (int m = 0; m < order; ++m) {
    if (m > 0) pmm *= sqrtl((2.0L * m + 1) / (2.0L * m)) * st;
    put(m, m, pmm);
    if (m + 1 >= order) continue;
    long double p2 = pmm, p1 = sqrtl(2.0L * m + 3) * ct * pmm;
    put(m + 1, m, p1);
    for (int l = m + 2; l < order; ++l) {
      const long double ll = 1.0L * l * l, mm = 1.0L * m * m, l1 = (l - 1.0L) * (l - 1.0L);
      const long double p =
          sqrtl((4 * ll - 1) / (ll - mm)) * (ct * p1 - sqrtl((l1 - mm) / (4 * l1 - 1)) * p2);
      put(l, m, p);
      p2 = p1;
      p1 = p;
    }
  }
  return ref;
}

// Directions for the stability tests: random ones, plus points at and within 1e-12..1e-3 rad
// of both poles (built from angles, so they are as close to the pole as double allows).
std::vector<Direction> stability_directions() {
  std::vector<Direction> d = random_directions(40, 7);
  const double offsets[] = {0.0, 1e-12, 1e-9, 1e-6, 1e-3};
  int i = 0;
  for (double t : offsets) {
    const double phi = 0.7 + 1.3 * i++;
    d.push_back(from_angles(t, phi));
    d.push_back(from_angles(kPi - t, phi));
  }
  d.push_back({0.0, 0.0, 1.0});
  d.push_back({0.0, 0.0, -1.0});
  return d;
}

// Checks evaluate() at one band l ≥ 0 against the reference. The rule for points near a zero
// crossing: a value counts as well conditioned when its trigonometric factor |cos mφ| (or
// |sin mφ|) is ≥ 1e-3 and its Legendre factor |P̄_lm| is ≥ 1e-3 of its neighbours' |P̄_{l±1,m}|
// (the recurrence's absolute error scales with those neighbours). Well-conditioned values with
// |Y_ref| > 1e-200 must match to a relative 1e-10; the others to 1e-10 of the envelope
// √2·max(|P̄_{l−1,m}|, |P̄_lm|, |P̄_{l+1,m}|); values with |Y_ref| ≤ 1e-200 only need
// |Y| ≤ 1e-190. Returns how many values were checked relatively.
int check_band_against_reference(int l, const double* y, const Reference& ref) {
  int relative_checks = 0;
  for (int m = -l; m <= l; ++m) {
    const int k = l * (l + 1) + m, am = m < 0 ? -m : m;
    const long double yr = ref.y[k];
    const long double err = fabsl(y[k] - yr);
    const long double p = fabsl(ref.legendre[k]);
    long double neighbours = 0;
    if (l - 1 >= am) neighbours = fabsl(ref.legendre[(l - 1) * l + m]);
    if (l + 1 < ref.order)
      neighbours = fmaxl(neighbours, fabsl(ref.legendre[(l + 1) * (l + 2) + m]));
    if (fabsl(yr) <= 1e-200L) {
      INFO("l=" << l << " m=" << m << " tiny ref " << double(yr) << " got " << y[k]);
      REQUIRE(std::fabs(y[k]) <= 1e-190);
      continue;
    }
    if (ref.trig[k] >= 1e-3L && p >= 1e-3L * neighbours) {
      INFO("l=" << l << " m=" << m << " ref " << double(yr) << " got " << y[k]);
      REQUIRE(double(err / fabsl(yr)) < 1e-10);
      ++relative_checks;
    } else {
      const long double envelope = sqrtl(2.0L) * fmaxl(p, neighbours);
      INFO("l=" << l << " m=" << m << " ref " << double(yr) << " got " << y[k] << " envelope "
                << double(envelope));
      REQUIRE(double(err) <= 1e-10 * double(envelope));
    }
  }
  return relative_checks;
}

}  // namespace

TEST_CASE("evaluate is orthonormal under an exact quadrature up to order 16", "[sh][basis]") {
  // Gauss–Legendre (order + 1 nodes in z) × 2·order + 2 angles integrates Y_i·Y_j exactly
  // (degree ≤ 2·order − 2); 1e-12 allows for the roundoff of ~10³ summed terms.
  for (int order : {1, 2, 3, 4, 5, 6, 9, 16}) {
    const sh_test::Quadrature q = sh_test::make_zone_quadrature(order + 1, 2 * order + 2);
    const int n = order * order;
    std::vector<double> gram(n * n, 0.0), y(n);
    for (std::size_t p = 0; p < q.weights.size(); ++p) {
      const auto& d = q.directions[p];
      prt::sh::evaluate(order, d[0], d[1], d[2], y.data());
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) gram[i * n + j] += q.weights[p] * y[i] * y[j];
      }
    }
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) worst = std::fmax(worst, std::fabs(gram[i * n + j] - (i == j)));
    }
    INFO("order " << order);
    REQUIRE(worst < 1e-12);
  }
}

TEST_CASE("evaluate matches the closed forms of bands 0..4", "[sh][basis]") {
  // Cartesian closed forms (e.g. Sloan 2013, appendix; no Condon–Shortley phase). Both sides
  // are O(1) polynomials, so 1e-14 is a few ulps.
  const double s = std::sqrt(1.0 / kPi);
  for (const Direction& d : random_directions(50, 3)) {
    const double x = d.x, y = d.y, z = d.z, x2 = x * x, y2 = y * y, z2 = z * z;
    const double expected[25] = {
        0.5 * s,
        std::sqrt(3.0 / (4 * kPi)) * y,
        std::sqrt(3.0 / (4 * kPi)) * z,
        std::sqrt(3.0 / (4 * kPi)) * x,
        0.5 * std::sqrt(15.0 / kPi) * x * y,
        0.5 * std::sqrt(15.0 / kPi) * y * z,
        0.25 * std::sqrt(5.0 / kPi) * (3 * z2 - 1),
        0.5 * std::sqrt(15.0 / kPi) * x * z,
        0.25 * std::sqrt(15.0 / kPi) * (x2 - y2),
        0.25 * std::sqrt(35.0 / (2 * kPi)) * (3 * x2 - y2) * y,
        0.5 * std::sqrt(105.0 / kPi) * x * y * z,
        0.25 * std::sqrt(21.0 / (2 * kPi)) * y * (5 * z2 - 1),
        0.25 * std::sqrt(7.0 / kPi) * (5 * z2 * z - 3 * z),
        0.25 * std::sqrt(21.0 / (2 * kPi)) * x * (5 * z2 - 1),
        0.25 * std::sqrt(105.0 / kPi) * (x2 - y2) * z,
        0.25 * std::sqrt(35.0 / (2 * kPi)) * (x2 - 3 * y2) * x,
        0.75 * std::sqrt(35.0 / kPi) * x * y * (x2 - y2),
        0.75 * std::sqrt(35.0 / (2 * kPi)) * (3 * x2 - y2) * y * z,
        0.75 * std::sqrt(5.0 / kPi) * x * y * (7 * z2 - 1),
        0.75 * std::sqrt(5.0 / (2 * kPi)) * y * z * (7 * z2 - 3),
        3.0 / 16.0 * s * (35 * z2 * z2 - 30 * z2 + 3),
        0.75 * std::sqrt(5.0 / (2 * kPi)) * x * z * (7 * z2 - 3),
        3.0 / 8.0 * std::sqrt(5.0 / kPi) * (x2 - y2) * (7 * z2 - 1),
        0.75 * std::sqrt(35.0 / (2 * kPi)) * (x2 - 3 * y2) * x * z,
        3.0 / 16.0 * std::sqrt(35.0 / kPi) * (x2 * (x2 - 3 * y2) - y2 * (3 * x2 - y2)),
    };
    double fast[25], recurrence[25], general[49];
    prt::sh::evaluate(5, x, y, z, fast);
    prt::sh::evaluate_recurrence(5, x, y, z, recurrence);
    prt::sh::evaluate(7, x, y, z, general);
    for (int k = 0; k < 25; ++k) {
      INFO("k=" << k);
      REQUIRE(fast[k] == Approx(expected[k]).margin(1e-14));
      REQUIRE(recurrence[k] == Approx(expected[k]).margin(1e-14));
      REQUIRE(general[k] == Approx(expected[k]).margin(1e-14));
    }
  }
  // The closed forms' constants to 6 significant digits (Ramamoorthi & Hanrahan 2001).
  double y[9];
  prt::sh::evaluate(3, 0.0, 0.0, 1.0, y);
  REQUIRE(y[0] == Approx(0.282095).margin(1e-6));
  REQUIRE(y[2] == Approx(0.488603).margin(1e-6));
  REQUIRE(y[6] == Approx(0.315392 * 2).margin(1e-6));
  const double h = std::sqrt(0.5);
  prt::sh::evaluate(3, h, h, 0.0, y);
  REQUIRE(y[4] == Approx(1.092548 * 0.5).margin(1e-6));
  prt::sh::evaluate(3, 1.0, 0.0, 0.0, y);
  REQUIRE(y[3] == Approx(0.488603).margin(1e-6));
  REQUIRE(y[8] == Approx(0.546274).margin(1e-6));
}

TEST_CASE("evaluate at the poles has only m = 0 terms, equal to sqrt((2l+1)/4pi)(+-1)^l",
          "[sh][basis]") {
  for (int order : {3, 6, 7, 40, 201}) {
    for (double sign : {1.0, -1.0}) {
      std::vector<double> y(order * order);
      prt::sh::evaluate(order, 0.0, 0.0, sign, y.data());
      for (int l = 0; l < order; ++l) {
        // Exact value in closed form; 1e-12 relative covers the recurrence's roundoff at l=200.
        const double expected = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * std::pow(sign, l);
        INFO("order " << order << " z " << sign << " l " << l);
        REQUIRE(y[l * (l + 1)] == Approx(expected).epsilon(1e-12));
        for (int m = 1; m <= l; ++m) {
          REQUIRE(y[l * (l + 1) + m] == 0.0);
          REQUIRE(y[l * (l + 1) - m] == 0.0);
        }
      }
    }
  }
}

TEST_CASE("evaluate is stable at l = 100 and l = 200 against a long-double reference",
          "[sh][basis]") {
  int relative_checks = 0;
  for (int order : {16, 64, 101, 201}) {
    std::vector<double> y(order * order);
    for (const Direction& d : stability_directions()) {
      prt::sh::evaluate(order, d.x, d.y, d.z, y.data());
      const Reference ref = reference_sh(order + 1, d.x, d.y, d.z);
      INFO("direction " << d.x << " " << d.y << " " << d.z);
      for (int l : {order - 1, order / 2})
        relative_checks += check_band_against_reference(l, y.data(), ref);
      // Addition theorem Σ_m Y_lm² = (2l+1)/4π (independent of the reference). Tolerance:
      // 1e-12 relative for roundoff, plus the effect of the input's own norm error |r − 1|
      // (≈1e-16): near a pole Σ_m Y_lm² of a non-unit vector moves by ≈ 2·l(l+1)·|r − 1|.
      const int l = order - 1;
      double sum = 0.0;
      for (int k = l * l; k < (l + 1) * (l + 1); ++k) sum += y[k] * y[k];
      const long double r =
          sqrtl((long double)d.x * d.x + (long double)d.y * d.y + (long double)d.z * d.z);
      const double norm_error = double(fabsl(r - 1));
      REQUIRE(
          sum ==
          Approx((2.0 * l + 1.0) / (4.0 * kPi)).epsilon(1e-12 + 4.0 * l * (l + 1.0) * norm_error));
    }
  }
  // Guard against a vacuous pass: most values must have been checked relatively.
  INFO("values checked to a relative 1e-10: " << relative_checks);
  REQUIRE(relative_checks > 20000);
}

TEST_CASE("float evaluate is usable up to l = 30", "[sh][basis]") {
  // Tolerance: 2e-5 of the band's bound √((2l+1)/4π) (|Y_lm| never exceeds it): float's ulp is
  // 6e-8 and the recurrence's error grows about linearly with l (measured ≈ 3e-6 at l = 30).
  const int order = 31;
  std::vector<float> y(order * order), fast(36);
  for (const Direction& d : stability_directions()) {
    const float x = float(d.x), yy = float(d.y), z = float(d.z);
    prt::sh::evaluate(order, x, yy, z, y.data());
    const Reference ref = reference_sh(order, x, yy, z);
    for (int l = 0; l < order; ++l) {
      const double bound = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
      for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
        INFO("l=" << l << " k=" << k);
        REQUIRE(std::fabs(double(y[k]) - double(ref.y[k])) <= 2e-5 * bound);
      }
    }
    prt::sh::evaluate(6, x, yy, z, fast.data());
    for (int k = 0; k < 36; ++k) REQUIRE(std::fabs(double(fast[k]) - double(ref.y[k])) < 2e-6);
  }
}

TEST_CASE("the order <= 6 fast path equals the recurrence", "[sh][basis]") {
  // Relative to the band bound √((2l+1)/4π): 1e-14 in double (a few ulps; the fast path's
  // explicit polynomials and the recurrence round differently), 1e-6 in float.
  std::vector<Direction> dirs = random_directions(500, 11);
  dirs.push_back({0.0, 0.0, 1.0});
  dirs.push_back({0.0, 0.0, -1.0});
  dirs.push_back({1.0, 0.0, 0.0});
  for (int order = 1; order <= 6; ++order) {
    for (const Direction& d : dirs) {
      double a[36], b[36];
      float af[36], bf[36];
      prt::sh::evaluate(order, d.x, d.y, d.z, a);
      prt::sh::evaluate_recurrence(order, d.x, d.y, d.z, b);
      prt::sh::evaluate(order, float(d.x), float(d.y), float(d.z), af);
      prt::sh::evaluate_recurrence(order, float(d.x), float(d.y), float(d.z), bf);
      for (int l = 0; l < order; ++l) {
        const double bound = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
          INFO("order " << order << " k " << k);
          REQUIRE(std::fabs(a[k] - b[k]) <= 1e-14 * bound);
          REQUIRE(std::fabs(double(af[k]) - double(bf[k])) <= 1e-6 * bound);
        }
      }
    }
  }
}

TEST_CASE("the unrolled orders <= 16 agree with the general recurrence", "[sh][basis]") {
  // Orders ≤ 16 run a compile-time-unrolled copy of the column recurrence; order 17 runs the
  // general loop. Same arithmetic, so they agree to roundoff (1e-15 of the band bound).
  for (const Direction& d : random_directions(200, 13)) {
    double a[17 * 17], b[16 * 16];
    prt::sh::evaluate(17, d.x, d.y, d.z, a);
    for (int order = 7; order <= 16; ++order) {
      prt::sh::evaluate(order, d.x, d.y, d.z, b);
      for (int l = 0; l < order; ++l) {
        const double bound = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
          REQUIRE(std::fabs(a[k] - b[k]) <= 1e-15 * bound);
        }
      }
    }
  }
}

TEST_CASE("evaluate ignores an order outside [1, kMaxOrder]", "[sh][basis]") {
  double y[4] = {7.0, 7.0, 7.0, 7.0};
  prt::sh::evaluate(0, 0.0, 0.0, 1.0, y);
  prt::sh::evaluate(-3, 0.0, 0.0, 1.0, y);
  prt::sh::evaluate(prt::sh::kMaxOrder + 1, 0.0, 0.0, 1.0, y);
  for (double v : y) REQUIRE(v == 7.0);
  REQUIRE(prt::sh::coefficient_count(5) == 25);
  REQUIRE(prt::sh::index(2, -1) == 5);
}
