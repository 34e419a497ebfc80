// tests/sh/test_window.cpp — window factors and the automatic window choice.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/window.h"
#include "sh/zonal.h"

namespace {

using prt::sh::kPi;

// Radiance coefficients of a "sun": a cap of half-angle α about the unit axis with radiance
// `value`, from the closed-form cap coefficients rotated with rotate_zonal.
std::vector<double> sun_coefficients(int order, double alpha, double value,
                                     std::array<double, 3> axis) {
  std::vector<double> zonal(order), out(order * order), p(order + 1);
  const double t = std::cos(alpha);
  p[0] = 1.0;
  p[1] = t;
  for (int l = 1; l < order; ++l) p[l + 1] = ((2 * l + 1) * t * p[l] - l * p[l - 1]) / (l + 1);
  zonal[0] = value * std::sqrt(kPi) * (1 - t);
  for (int l = 1; l < order; ++l) {
    zonal[l] =
        value * 2 * kPi * std::sqrt((2 * l + 1) / (4 * kPi)) * (p[l - 1] - p[l + 1]) / (2 * l + 1);
  }
  prt::sh::rotate_zonal(order, zonal.data(), axis[0], axis[1], axis[2], out.data());
  return out;
}

// Minimum irradiance E = Σ A_l h_l L_lm Y_lm over a dense θ–φ grid (independent of the
// library's Fibonacci set).
double minimum_irradiance(const std::vector<double>& l_coeffs, int order,
                          const std::vector<double>& h) {
  std::vector<double> y(order * order);
  double lowest = 1e300;
  for (int i = 0; i <= 180; ++i) {
    for (int j = 0; j < 360; ++j) {
      const double theta = kPi * i / 180, phi = 2 * kPi * j / 360;
      prt::sh::evaluate(order, std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                        std::cos(theta), y.data());
      double e = 0.0;
      for (int l = 0; l < order; ++l) {
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
          e += prt::sh::clamped_cosine_band_factor(l) * h[l] * l_coeffs[k] * y[k];
        }
      }
      lowest = std::fmin(lowest, e);
    }
  }
  return lowest;
}

}  // namespace

TEST_CASE("window factors lie in [0, 1] with h0 = 1", "[sh][window]") {
  for (prt::sh::Window w :
       {prt::sh::Window::None, prt::sh::Window::Hanning, prt::sh::Window::Lanczos,
        prt::sh::Window::Laplacian, prt::sh::Window::Auto}) {
    for (int order : {1, 2, 3, 5, 9, 16}) {
      for (double strength : {0.0, 0.5, 1.0, 3.0, 1e-3, -1.0}) {
        const std::vector<double> h = prt::sh::window_band_factors(w, order, strength);
        INFO(prt::sh::window_name(w) << " order " << order << " strength " << strength);
        REQUIRE(int(h.size()) == order);
        REQUIRE(h[0] == 1.0);
        for (int l = 1; l < order; ++l) {
          REQUIRE(h[l] >= 0.0);
          REQUIRE(h[l] <= 1.0);
          // Every window here is non-increasing in l (Hanning/Lanczos up to the cutoff).
          REQUIRE(h[l] <= h[l - 1] + 1e-15);
          if (w == prt::sh::Window::None || w == prt::sh::Window::Auto) REQUIRE(h[l] == 1.0);
        }
      }
    }
  }
  REQUIRE(prt::sh::window_band_factors(prt::sh::Window::Hanning, 0, 1.0).empty());
}

