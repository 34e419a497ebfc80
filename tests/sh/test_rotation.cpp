// tests/sh/test_rotation.cpp — prt::sh::Rotation against numerical projection and group laws.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/rotation.h"
#include "sh_core_quadrature.h"

namespace {

using prt::sh::kPi;
using Matrix3 = std::array<double, 9>;

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) c[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
    }
  }
  return c;
}

// Rotation by `angle` about the unit axis (Rodrigues), right-handed.
Matrix3 axis_angle(double ax, double ay, double az, double angle) {
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n;
  ay /= n;
  az /= n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  return {t * ax * ax + c,      t * ax * ay - s * az, t * ax * az + s * ay,
          t * ax * ay + s * az, t * ay * ay + c,      t * ay * az - s * ax,
          t * ax * az - s * ay, t * ay * az + s * ax, t * az * az + c};
}

Matrix3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> a(0.0, 2.0 * kPi);
  return axis_angle(g(rng), g(rng), g(rng), a(rng));
}

std::vector<double> random_coefficients(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(n);
  for (double& v : c) v = u(rng);
  return c;
}

}  // namespace

TEST_CASE("band matrices are orthogonal up to l = 20", "[sh][rotation]") {
  // Ivanic–Ruedenberg error grows with l; at l = 20 it measures ≈ 5e-15 in double. 1e-10 (the
  // brief's bound) leaves margin and still catches any wrong coefficient (O(1) errors).
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const prt::sh::Rotation r(21, random_rotation(rng));
    REQUIRE(r.order() == 21);
    for (int l = 0; l <= 20; ++l) {
      const int s = 2 * l + 1;
      const double* b = r.band_matrix(l);
      REQUIRE(b != nullptr);
      double worst = 0.0;
      for (int i = 0; i < s; ++i) {
        for (int j = 0; j < s; ++j) {
          double dot = 0.0;
          for (int k = 0; k < s; ++k) dot += b[i * s + k] * b[j * s + k];
          worst = std::fmax(worst, std::fabs(dot - (i == j)));
        }
      }
      INFO("l=" << l);
      REQUIRE(worst < 1e-10);
    }
    REQUIRE(r.band_matrix(21) == nullptr);
    REQUIRE(r.band_matrix(-1) == nullptr);
  }
}

