// cpu_features.h (internal) — runtime CPU feature checks for the x86-64 fast paths.
// On other architectures every check is false and the portable code runs.
#pragma once

namespace prt::detail {

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PRT_HAVE_X86_DISPATCH 1
inline bool cpu_supports_avx2_f16c_fma() noexcept {
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("f16c") &&
         __builtin_cpu_supports("fma");
}
inline bool cpu_supports_f16c() noexcept {
  return __builtin_cpu_supports("avx") && __builtin_cpu_supports("f16c");
}
inline bool cpu_supports_sse42() noexcept {
  return __builtin_cpu_supports("sse4.2");
}
#else
#define PRT_HAVE_X86_DISPATCH 0
inline bool cpu_supports_avx2_f16c_fma() noexcept {
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
