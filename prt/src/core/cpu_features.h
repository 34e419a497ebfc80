// cpu_features.h (internal) — runtime CPU feature checks for the x86-64 fast paths.
// On other architectures every check is false and the portable code runs.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#endif

namespace prt::detail {

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PRT_HAVE_X86_DISPATCH 1
// F16C from CPUID leaf 1, ECX bit 29: clang (14) rejects __builtin_cpu_supports("f16c").
inline bool cpuid_has_f16c() noexcept {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  return (ecx & (1u << 29)) != 0;
}
inline bool cpu_supports_avx2_f16c_fma() noexcept {
  return __builtin_cpu_supports("avx2") && cpuid_has_f16c() && __builtin_cpu_supports("fma");
}
// AVX-512 Foundation on top of the AVX2 set (the compiler's check includes the operating
// system's saving of the 512-bit state).
inline bool cpu_supports_avx512f_avx2_f16c_fma() noexcept {
  return cpu_supports_avx2_f16c_fma() && __builtin_cpu_supports("avx512f");
}
inline bool cpu_supports_f16c() noexcept {
  return __builtin_cpu_supports("avx") && cpuid_has_f16c();
}
inline bool cpu_supports_sse42() noexcept {
  return __builtin_cpu_supports("sse4.2");
}
#else
#define PRT_HAVE_X86_DISPATCH 0
inline bool cpu_supports_avx2_f16c_fma() noexcept {
  return false;
}
inline bool cpu_supports_avx512f_avx2_f16c_fma() noexcept {
  return false;
}
inline bool cpu_supports_f16c() noexcept {
  return false;
}
inline bool cpu_supports_sse42() noexcept {
  return false;
}
#endif

}  // namespace prt::detail
