// Tests of sh/constants.h: the values the header promises, bit for bit.
#include <cmath>

#include <catch2/catch.hpp>

#include "sh/constants.h"

// The decimal expansions below are independent of the header's: each must round to the same
// value, which is what makes replacing a literal by the constant bit-identical.
static_assert(prt::sh::kPi == 3.14159265358979323846, "nearest double to π");
static_assert(prt::sh::kPiFloat == 3.14159265358979323846f, "nearest float to π");
static_assert(prt::sh::kHalfPi == 1.57079632679489661923, "nearest double to π/2");
static_assert(prt::sh::kTwoPi == 6.28318530717958647693, "nearest double to 2π");
static_assert(prt::sh::kInvPi == 0.31830988618379067154, "nearest double to 1/π");
static_assert(prt::sh::kY00 == 0.28209479177387814347, "nearest double to 1/(2√π)");

TEST_CASE("the square roots are what std::sqrt gives for the double arguments", "[sh][constants]") {
  // √(4·kPi) rounds one ulp below the nearest double to √(4π) (3.5449077018110322), because
  // kPi is below π; the constant keeps the value every caller has always computed.
  CHECK(prt::sh::kSqrtFourPi == std::sqrt(4.0 * prt::sh::kPi));
  CHECK(prt::sh::kY00 == 0.5 / std::sqrt(prt::sh::kPi));
  CHECK(prt::sh::kY00 == 1.0 / prt::sh::kSqrtFourPi);
  CHECK(static_cast<double>(prt::sh::kPiLong) == prt::sh::kPi);
  CHECK(std::fabs(static_cast<double>(prt::sh::kPiLong - std::acos(-1.0L))) <= 1e-18);
}
