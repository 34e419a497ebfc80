// sh/constants.h — π and friends for the SH maths, and the SH normalisation constants.
//
// π and the constants derived from it are defined once, in numerics/constants.h (prt::numerics,
// the target below sh); this header makes them visible as prt::sh::kPi, kPiFloat, kPiLong,
// kHalfPi, kTwoPi and kInvPi (the same objects, not copies) and adds what is SH's own.
// std::sqrt is not constexpr in C++17, so the square roots are literals: kSqrtFourPi is
// std::sqrt(4 * kPi) (one ulp below the nearest double to √(4π)) and kY00 is 0.5 / std::sqrt(kPi).
// tests/sh/test_constants.cpp checks every value bit for bit.
#pragma once

#include "numerics/constants.h"

namespace prt::sh {

using numerics::kHalfPi;
using numerics::kInvPi;
using numerics::kPi;
using numerics::kPiFloat;
using numerics::kPiLong;
using numerics::kTwoPi;
inline constexpr double kSqrtFourPi = 3.5449077018110318;  // √(4π)
// Y00 = 1/√(4π) = 1/(2√π), the constant SH basis function; a constant radiance c projects to
// the single coefficient c·√(4π).
inline constexpr double kY00 = 0.28209479177387814;

}  // namespace prt::sh