TEST_CASE("window factors follow their formulas and defaults", "[sh][window]") {
  // Hanning with width 4: ½(1 + cos(πl/4)), zero from l = 4 on.
  const std::vector<double> hann = prt::sh::window_band_factors(prt::sh::Window::Hanning, 6, 4.0);
  REQUIRE(hann[1] == Approx(0.5 * (1 + std::cos(kPi / 4))));
  REQUIRE(hann[2] == Approx(0.5));
  REQUIRE(hann[4] == 0.0);
  REQUIRE(hann[5] == 0.0);
  // Default width = order: the last band is attenuated, not removed.
  const std::vector<double> hann_default =
      prt::sh::window_band_factors(prt::sh::Window::Hanning, 5, 0.0);
  REQUIRE(hann_default[4] == Approx(0.5 * (1 + std::cos(kPi * 4 / 5))));
  // Lanczos: sinc(πl/order)^s.
  const std::vector<double> lanczos =
      prt::sh::window_band_factors(prt::sh::Window::Lanczos, 4, 2.0);
  const double x = kPi * 3 / 4;
  REQUIRE(lanczos[3] == Approx(std::pow(std::sin(x) / x, 2.0)));
  // Laplacian: 1/(1 + λ l²(l+1)²); the default halves the last band.
  const std::vector<double> lap = prt::sh::window_band_factors(prt::sh::Window::Laplacian, 5, 0.01);
  REQUIRE(lap[2] == Approx(1 / (1 + 0.01 * 36)));
  REQUIRE(prt::sh::window_band_factors(prt::sh::Window::Laplacian, 5, 0.0)[4] == Approx(0.5));
}

TEST_CASE("window names round-trip", "[sh][window]") {
  for (prt::sh::Window w :
       {prt::sh::Window::None, prt::sh::Window::Hanning, prt::sh::Window::Lanczos,
        prt::sh::Window::Laplacian, prt::sh::Window::Auto}) {
    prt::sh::Window parsed = prt::sh::Window::None;
    REQUIRE(prt::sh::parse_window(prt::sh::window_name(w), &parsed));
    REQUIRE(parsed == w);
  }
  prt::sh::Window w = prt::sh::Window::Auto;
  REQUIRE(prt::sh::parse_window("LaPlacian", &w));
  REQUIRE(w == prt::sh::Window::Laplacian);
  REQUIRE(prt::sh::parse_window("hann", &w));
  REQUIRE(w == prt::sh::Window::Hanning);
  REQUIRE_FALSE(prt::sh::parse_window("gauss", &w));
  REQUIRE(w == prt::sh::Window::Hanning);  // untouched on failure
  REQUIRE_FALSE(prt::sh::parse_window("", &w));
}

TEST_CASE("auto window removes the negative irradiance of a sun", "[sh][window]") {
  // A small bright sun (half-angle 2°, radiance 5000) over a dim sky of radiance 0.05: at order
  // 9 the band-limited irradiance rings well below zero opposite the sun.
  const int order = 9, n = order * order;
  const double len = std::sqrt(0.2 * 0.2 + 0.9 * 0.9 + 0.4 * 0.4);
  std::vector<double> sun =
      sun_coefficients(order, 2.0 * kPi / 180, 5000.0, {0.2 / len, 0.9 / len, 0.4 / len});
  std::vector<double> rgb(3 * n);
  const double sky[3] = {0.05, 0.04, 0.03}, tint[3] = {1.0, 0.9, 0.7};
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < n; ++k) rgb[c * n + k] = tint[c] * sun[k];
    rgb[c * n] += sky[c] * 2 * std::sqrt(kPi);  // constant sky: c00 = 2√π·value
  }
  const prt::sh::WindowChoice choice = prt::sh::choose_window_auto(rgb.data(), 3, order);
  REQUIRE(choice.min_irradiance_before < 0.0);
  REQUIRE(choice.window == prt::sh::Window::Laplacian);
  REQUIRE(choice.strength > 0.0);
  REQUIRE(choice.min_irradiance_after >= 0.0);
  // Independent check on a θ–φ grid, per channel. The library's set is a different (Fibonacci)
  // set, so allow a small dip: −1e-3 of the mean irradiance π·(sky + sun power) scale ~ 1.
  const std::vector<double> h =
      prt::sh::window_band_factors(prt::sh::Window::Laplacian, order, choice.strength);
  const std::vector<double> none(order, 1.0);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> channel(rgb.begin() + c * n, rgb.begin() + (c + 1) * n);
    REQUIRE(minimum_irradiance(channel, order, none) < 0.0);
    REQUIRE(minimum_irradiance(channel, order, h) >= -1e-3);
  }
  // "Weakest": half the chosen λ must still leave negative irradiance somewhere.
  const prt::sh::WindowChoice again = prt::sh::choose_window_auto(rgb.data(), 3, order);
  REQUIRE(again.strength == choice.strength);
  const std::vector<double> weaker =
      prt::sh::window_band_factors(prt::sh::Window::Laplacian, order, choice.strength / 2);
  double weaker_min = 1e300;
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> channel(rgb.begin() + c * n, rgb.begin() + (c + 1) * n);
    weaker_min = std::fmin(weaker_min, minimum_irradiance(channel, order, weaker));
  }
  REQUIRE(weaker_min < 0.0);
}

