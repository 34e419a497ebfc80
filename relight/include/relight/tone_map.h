// relight/tone_map.h — linear radiance → display-encoded [0, 1] values for PNG output.
//
// Pipeline per channel (EXR output skips all of this and stays linear):
//   1. exposure: x · 2^EV;
//   2. a filmic curve, Narkowicz's fit of the ACES reference rendering transform
//      ("ACES Filmic Tone Mapping Curve", K. Narkowicz, 2015):
//        f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0, 1].
//      Its derivative's numerator is 1.408x² + 0.7028x + 0.0042 > 0 for x ≥ 0, so it is
//      monotonic; f(0) = 0; it reaches 1 near x ≈ 11 (scene-referred highlights roll off).
//      The curve is applied per channel (as in the original fit), not to luminance.
//   3. the sRGB OETF (IEC 61966-2-1): 12.92x below 0.0031308, else 1.055x^(1/2.4) − 0.055.
// NaN and negative values map to 0, +Inf to 1: the output is always a finite value in [0, 1].
// References: [20] of docs/REFERENCES.md.
#pragma once

#include <cstddef>

namespace prt::relight {

enum class ToneCurve {
  AcesFilmic,  // Narkowicz 2015 (default)
  Clamp,       // no curve: exposure, clamp to [0, 1], sRGB (for exact colour checks)
};

// The sRGB OETF on [0, 1] (inputs outside are clamped; NaN → 0).
float encode_srgb(float linear) noexcept;

// Narkowicz's ACES fit on [0, ∞), clamped to [0, 1] (NaN or negative → 0, +Inf → 1).
float apply_aces_filmic(float x) noexcept;

// One channel through exposure, curve and sRGB.
float tone_map_value(float linear, float exposure_ev,
                     ToneCurve curve = ToneCurve::AcesFilmic) noexcept;

// `count` floats (e.g. 3 per pixel) from `linear` to `encoded`; the two may alias.
void tone_map(const float* linear, std::size_t count, float exposure_ev, float* encoded,
              ToneCurve curve = ToneCurve::AcesFilmic) noexcept;

}  // namespace prt::relight