TEST_CASE("rotation composes: R(a)R(b) = R(ab), and R(I) = I", "[sh][rotation]") {
  // 1e-12: products of orthogonal matrices of size ≤ 21 in double.
  std::mt19937_64 rng(9);
  const int order = 12, n = order * order;
  for (int trial = 0; trial < 5; ++trial) {
    const Matrix3 a = random_rotation(rng), b = random_rotation(rng);
    const prt::sh::Rotation ra(order, a), rb(order, b), rab(order, multiply(a, b));
    const std::vector<double> f = random_coefficients(n, rng);
    std::vector<double> g(n), h(n), direct(n);
    rb.apply(f.data(), g.data());
    ra.apply(g.data(), h.data());
    rab.apply(f.data(), direct.data());
    for (int k = 0; k < n; ++k) REQUIRE(h[k] == Approx(direct[k]).margin(1e-12));
  }
  const prt::sh::Rotation identity(order, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  for (int l = 0; l < order; ++l) {
    const int s = 2 * l + 1;
    for (int i = 0; i < s * s; ++i) {
      REQUIRE(identity.band_matrix(l)[i] == Approx(i % (s + 1) == 0 ? 1.0 : 0.0).margin(1e-14));
    }
  }
}

TEST_CASE("rotating coefficients equals projecting the rotated function", "[sh][rotation]") {
  // f = Σ c_k Y_k is band-limited to `order`, so g(ω) = f(Mᵀω) is too, and the product
  // quadrature (order+1 nodes × 2·order+2 angles) projects it exactly: agreement to 1e-11
  // (roundoff of ~600-point sums of O(1) terms).
  std::mt19937_64 rng(21);
  const int order = 8, n = order * order;
  const sh_test::Quadrature q = sh_test::make_zone_quadrature(order + 1, 2 * order + 2);
  for (int trial = 0; trial < 4; ++trial) {
    const Matrix3 m = random_rotation(rng);
    const std::vector<double> f = random_coefficients(n, rng);
    std::vector<double> projected(n, 0.0), y(n), rotated(n);
    for (std::size_t p = 0; p < q.weights.size(); ++p) {
      const auto& w = q.directions[p];
      // Mᵀω
      const double u[3] = {m[0] * w[0] + m[3] * w[1] + m[6] * w[2],
                           m[1] * w[0] + m[4] * w[1] + m[7] * w[2],
                           m[2] * w[0] + m[5] * w[1] + m[8] * w[2]};
      prt::sh::evaluate(order, u[0], u[1], u[2], y.data());
      double value = 0.0;
      for (int k = 0; k < n; ++k) value += f[k] * y[k];
      prt::sh::evaluate(order, w[0], w[1], w[2], y.data());
      for (int k = 0; k < n; ++k) projected[k] += q.weights[p] * value * y[k];
    }
    prt::sh::Rotation(order, m).apply(f.data(), rotated.data());
    std::vector<float> ff(f.begin(), f.end()), rf(n);
    prt::sh::Rotation(order, m).apply(ff.data(), rf.data());
    for (int k = 0; k < n; ++k) {
      INFO("k=" << k);
      REQUIRE(rotated[k] == Approx(projected[k]).margin(1e-11));
      // Float apply: inputs rounded to float (6e-8) times ‖f‖₁ per band ≲ 20.
      REQUIRE(double(rf[k]) == Approx(projected[k]).margin(5e-6));
    }
  }
}

TEST_CASE("rotating Y1,0 (z) by 90 degrees about +x gives -y", "[sh][rotation]") {
  // Rx(90°) maps +z to −y, so g(ω) = f(Mᵀω) = (M·e_z)·ω = −y: coefficient −1 on Y1,−1.
  const prt::sh::Rotation r(2, axis_angle(1, 0, 0, kPi / 2));
  const double f[4] = {0.0, 0.0, 1.0, 0.0};
  double g[4];
  r.apply(f, g);
  REQUIRE(g[0] == Approx(0.0).margin(1e-15));
  REQUIRE(g[1] == Approx(-1.0).margin(1e-15));
  REQUIRE(g[2] == Approx(0.0).margin(1e-15));
  REQUIRE(g[3] == Approx(0.0).margin(1e-15));
  // Band 2: Y2,0 turned by 90° about +y (+z → +x) must equal Y2,0(Mᵀω) pointwise.
  const prt::sh::Rotation ry(3, axis_angle(0, 1, 0, kPi / 2));
  double c[9] = {0, 0, 0, 0, 0, 0, 1, 0, 0}, rc[9], y[9], y0[9];
  ry.apply(c, rc);
  for (const auto& w : {std::array<double, 3>{0.6, 0.0, 0.8}, std::array<double, 3>{0.0, 0.6, 0.8},
                        std::array<double, 3>{1.0, 0.0, 0.0}}) {
    prt::sh::evaluate(3, w[0], w[1], w[2], y);
    // Mᵀω for M = Ry(90°): Mᵀ(x, y, z) = (−z, y, x).
    prt::sh::evaluate(3, -w[2], w[1], w[0], y0);
    double value = 0.0;
    for (int k = 0; k < 9; ++k) value += rc[k] * y[k];
    REQUIRE(value == Approx(y0[6]).margin(1e-14));
  }
}

TEST_CASE("rotation_from_yaw_pitch_roll is Ry(yaw) Rx(pitch) Rz(roll)", "[sh][rotation]") {
  const double yaw = 30.0, pitch = -50.0, roll = 110.0, d = kPi / 180.0;
  const Matrix3 expected =
      multiply(axis_angle(0, 1, 0, yaw * d),
               multiply(axis_angle(1, 0, 0, pitch * d), axis_angle(0, 0, 1, roll * d)));
  const Matrix3 m = prt::sh::rotation_from_yaw_pitch_roll(yaw, pitch, roll);
  for (int i = 0; i < 9; ++i) REQUIRE(m[i] == Approx(expected[i]).margin(1e-15));
  // Yaw 90° turns +x toward −z (right-handed about +Y).
  const Matrix3 y90 = prt::sh::rotation_from_yaw_pitch_roll(90.0, 0.0, 0.0);
  REQUIRE(y90[0] == Approx(0.0).margin(1e-15));
  REQUIRE(y90[6] == Approx(-1.0).margin(1e-15));
}

TEST_CASE("closed-form band 2 and inline storage equal the plain recurrence", "[sh][rotation]") {
  // The constructor writes band 2 in closed form (quadratic in M) and keeps order ≤ 6 inline;
  // build_with_recurrence() runs Ivanic–Ruedenberg from band 2. Both are exact for proper
  // rotations, so they must agree to roundoff: 1e-13 (entries are O(1), ~10 operations each;
  // a wrong sign or index in any closed-form entry is an O(1) error). Cases: random rotations,
  // the identity, 180° turns about axes and diagonals, and near-gimbal ones (tiny angles about
  // x/y, i.e. the z axis almost fixed or almost flipped).
  std::mt19937_64 rng(77);
  std::vector<Matrix3> cases;
  for (int i = 0; i < 200; ++i) cases.push_back(random_rotation(rng));
  cases.push_back({1, 0, 0, 0, 1, 0, 0, 0, 1});
  for (const auto& axis : {std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0, 1, 0},
                           std::array<double, 3>{0, 0, 1}, std::array<double, 3>{1, 1, 0},
                           std::array<double, 3>{1, -2, 3}}) {
    cases.push_back(axis_angle(axis[0], axis[1], axis[2], kPi));
    for (double eps : {1e-9, 1e-4}) {
      cases.push_back(axis_angle(axis[0], axis[1], axis[2], eps));
      cases.push_back(axis_angle(axis[0], axis[1], axis[2], kPi - eps));
    }
  }
  for (const Matrix3& m : cases) {
    for (int order : {1, 2, 3, 4, 5, 6, 7, 12}) {
      const prt::sh::Rotation fast(order, m);
      const prt::sh::Rotation reference = prt::sh::Rotation::build_with_recurrence(order, m);
      REQUIRE(fast.order() == order);
      REQUIRE(reference.order() == order);
      for (int l = 0; l < order; ++l) {
        const int s = 2 * l + 1;
        for (int i = 0; i < s * s; ++i) {
          INFO("order=" << order << " l=" << l << " entry=" << i);
          REQUIRE(fast.band_matrix(l)[i] == Approx(reference.band_matrix(l)[i]).margin(1e-13));
        }
      }
      // A copy (inline storage for order ≤ 6) must keep the same matrices.
      const prt::sh::Rotation copy = fast;
      const std::vector<double> f = random_coefficients(order * order, rng);
      std::vector<double> g(order * order), h(order * order);
      fast.apply(f.data(), g.data());
      copy.apply(f.data(), h.data());
      REQUIRE(g == h);
    }
  }
}

