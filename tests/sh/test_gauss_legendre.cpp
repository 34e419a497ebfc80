// numerics/gauss_legendre.h: the rule against the closed-form 3-point rule and the tabulated
// 5-point rule, its exactness degree 2n − 1 on several intervals (and that degree 2n is not
// exact), the node order and sum of weights, appending, the [−1, 1] form, and a smooth integrand.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"

namespace {

using prt::numerics::kPi;

struct Rule {
  std::vector<double> x, w;
};

Rule rule(int n, double a, double b) {
  Rule r;
  prt::numerics::append_gauss_legendre(n, a, b, &r.x, &r.w);
  return r;
}

// ∫_a^b t^k dx with t = (x − mid)/half: half · (1 + (−1)^k)/(k + 1).
double monomial_exact(int k, double a, double b) {
  return 0.5 * (b - a) * (k % 2 == 0 ? 2.0 / (k + 1) : 0.0);
}

double monomial_rule(const Rule& r, int k, double a, double b) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sum = 0.0;
  for (std::size_t i = 0; i < r.x.size(); ++i) sum += r.w[i] * std::pow((r.x[i] - mid) / half, k);
  return sum;
}

}  // namespace

TEST_CASE("Gauss-Legendre: the 3-point rule is the closed form, nodes from b towards a",
          "[gauss_legendre]") {
  // Nodes ±√(3/5), 0 and weights 5/9, 8/9, 5/9 on [−1, 1], to a few ulp (the weights come out
  // 3 ulp low: 1e-15 relative allows 9).
  const Rule r = rule(3, -1.0, 1.0);
  REQUIRE(r.x.size() == 3);
  REQUIRE(r.w.size() == 3);
  CHECK(r.x[0] == Approx(std::sqrt(0.6)).epsilon(1e-15));
  CHECK(std::abs(r.x[1]) < 1e-15);
  CHECK(r.x[2] == Approx(-std::sqrt(0.6)).epsilon(1e-15));
  CHECK(r.w[0] == Approx(5.0 / 9.0).epsilon(1e-15));
  CHECK(r.w[1] == Approx(8.0 / 9.0).epsilon(1e-15));
  CHECK(r.w[2] == Approx(5.0 / 9.0).epsilon(1e-15));
}

TEST_CASE("Gauss-Legendre: exact to degree 2n - 1 on any interval, not to degree 2n",
          "[gauss_legendre]") {
  const double intervals[][2] = {{-1.0, 1.0}, {0.0, 1.0}, {2.0, 7.5}, {std::cos(0.0046), 1.0}};
  for (const auto& ab : intervals) {
    const double a = ab[0], b = ab[1];
    for (int n : {1, 2, 3, 5, 8, 13, 32, 64}) {
      const Rule r = rule(n, a, b);
      REQUIRE(r.x.size() == std::size_t(n));
      INFO("n " << n << " on [" << a << ", " << b << "]");
      double weight_sum = 0.0;
      for (std::size_t i = 0; i < r.x.size(); ++i) {
        CHECK(r.x[i] > a);
        CHECK(r.x[i] < b);
        if (i > 0) CHECK(r.x[i] < r.x[i - 1]);
        CHECK(r.w[i] > 0.0);
        weight_sum += r.w[i];
      }
      // Rounding: about n ulp of the interval's length.
      CHECK(std::abs(weight_sum - (b - a)) <= 1e-15 * n * (b - a));
      // Nodes carry rounding of the endpoints' magnitude (1 ulp of 1 is 2e-11 of the sun
      // disc's interval of 1.06e-5), which t^k amplifies by k: the bound scales with the larger.
      const double scale = std::max(b - a, std::max(std::abs(a), std::abs(b)));
      for (int k = 0; k <= 2 * n - 1; ++k) {
        INFO("degree " << k);
        CHECK(std::abs(monomial_rule(r, k, a, b) - monomial_exact(k, a, b)) <= 1e-14 * n * scale);
      }
      // Degree 2n: the error is half·2^(2n+1)(n!)^4/((2n+1)((2n)!)^2) of t^2n, 0.67 for n = 1
      // and 4.7e-5 for n = 8: far above rounding, so a rule exact to a higher degree than
      // claimed (or a wrong node set) fails here.
      if (n <= 8)
        CHECK(std::abs(monomial_rule(r, 2 * n, a, b) - monomial_exact(2 * n, a, b)) >
              1e-6 * (b - a));
    }
  }
}

