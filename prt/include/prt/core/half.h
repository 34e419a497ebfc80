// prt/core/half.h — IEEE 754 binary16 ("half", float16) <-> binary32 conversion.
//
// Conventions: binary16 has 1 sign bit, 5 exponent bits (bias 15) and 10 mantissa bits.
// The largest finite half is 65504; the smallest normal is 2^-14, the smallest subnormal
// 2^-24. float -> half rounds to nearest, ties to even (IEEE 754-2008 §4.3.1), exactly as
// the F16C instruction VCVTPS2PH with imm8 = 0 does:
//   * finite values whose rounded magnitude exceeds 65504 (|x| >= 65520) become ±Inf;
//     use would_overflow_half() / find_half_overflow() to detect this before storing;
//   * results below 2^-14 are correctly rounded subnormals; below 2^-25 (or exactly 2^-25,
//     the tie) they become ±0;
//   * NaN stays NaN (quiet bit set, top payload bits kept), ±Inf stays ±Inf.
// half -> float is exact (every half is a float); signalling NaNs come back quiet.
// The relative rounding error of a normal half is at most 2^-11.
// The bulk functions use F16C when the CPU has it (runtime dispatch) and give bit-identical
// results to the scalar functions. Thread-safe; no allocation. Compiles as C++17.
// References: [22] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <cstdint>

namespace prt {

inline constexpr float kHalfMax = 65504.0f;

// One value, round to nearest even.
uint16_t float_to_half(float value) noexcept;
// One value, exact.
float half_to_float(uint16_t half) noexcept;

// True when `value` is finite but rounds to ±Inf in binary16.
bool would_overflow_half(float value) noexcept;

// Index of the first finite value in in[0 .. n) that would overflow to ±Inf, or n if none.
std::size_t find_half_overflow(const float* in, std::size_t n) noexcept;

// Bulk conversions (in and out must not overlap).
void convert_floats_to_halves(const float* in, std::size_t n, uint16_t* out) noexcept;
void convert_halves_to_floats(const uint16_t* in, std::size_t n, float* out) noexcept;

// Whether the bulk conversions (and the relighting kernel) use F16C on this CPU.
bool cpu_has_f16c() noexcept;

}  // namespace prt