namespace {

Matrix3 rotation_z(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c, -s, 0, s, c, 0, 0, 0, 1};
}

Matrix3 rotation_y(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c, 0, s, 0, 1, 0, -s, 0, c};
}

// Rotations that stress rotate_coefficients' Euler decomposition: random ones, the identity,
// 180° turns about the axes and diagonals, ZYZ products with β exactly at and within
// 1e-12..1e-6 of 0 and π (gimbal poles), and near-identity turns about random axes.
std::vector<Matrix3> make_euler_stress_rotations(std::mt19937_64& rng) {
  std::vector<Matrix3> cases;
  for (int i = 0; i < 500; ++i) cases.push_back(random_rotation(rng));
  cases.push_back({1, 0, 0, 0, 1, 0, 0, 0, 1});
  for (const auto& axis : {std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0, 1, 0},
                           std::array<double, 3>{0, 0, 1}, std::array<double, 3>{1, 1, 0},
                           std::array<double, 3>{1, 0, 1}, std::array<double, 3>{0, 1, 1},
                           std::array<double, 3>{1, 1, 1}, std::array<double, 3>{1, -1, 1},
                           std::array<double, 3>{1, -2, 3}}) {
    cases.push_back(axis_angle(axis[0], axis[1], axis[2], kPi));
  }
  // Exact 180° turns without rounding in sin π: diag(1, −1, −1), diag(−1, 1, −1), diag(−1, −1, 1).
  cases.push_back({1, 0, 0, 0, -1, 0, 0, 0, -1});
  cases.push_back({-1, 0, 0, 0, 1, 0, 0, 0, -1});
  cases.push_back({-1, 0, 0, 0, -1, 0, 0, 0, 1});
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (double delta : {0.0, 1e-12, 3e-11, 1e-9, 1e-8, 1e-7, 1e-6}) {
    for (int i = 0; i < 4; ++i) {
      const double alpha = angle(rng), gamma = angle(rng);
      for (double beta : {delta, kPi - delta, -delta}) {
        cases.push_back(multiply(rotation_z(alpha), multiply(rotation_y(beta), rotation_z(gamma))));
      }
    }
  }
  std::normal_distribution<double> g;
  for (double eps : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3}) {
    for (int i = 0; i < 4; ++i) cases.push_back(axis_angle(g(rng), g(rng), g(rng), eps));
  }
  return cases;
}

}  // namespace

