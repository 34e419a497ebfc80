// half.cpp — binary16 conversion; see prt/core/half.h for the conventions.
#include "prt/core/half.h"

#include <cstring>

#include "core/cpu_features.h"
#include "core/half_inline.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {
namespace {

uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Magnitude bit patterns (sign cleared) of the float thresholds.
constexpr uint32_t kFloatInf = 0x7f800000u;
constexpr uint32_t kHalfOverflow = 0x477ff000u;   // 65520: ties to even rounds up to 2^16 = Inf
constexpr uint32_t kHalfMinNormal = 0x38800000u;  // 2^-14
constexpr uint32_t kHalfZeroLimit = 0x33000000u;  // 2^-25: at or below rounds to zero

}  // namespace

uint16_t float_to_half(float value) noexcept {
  uint32_t x = bits_of(value);
  const auto sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
  x &= 0x7fffffffu;
  if (x >= kFloatInf) {
    if (x == kFloatInf) return static_cast<uint16_t>(sign | 0x7c00u);
    return static_cast<uint16_t>(sign | 0x7e00u | ((x >> 13) & 0x3ffu));  // quiet NaN
  }
  if (x >= kHalfOverflow) return static_cast<uint16_t>(sign | 0x7c00u);
  if (x >= kHalfMinNormal) {
    // Re-bias the exponent (127 -> 15) and round the 13 dropped mantissa bits; a carry
    // correctly ripples into the exponent.
    uint32_t h = (x - 0x38000000u) >> 13;
    const uint32_t rest = x & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;
    return static_cast<uint16_t>(sign | h);
  }
  if (x <= kHalfZeroLimit) return sign;  // includes float subnormals
  // Half subnormal: value / 2^-24 = m · 2^(e-126), with m the 24-bit significand.
  const uint32_t e = x >> 23;
  const uint32_t m = (x & 0x7fffffu) | 0x800000u;
  const uint32_t shift = 126u - e;  // 14 .. 24
  uint32_t h = m >> shift;
  const uint32_t rest = m & ((1u << shift) - 1u);
  const uint32_t half_way = 1u << (shift - 1u);
  if (rest > half_way || (rest == half_way && (h & 1u))) ++h;
  return static_cast<uint16_t>(sign | h);
}

float half_to_float(uint16_t half) noexcept {
  return detail::half_bits_to_float(half);
}

bool would_overflow_half(float value) noexcept {
  const uint32_t x = bits_of(value) & 0x7fffffffu;
  return x >= kHalfOverflow && x < kFloatInf;
}

std::size_t find_half_overflow(const float* in, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    if (would_overflow_half(in[i])) return i;
  }
  return n;
}

bool cpu_has_f16c() noexcept {
  // Asked once: CPUID traps to the hypervisor in a virtual machine (microseconds a call), and the
  // bulk conversions ask on every call (the glossy bake converts one matrix a hit).
  static const bool has = detail::cpu_supports_f16c();
  return has;
}

#if PRT_HAVE_X86_DISPATCH
namespace {

__attribute__((target("avx,f16c"))) void floats_to_halves_f16c(const float* in, std::size_t n,
                                                               uint16_t* out) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m128i h = _mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), h);
  }
  for (; i < n; ++i) out[i] = float_to_half(in[i]);
}

__attribute__((target("avx,f16c"))) void halves_to_floats_f16c(const uint16_t* in, std::size_t n,
                                                               float* out) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m128i h = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i));
    _mm256_storeu_ps(out + i, _mm256_cvtph_ps(h));
  }
  for (; i < n; ++i) out[i] = half_to_float(in[i]);
}

}  // namespace
#endif

void convert_floats_to_halves(const float* in, std::size_t n, uint16_t* out) noexcept {
#if PRT_HAVE_X86_DISPATCH
  if (cpu_has_f16c()) {
    floats_to_halves_f16c(in, n, out);
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) out[i] = float_to_half(in[i]);
}

void convert_halves_to_floats(const uint16_t* in, std::size_t n, float* out) noexcept {
#if PRT_HAVE_X86_DISPATCH
  if (cpu_has_f16c()) {
    halves_to_floats_f16c(in, n, out);
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) out[i] = half_to_float(in[i]);
}

}  // namespace prt
