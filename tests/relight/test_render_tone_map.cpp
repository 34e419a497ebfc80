// Tone mapping (relight/tone_map.h).
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "relight/tone_map.h"

using prt::relight::ToneCurve;

namespace {
// The sRGB EOTF (decoding), IEC 61966-2-1 — the inverse of what the code implements, so the
// round trip checks the encoder with an independent formula.
double decode_srgb(double s) {
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}
}  // namespace

TEST_CASE("sRGB encoding of known values and round trip with the standard's decoder") {
  CHECK(prt::relight::encode_srgb(0.f) == 0.f);
  CHECK(prt::relight::encode_srgb(1.f) == 1.f);
  // 50% sRGB grey is linear 0.214041 (published value); float pow: 1e-5.
  CHECK(prt::relight::encode_srgb(0.214041f) == Approx(0.5).margin(1e-5));
  // Linear 0.18 (photographic middle grey) encodes to 0.4614 (118/255 in 8 bits).
  CHECK(std::lround(255.0 * prt::relight::encode_srgb(0.18f)) == 118);
  // Both sides of the breakpoint: the standard's piecewise curve is continuous to ~1e-7 there.
  CHECK(prt::relight::encode_srgb(0.0031308f) == Approx(0.0404500).margin(1e-6));
  CHECK(prt::relight::encode_srgb(0.0031309f) == Approx(0.0404512).margin(1e-6));
  for (int i = 0; i <= 255; ++i) {
    const double s = i / 255.0;
    // float evaluation of pow; 2e-6 covers it.
    CHECK(prt::relight::encode_srgb(static_cast<float>(decode_srgb(s))) == Approx(s).margin(2e-6));
  }
}

TEST_CASE("tone mapping: 0 maps to 0, monotonic, bounded, NaN/Inf safe") {
  CHECK(prt::relight::tone_map_value(0.f, 0.f) == 0.f);
  CHECK(prt::relight::apply_aces_filmic(0.f) == 0.f);
  // Narkowicz's curve at x = 1: (2.51 + 0.03) / (2.43 + 0.59 + 0.14) = 2.54 / 3.16.
  CHECK(prt::relight::apply_aces_filmic(1.f) == Approx(2.54 / 3.16).epsilon(1e-6));
  float previous = 0.f;
  for (double x = 1e-8; x < 1e12; x *= 1.01) {
    const float y = prt::relight::tone_map_value(static_cast<float>(x), 0.f);
    CHECK(y >= previous);
    CHECK(y <= 1.f);
    previous = y;
  }
  CHECK(previous == 1.f);  // highlights saturate to white
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(prt::relight::tone_map_value(nan, 0.f) == 0.f);
  CHECK(prt::relight::tone_map_value(inf, 0.f) == 1.f);
  CHECK(prt::relight::tone_map_value(-inf, 0.f) == 0.f);
  CHECK(prt::relight::tone_map_value(-3.f, 0.f) == 0.f);
  CHECK(prt::relight::tone_map_value(3e38f, 10.f) == 1.f);  // exposure overflow stays finite
  CHECK(prt::relight::tone_map_value(1.f, nan) == prt::relight::tone_map_value(1.f, 0.f));
}

TEST_CASE("exposure multiplies by 2^EV before the curve") {
  for (float x : {0.01f, 0.2f, 1.f, 5.f}) {
    CHECK(prt::relight::tone_map_value(x, 1.f) == Approx(prt::relight::tone_map_value(2 * x, 0.f)));
    CHECK(prt::relight::tone_map_value(x, -2.f) ==
          Approx(prt::relight::tone_map_value(x / 4, 0.f)));
  }
  // With the plain clamp curve, exposure then sRGB: 0.25 · 2² = 1 → white; 0.1 · 2 → sRGB(0.2).
  CHECK(prt::relight::tone_map_value(0.25f, 2.f, ToneCurve::Clamp) == 1.f);
  CHECK(prt::relight::tone_map_value(0.1f, 1.f, ToneCurve::Clamp) ==
        Approx(1.055 * std::pow(0.2, 1 / 2.4) - 0.055).margin(1e-6));
  float buffer[4] = {0.f, 0.5f, 2.f, -1.f};
  prt::relight::tone_map(buffer, 4, 0.f, buffer);  // in place
  CHECK(buffer[0] == 0.f);
  CHECK(buffer[1] > 0.f);
  CHECK(buffer[2] > buffer[1]);
  CHECK(buffer[3] == 0.f);
}