TEST_CASE("Gauss-Legendre: appends, n = 0 appends nothing, a smooth integrand converges",
          "[gauss_legendre]") {
  std::vector<double> x{42.0}, w{-1.0};
  prt::numerics::append_gauss_legendre(4, 0.0, 1.0, &x, &w);
  prt::numerics::append_gauss_legendre(0, 0.0, 1.0, &x, &w);
  prt::numerics::append_gauss_legendre(4, 1.0, 2.0, &x, &w);
  REQUIRE(x.size() == 9);
  CHECK(x[0] == 42.0);
  CHECK(w[0] == -1.0);
  double panels = 0.0;  // ∫_0^2 x^7 dx = 32 by two 4-point panels (degree 7 = 2·4 − 1)
  for (std::size_t i = 1; i < x.size(); ++i) panels += w[i] * std::pow(x[i], 7);
  CHECK(panels == Approx(32.0).epsilon(1e-14));
  // ∫_0^π sin = 2: the error of n points is at most π^(2n+1)(n!)^4/((2n+1)((2n)!)^3) (|sin^(2n)|
  // ≤ 1): 1.7e-5 for n = 4, 3e-24 for n = 12 (so rounding only).
  double s4 = 0.0, s12 = 0.0;
  const Rule r4 = rule(4, 0.0, kPi), r12 = rule(12, 0.0, kPi);
  for (std::size_t i = 0; i < r4.x.size(); ++i) s4 += r4.w[i] * std::sin(r4.x[i]);
  for (std::size_t i = 0; i < r12.x.size(); ++i) s12 += r12.w[i] * std::sin(r12.x[i]);
  CHECK(std::abs(s4 - 2.0) > 1e-6);
  CHECK(std::abs(s4 - 2.0) < 1.7e-5);
  CHECK(std::abs(s12 - 2.0) < 1e-14);
  // A reversed interval: the same nodes, weights negated (∫_b^a = −∫_a^b).
  const Rule fwd = rule(5, 0.0, 3.0), rev = rule(5, 3.0, 0.0);
  double sum = 0.0;
  for (std::size_t i = 0; i < rev.w.size(); ++i) {
    CHECK(rev.w[i] < 0.0);
    sum += rev.w[i];
  }
  CHECK(sum == Approx(-3.0).epsilon(1e-15));
}

TEST_CASE("Gauss-Legendre: the tabulated 5-point rule, and gauss_legendre is the rule on [-1, 1]",
          "[gauss_legendre]") {
  // Abramowitz & Stegun, Table 25.4 (n = 5), 16 digits: nodes ±0.9061798459386640,
  // ±0.5384693101056831, 0 and weights 0.2369268850561891, 0.4786286704993665, 128/225. The
  // rule's nodes and weights are good to a few ulp: 1e-15 relative (absolute for the 0 node).
  const double nodes[5] = {0.9061798459386640, 0.5384693101056831, 0.0, -0.5384693101056831,
                           -0.9061798459386640};
  const double weights[5] = {0.2369268850561891, 0.4786286704993665, 128.0 / 225.0,
                             0.4786286704993665, 0.2369268850561891};
  std::vector<double> x{1.0, 2.0}, w{3.0};  // replaced, not appended to
  prt::numerics::gauss_legendre(5, &x, &w);
  REQUIRE(x.size() == 5);
  REQUIRE(w.size() == 5);
  for (int i = 0; i < 5; ++i) {
    INFO("node " << i);
    CHECK(std::abs(x[i] - nodes[i]) <= 1e-15 * std::max(1.0, std::abs(nodes[i])));
    CHECK(w[i] == Approx(weights[i]).epsilon(1e-15));
  }
  // The same numbers, bit for bit, as the interval form on [−1, 1].
  for (int n : {1, 2, 3, 6, 17, 40}) {
    std::vector<double> a, wa, b, wb;
    prt::numerics::gauss_legendre(n, &a, &wa);
    prt::numerics::append_gauss_legendre(n, -1.0, 1.0, &b, &wb);
    CHECK(a == b);
    CHECK(wa == wb);
  }
}
