// Automatic exposure (relight/auto_exposure.h): the median vertex luminance brought to the key.
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "relight/auto_exposure.h"
#include "relight/tone_map.h"

using prt::relight::choose_auto_exposure;
using prt::relight::kAutoExposureKey;

namespace {

std::vector<float> grey_vertices(const std::vector<float>& values) {
  std::vector<float> rgb;
  for (float v : values) rgb.insert(rgb.end(), {v, v, v});
  return rgb;
}

}  // namespace

TEST_CASE("auto exposure brings the median vertex luminance to the key, in quarter stops") {
  // Grey radiance 4.8 = 16 × 0.3: exactly −4 EV.
  CHECK(choose_auto_exposure(grey_vertices({4.8f})) == -4.f);
  // The median of {0.1, 1.2, 1000} is 1.2 = 4 × 0.3: −2 EV, whatever the outliers.
  CHECK(choose_auto_exposure(grey_vertices({1000.f, 0.1f, 1.2f})) == -2.f);
  // 0.3 / 0.5 → log2 = −0.737 → −0.75 (nearest quarter).
  CHECK(choose_auto_exposure(grey_vertices({0.5f})) == -0.75f);
  // Luminance weights are Rec. 709's: pure green 0.3 / 0.7152 → Y = 0.3 → 0 EV.
  CHECK(choose_auto_exposure({0.f, 0.3f / 0.7152f, 0.f}) == 0.f);
}

TEST_CASE("auto exposure ignores NaN, infinite, negative and zero vertices") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(choose_auto_exposure(grey_vertices({nan, -5.f, 0.f, inf, 4.8f})) == -4.f);
  CHECK(choose_auto_exposure(grey_vertices({nan, -1.f, 0.f})) == 0.f);
  CHECK(choose_auto_exposure({}) == 0.f);
}

TEST_CASE("auto exposure puts the median vertex a little above mid grey on the PNG") {
  // Independent check through the tone mapper: after exposure, the median vertex displays as
  // tone_map(key) ≈ 0.69, within the quarter-stop rounding (±1/8 EV → ±0.03 in display value).
  const std::vector<float> values = {0.02f, 0.7f, 3.f, 9.f, 150.f};
  const float ev = choose_auto_exposure(grey_vertices(values));
  const float shown = prt::relight::tone_map_value(3.f, ev);
  CHECK(shown == Approx(prt::relight::tone_map_value(float(kAutoExposureKey), 0.f)).margin(0.03));
  CHECK(shown == Approx(0.69).margin(0.04));
}