TEST_CASE("rotate_coefficients equals Rotation::apply", "[sh][rotation]") {
  // Both compute the same orthogonal map; rotate_coefficients goes through Euler angles and five
  // factors, apply through the Ivanic–Ruedenberg matrices, so they agree to roundoff: entries of
  // the band matrices are O(1), inputs are in [−1, 1], ~4·(2l+1) operations per output, so errors
  // are ~1e-14 at l ≤ 15. 1e-12 leaves margin; a wrong sign, index or ill-conditioned angle
  // (error ε/sin β ≥ 1e-10 near the poles) would exceed it.
  std::mt19937_64 rng(91);
  const std::vector<Matrix3> cases = make_euler_stress_rotations(rng);
  std::vector<int> orders;
  for (int order = 1; order <= 10; ++order) orders.push_back(order);
  orders.push_back(prt::sh::kFastRotateOrder);      // the largest fast-path order
  orders.push_back(prt::sh::kFastRotateOrder + 1);  // falls back to Rotation
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Matrix3& m = cases[c];
    for (int order : orders) {
      if (order > 10 && c % 10 != 0) continue;  // high orders on a subset, for run time
      const int n = order * order;
      const std::vector<double> f = random_coefficients(n, rng);
      std::vector<double> expected(n), actual(n, std::nan(""));
      prt::sh::Rotation(order, m).apply(f.data(), expected.data());
      prt::sh::rotate_coefficients(order, m, f.data(), actual.data());
      for (int k = 0; k < n; ++k) {
        INFO("case=" << c << " order=" << order << " k=" << k);
        REQUIRE(std::isfinite(actual[k]));
        REQUIRE(std::abs(actual[k] - expected[k]) <= 1e-12);
      }
    }
  }
}

TEST_CASE("rotate_coefficients composes: R(a)(R(b) x) = R(ab) x", "[sh][rotation]") {
  // The group law checks the factorisation independently of prt::sh::Rotation. Two chained
  // rotations against one: roundoff ~1e-14 at order 10, 1e-12 as above.
  std::mt19937_64 rng(92);
  for (int trial = 0; trial < 100; ++trial) {
    const Matrix3 a = random_rotation(rng), b = random_rotation(rng);
    for (int order : {2, 3, 5, 8, 10, prt::sh::kFastRotateOrder}) {
      const int n = order * order;
      const std::vector<double> x = random_coefficients(n, rng);
      std::vector<double> bx(n), abx(n), direct(n);
      prt::sh::rotate_coefficients(order, b, x.data(), bx.data());
      prt::sh::rotate_coefficients(order, a, bx.data(), abx.data());
      prt::sh::rotate_coefficients(order, multiply(a, b), x.data(), direct.data());
      for (int k = 0; k < n; ++k) {
        INFO("trial=" << trial << " order=" << order << " k=" << k);
        REQUIRE(std::abs(abx[k] - direct[k]) <= 1e-12);
      }
    }
  }
}

TEST_CASE("rotate_coefficients rotates an evaluated lobe to M·d", "[sh][rotation]") {
  // Independent of prt::sh::Rotation: the coefficients of a delta at d are Y(d), and f(Mᵀω) for
  // that delta is a delta at M·d, so R·Y(d) = Y(M·d) exactly. Roundoff ~1e-14; 1e-12 bound.
  std::mt19937_64 rng(93);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 100; ++trial) {
    const Matrix3 m = random_rotation(rng);
    double d[3] = {g(rng), g(rng), g(rng)};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& v : d) v /= len;
    const double md[3] = {m[0] * d[0] + m[1] * d[1] + m[2] * d[2],
                          m[3] * d[0] + m[4] * d[1] + m[5] * d[2],
                          m[6] * d[0] + m[7] * d[1] + m[8] * d[2]};
    for (int order : {3, 5, 10}) {
      const int n = order * order;
      std::vector<double> y(n), rotated(n), expected(n);
      prt::sh::evaluate(order, d[0], d[1], d[2], y.data());
      prt::sh::evaluate(order, md[0], md[1], md[2], expected.data());
      prt::sh::rotate_coefficients(order, m, y.data(), rotated.data());
      for (int k = 0; k < n; ++k) {
        INFO("trial=" << trial << " order=" << order << " k=" << k);
        REQUIRE(rotated[k] == Approx(expected[k]).margin(1e-12));
      }
    }
  }
}

TEST_CASE("rotate_coefficients float matches double", "[sh][rotation]") {
  // The float version computes in double and rounds the results: each output is within one float
  // rounding (6e-8 relative, outputs ≤ ~4 in magnitude) of the double result, plus the input
  // rounding carried through the orthogonal map; 1e-6 absolute bounds both.
  std::mt19937_64 rng(94);
  for (int trial = 0; trial < 50; ++trial) {
    const Matrix3 m = random_rotation(rng);
    for (int order : {1, 3, 5, 10, prt::sh::kFastRotateOrder + 2}) {
      const int n = order * order;
      const std::vector<double> x = random_coefficients(n, rng);
      std::vector<float> xf(x.begin(), x.end()), yf(n);
      std::vector<double> xd(xf.begin(), xf.end()), yd(n);
      prt::sh::rotate_coefficients(order, m, xf.data(), yf.data());
      prt::sh::rotate_coefficients(order, m, xd.data(), yd.data());
      for (int k = 0; k < n; ++k) REQUIRE(std::abs(double(yf[k]) - yd[k]) <= 1e-6);
    }
  }
}
