#include "relight/tone_map.h"

#include <cmath>

namespace prt::relight {

float encode_srgb(float linear) noexcept {
  if (!(linear > 0.f)) return 0.f;  // also NaN
  if (linear >= 1.f) return 1.f;
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.f / 2.4f) - 0.055f;
}

float apply_aces_filmic(float x) noexcept {
  if (!(x > 0.f)) return 0.f;  // also NaN
  if (std::isinf(x)) return 1.f;
  // Evaluate in double: for large finite x the float products would overflow to Inf/Inf.
  const double xd = x;
  const double y = xd * (2.51 * xd + 0.03) / (xd * (2.43 * xd + 0.59) + 0.14);
  return y >= 1.0 ? 1.f : static_cast<float>(y);
}

float tone_map_value(float linear, float exposure_ev, ToneCurve curve) noexcept {
  if (std::isnan(linear)) return 0.f;
  const double scale =
      std::isfinite(exposure_ev) ? std::exp2(static_cast<double>(exposure_ev)) : 1.0;
  const double exposed = static_cast<double>(linear) * scale;
  const float x = exposed > 3.0e38 ? INFINITY : static_cast<float>(exposed);
  const float curved =
      curve == ToneCurve::AcesFilmic ? apply_aces_filmic(x) : (x > 1.f ? 1.f : (x > 0.f ? x : 0.f));
  return encode_srgb(curved);
}

void tone_map(const float* linear, std::size_t count, float exposure_ev, float* encoded,
              ToneCurve curve) noexcept {
  for (std::size_t i = 0; i < count; ++i)
    encoded[i] = tone_map_value(linear[i], exposure_ev, curve);
}

}  // namespace prt::relight
