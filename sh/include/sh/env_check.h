// sh/env_check.h — what every command (and sh::project) does with an environment map that is
// not a clean radiance map: texels that are not finite non-negative RGB, and a map too coarse
// for the SH order asked of it. docs/CONVENTIONS.md, "Environment maps that are not clean",
// states the policy for users.
//
// Texel policy (screen_texel), one rule for every path:
//   * a texel with a NaN in any channel, or else ±Inf in any channel, is INVALID: it contributes
//     nothing (all three channels are taken as 0) and is counted;
//   * otherwise a negative channel is CLAMPED to 0, each channel on its own (the others keep
//     their value), and the texel is counted as clamped. (Skipping such a texel whole, as
//     before, turned a map whose every texel had one slightly negative channel into zeros.)
// A map is refused when invalid texels cover more than kMaxInvalidSolidAngleFraction of the
// sphere's 4π (it is not a radiance map); fewer are allowed with a warning.
//
// Resolution: a map with C texels around a great circle (lat-long: W; angular: W; cross:
// 4·W/3; faces: 4·W) samples band l with C/l texels per period, so it resolves bands up to
// about l = C/2 (two texels per period). Order n asks for l = n − 1:
//   l ≤ C/2       fine;
//   C/2 < l ≤ C   aliasing: warned (the top bands hold sampling noise);
//   l > C         far too small: refused (fewer texels than periods).
//
// Standard library only.
#pragma once

#include <cmath>
#include <cstddef>

#include "sh/env_map.h"

namespace prt::sh {

enum class TexelClass { Good, NaN, Inf, Negative };

// Applies the texel policy to rgb[0..2]: writes the radiance to use into out[0..2] (zeros for
// an invalid texel, negative channels clamped to 0) and returns the class (NaN wins over Inf,
// Inf over Negative). `out` may alias `rgb`.
inline TexelClass screen_texel(const float* rgb, float* out) noexcept {
  TexelClass kind = TexelClass::Good;
  for (int c = 0; c < 3; ++c) {
    if (std::isnan(rgb[c]))
      kind = TexelClass::NaN;
    else if (std::isinf(rgb[c]) && kind != TexelClass::NaN)
      kind = TexelClass::Inf;
    else if (rgb[c] < 0.0f && kind == TexelClass::Good)
      kind = TexelClass::Negative;
  }
  const bool invalid = kind == TexelClass::NaN || kind == TexelClass::Inf;
  for (int c = 0; c < 3; ++c) out[c] = invalid || rgb[c] < 0.0f ? 0.0f : rgb[c];
  return kind;
}

// More invalid solid angle than this fraction of 4π: the map is refused.
inline constexpr double kMaxInvalidSolidAngleFraction = 0.5;

// What screen_env_map found, over the texels on the sphere only.
struct EnvTexelReport {
  std::size_t nan_texels = 0, inf_texels = 0;  // invalid: now zero
  std::size_t negative_texels = 0;             // a negative channel, now clamped to 0
  double invalid_solid_angle = 0;              // sr covered by NaN/Inf texels
  bool all_black = true;                       // after screening, every texel is 0 in every channel

  std::size_t invalid_texels() const { return nan_texels + inf_texels; }
  double invalid_fraction() const;  // invalid_solid_angle / 4π
};

// Applies screen_texel to every texel of `env` in place (texels off the sphere are set to 0
// too) and reports what it changed. The layout must be valid for the size.
EnvTexelReport screen_env_map(EnvMap* env);

// Texels along a great circle, C above.
int great_circle_texels(const EnvMap& env) noexcept;

// The highest band the map resolves, C/2 (at least 0).
int resolved_band(const EnvMap& env) noexcept;

enum class OrderFit { Fine, Aliasing, FarTooSmall };

// How order `order` (bands 0..order−1) fits the map's resolution, as above.
OrderFit order_fit(const EnvMap& env, int order) noexcept;

}  // namespace prt::sh
