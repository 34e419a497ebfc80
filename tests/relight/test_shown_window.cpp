// tests/relight/test_shown_window.cpp — the automatic window chosen on shaded vertices
// (relight/shown_window.h), on band sums whose answer is known in closed form.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "relight/shown_window.h"
#include "sh/window.h"

namespace {

using prt::relight::ShownWindowChoice;
using prt::relight::ShownWindowSearch;

// Band sums for vertices whose three channels are equal: s[(v·3 + c)·order + l].
std::vector<float> grey_bands(const std::vector<std::vector<float>>& per_vertex) {
  std::vector<float> bands;
  for (const std::vector<float>& s : per_vertex)
    for (int c = 0; c < 3; ++c) bands.insert(bands.end(), s.begin(), s.end());
  return bands;
}

double windowed(const std::vector<float>& s, double lambda) {
  const std::vector<double> h =
      prt::sh::window_band_factors(prt::sh::Window::Laplacian, int(s.size()), lambda);
  double sum = 0.0;
  for (std::size_t l = 0; l < s.size(); ++l) sum += h[l] * s[l];
  return sum;
}

}  // namespace

TEST_CASE("shown window: none when every vertex is non-negative") {
  ShownWindowSearch search(3);
  search.add_view_bands(grey_bands({{1.f, 0.5f, -0.4f}, {0.f, 0.f, 0.f}}), 2);
  const ShownWindowChoice choice = search.choose();
  CHECK(choice.window == prt::sh::Window::None);
  CHECK(choice.negative_before == 0);
  CHECK(choice.negative_after == 0);
  CHECK(choice.unremovable == 0);
  CHECK(choice.vertices == 2);
  CHECK(choice.views == 1);
}

TEST_CASE("shown window: the weakest candidate that lifts a ringing vertex to zero") {
  // s = (1, 0, -3): B(λ) = 1 − 3/(1 + 36λ) ≥ 0 from λ = 1/18 on. The chosen λ must pass and
  // the candidate before it (λ/2^(1/4)) must not: the search is the weakest on its ladder.
  const std::vector<float> s{1.f, 0.f, -3.f};
  ShownWindowSearch search(3);
  search.add_view_bands(grey_bands({s, {2.f, 1.f, 0.5f}}), 2);
  const ShownWindowChoice choice = search.choose();
  REQUIRE(choice.window == prt::sh::Window::Laplacian);
  CHECK(choice.strength >= 1.0 / 18.0);
  CHECK(windowed(s, choice.strength) >= 0.0);
  CHECK(windowed(s, choice.strength / std::exp2(0.25)) < 0.0);
  CHECK(choice.negative_before == 1);
  CHECK(choice.negative_after == 0);
  CHECK(choice.unremovable == 0);
}

TEST_CASE("shown window: views combine by their worst, unremovable vertices are counted apart") {
  ShownWindowSearch search(3);
  // View 1 needs λ ≥ 1/18; view 2 needs more: s = (1, 0, -10) needs λ ≥ 1/4.
  search.add_view_bands(grey_bands({{1.f, 0.f, -3.f}, {1.f, 0.f, 0.f}}), 2);
  search.add_view_bands(grey_bands({{1.f, 0.f, 0.f}, {1.f, 0.f, -10.f}}), 2);
  ShownWindowChoice choice = search.choose();
  CHECK(choice.strength >= 0.25);
  CHECK(choice.views == 2);
  CHECK(choice.negative_before == 1);
  // A third view whose vertex is negative under the lighting's mean alone (s_0 < 0): no window
  // removes it; it is counted, and it does not push the choice to the strongest window.
  search.add_view_bands(grey_bands({{-0.1f, 0.f, 0.05f}, {1.f, 0.f, 0.f}}), 2);
  choice = search.choose();
  CHECK(choice.unremovable == 1);
  CHECK(choice.negative_after == 1);
  CHECK(choice.strength >= 0.25);
  CHECK(choice.strength < 1.0);
  CHECK(prt::relight::describe_shown_window(choice).find("1 in a view") != std::string::npos);
  CHECK_THROWS(search.add_view_bands(std::vector<float>(5), 2));
}

TEST_CASE("shown window: order 1 has nothing to window") {
  ShownWindowSearch search(1);
  REQUIRE(search.strengths().size() == 1);
  search.add_view_bands(grey_bands({{-1.f}}), 1);
  const ShownWindowChoice choice = search.choose();
  CHECK(choice.window == prt::sh::Window::None);
  CHECK(choice.unremovable == 1);
  CHECK(choice.negative_after == 1);
}

TEST_CASE("shown window: counts over many vertices (ranges counted apart) add up exactly") {
  // 100,003 vertices (several of the search's ranges, the last one partial): every 1000th rings
  // as (1, 0, −3) (λ ≥ 1/18 lifts it), every 7001st is negative under the mean alone.
  const std::size_t n = 100003;
  std::vector<std::vector<float>> per_vertex(n, {2.f, 1.f, 0.5f});
  std::size_t ringing = 0, intrinsic = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (v % 7001 == 3) {
      per_vertex[v] = {-0.1f, 0.f, 0.05f};
      ++intrinsic;
    } else if (v % 1000 == 999) {
      per_vertex[v] = {1.f, 0.f, -3.f};
      ++ringing;
    }
  }
  ShownWindowSearch search(3);
  search.add_view_bands(grey_bands(per_vertex), n);
  const ShownWindowChoice choice = search.choose();
  CHECK(choice.vertices == n);
  CHECK(choice.negative_before == ringing + intrinsic);
  CHECK(choice.unremovable == intrinsic);
  CHECK(choice.negative_after == intrinsic);
  CHECK(choice.strength >= 1.0 / 18.0);
  CHECK(choice.strength < 0.25);
}
