// numerics/constants.h — π and the constants derived from it, defined once for all of prt.
//
// This header is in prt::numerics, the lowest target (numerics → sh → prt → scene → …), so that
// every layer, the tests, benchmarks and fuzzers reach the same definitions; sh/constants.h
// re-exports them as prt::sh::kPi and friends. Header-only, C++17, no dependencies.
//
// Values: kPiLong is π to the precision of long double; kPi and kPiFloat are the nearest double
// and float to π; kHalfPi, kTwoPi and kFourPi are exact multiples of kPi (so kTwoPi * u equals
// 2.0 * kPi * u bit for bit), and kInvPi, kInvTwoPi, kInvFourPi are 1/kPi, 1/(2 kPi), 1/(4 kPi)
// correctly rounded. kOneMinusEpsilon and kOneMinusEpsilonFloat are the largest double and float
// below 1: what a uniform number in [0, 1) is clamped to. tests/sh/test_constants.cpp and
// tests/sh/test_numerics.cpp check the values bit for bit.
#pragma once

namespace prt::numerics {

inline constexpr long double kPiLong = 3.141592653589793238462643383279502884L;  // π
inline constexpr double kPi = static_cast<double>(kPiLong);                      // π
inline constexpr float kPiFloat = static_cast<float>(kPi);                       // π
inline constexpr double kHalfPi = kPi / 2;                                       // π/2
inline constexpr double kTwoPi = 2 * kPi;                                        // 2π
inline constexpr double kFourPi = 4 * kPi;                                       // 4π
inline constexpr double kInvPi = 1 / kPi;                                        // 1/π
inline constexpr double kInvTwoPi = 1 / kTwoPi;                                  // 1/(2π)
inline constexpr double kInvFourPi = 1 / kFourPi;                                // 1/(4π)
inline constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;                 // 1 − 2⁻⁵³
inline constexpr float kOneMinusEpsilonFloat = 0x1.fffffep-1f;                   // 1 − 2⁻²⁴

}  // namespace prt::numerics
