// sh/constants.h — π and the constants derived from it, defined once for all of prt.
//
// This header is in prt::sh, the lowest layer (sh → prt → bake → relight → cli), because the
// SH maths itself needs π and sh may not include anything from the layers above it. Every
// other layer, the tests, benchmarks and fuzzers reach it through their dependency on prt::sh,
// so each constant has exactly one definition. Header-only, C++17, no dependencies.
//
// Values: kPiLong is π to the precision of long double; kPi and kPiFloat are the nearest double
// and float to π, kHalfPi and kTwoPi are exact multiples of kPi, and kInvPi is 1/kPi correctly
// rounded (each is also the nearest double to the exact number). std::sqrt is not constexpr in
// C++17, so the square roots are literals: kSqrtFourPi is std::sqrt(4 * kPi) (one ulp below the
// nearest double to √(4π)) and kY00 is 0.5 / std::sqrt(kPi). tests/sh/test_constants.cpp
// checks every value bit for bit.
#pragma once

namespace prt::sh {

inline constexpr long double kPiLong = 3.141592653589793238462643383279502884L;  // π
inline constexpr double kPi = static_cast<double>(kPiLong);                      // π
inline constexpr float kPiFloat = static_cast<float>(kPi);                       // π
inline constexpr double kHalfPi = kPi / 2;                                       // π/2
inline constexpr double kTwoPi = 2 * kPi;                                        // 2π
inline constexpr double kInvPi = 1 / kPi;                                        // 1/π
inline constexpr double kSqrtFourPi = 3.5449077018110318;                        // √(4π)
// Y00 = 1/√(4π) = 1/(2√π), the constant SH basis function; a constant radiance c projects to
// the single coefficient c·√(4π).
inline constexpr double kY00 = 0.28209479177387814;

}  // namespace prt::sh