TEST_CASE("auto window keeps already non-negative lighting unwindowed", "[sh][window]") {
  // A constant radiance 2 (irradiance 2π everywhere), and a smooth positive lobe 1 + 0.5z.
  const int order = 5, n = order * order;
  std::vector<double> c(2 * n, 0.0);
  c[0] = 2.0 * 2 * std::sqrt(kPi);
  c[n] = 2 * std::sqrt(kPi);
  c[n + 2] = 0.5 / std::sqrt(3 / (4 * kPi));
  const prt::sh::WindowChoice choice = prt::sh::choose_window_auto(c.data(), 2, order);
  REQUIRE(choice.window == prt::sh::Window::None);
  REQUIRE(choice.strength == 0.0);
  // Minimum over both channels: channel 1 at −z gives π − (2π/3)·0.5 = 2π/3 < 2π.
  REQUIRE(choice.min_irradiance_before == Approx(2 * kPi / 3).epsilon(1e-12));
  REQUIRE(choice.min_irradiance_after == choice.min_irradiance_before);
}

TEST_CASE("auto window reports lighting it cannot fix", "[sh][window]") {
  // Negative mean radiance: no window makes E ≥ 0; the result must say so.
  const int order = 4, n = order * order;
  std::vector<double> c(n, 0.0);
  c[0] = -1.0;
  c[6] = 0.3;
  const prt::sh::WindowChoice choice = prt::sh::choose_window_auto(c.data(), 1, order);
  REQUIRE(choice.min_irradiance_after < 0.0);
  REQUIRE(choice.min_irradiance_after >= choice.min_irradiance_before);
  // Degenerate input.
  const prt::sh::WindowChoice empty = prt::sh::choose_window_auto(c.data(), 0, order);
  REQUIRE(empty.window == prt::sh::Window::None);
  std::vector<double> bad(n, 0.0);
  bad[0] = std::nan("");
  const prt::sh::WindowChoice nan_choice = prt::sh::choose_window_auto(bad.data(), 1, order);
  REQUIRE(nan_choice.window == prt::sh::Window::None);
  REQUIRE(std::isnan(nan_choice.min_irradiance_before));
}

TEST_CASE("auto window reports its progress and chooses the same with or without it",
          "[sh][window]") {
  // A sun over a dim sky at order 12: the search runs over 64·144 + 6 test directions.
  const int order = 12, n = order * order;
  std::vector<double> rgb(3 * n);
  const std::vector<double> sun = sun_coefficients(order, 3.0 * kPi / 180, 2000.0, {0.0, 1.0, 0.0});
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < n; ++k) rgb[c * n + k] = sun[k];
    rgb[c * n] += 0.1 * 2 * std::sqrt(kPi);
  }
  std::uint64_t calls = 0, last_done = 0, last_total = 0;
  bool increasing = true;
  const prt::sh::WindowChoice with = prt::sh::choose_window_auto(
      rgb.data(), 3, order, [&](std::uint64_t done, std::uint64_t total) {
        increasing = increasing && done >= last_done && (last_total == 0 || total == last_total);
        last_done = done, last_total = total;
        ++calls;
      });
  const prt::sh::WindowChoice without = prt::sh::choose_window_auto(rgb.data(), 3, order);
  CHECK(increasing);
  CHECK(last_total == static_cast<std::uint64_t>(64 * n + 6));
  CHECK(last_done == last_total);  // the last call says it finished
  CHECK(calls >= last_total / 256);
  CHECK(with.window == without.window);
  CHECK(with.strength == without.strength);
  CHECK(with.min_irradiance_after == without.min_irradiance_after);
}
