// half_inline.h (internal) — inlinable binary16 -> float used by half.cpp and the kernel.
#pragma once

#include <cstdint>
#include <cstring>

namespace prt::detail {

// Exact; signalling NaNs come back quiet (as F16C's VCVTPH2PS does).
inline float half_bits_to_float(uint16_t half) noexcept {
  const uint32_t sign = static_cast<uint32_t>(half & 0x8000u) << 16;
  const uint32_t exponent = (half >> 10) & 0x1fu;
  const uint32_t mantissa = half & 0x3ffu;
  uint32_t bits;
  if (exponent == 0) {
    // Zero or subnormal: m · 2^-24, computed exactly without float subnormals.
    const float magnitude = static_cast<float>(mantissa) * 0x1p-24f;
    std::memcpy(&bits, &magnitude, sizeof bits);
    bits |= sign;
  } else if (exponent == 31) {
    bits = sign | (mantissa == 0 ? 0x7f800000u : 0x7fc00000u | (mantissa << 13));
  } else {
    bits = sign | ((exponent + 112u) << 23) | (mantissa << 13);
  }
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace prt::detail
