// Tests of prt/core/half.h: exhaustive round trip, known values, an independent rounding model.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/core/half.h"

namespace {

uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// Independent model of round-to-nearest-even into binary16, in double arithmetic:
// the spacing of halves near |x| is 2^(e−10) with e = max(floor(log2|x|), −14).
double round_to_half_model(float xf) {
  const double x = xf;
  if (x == 0.0) return x;
  int e = std::ilogb(x);
  if (e < -14) e = -14;
  const double ulp = std::ldexp(1.0, e - 10);
  const double q = std::nearbyint(x / ulp) * ulp;  // default rounding mode: ties to even
  if (std::abs(q) > 65504.0) return std::copysign(std::numeric_limits<double>::infinity(), x);
  return q;
}

}  // namespace

TEST_CASE("every half survives half -> float -> half", "[half]") {
  for (uint32_t h = 0; h < 65536; ++h) {
    const auto half = static_cast<uint16_t>(h);
    const float f = prt::half_to_float(half);
    const bool is_nan = (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu) != 0;
    if (is_nan) {
      REQUIRE(std::isnan(f));
      const uint16_t back = prt::float_to_half(f);
      // NaN stays NaN with its sign; the quiet bit is set.
      REQUIRE((back & 0x7c00u) == 0x7c00u);
      REQUIRE((back & 0x3ffu) != 0);
      REQUIRE((back & 0x8000u) == (h & 0x8000u));
    } else {
      REQUIRE(prt::float_to_half(f) == half);
    }
  }
}

TEST_CASE("half conversion matches known values", "[half]") {
  CHECK(prt::float_to_half(1.0f) == 0x3c00);
  CHECK(prt::float_to_half(-2.0f) == 0xc000);
  CHECK(prt::float_to_half(0.0f) == 0x0000);
  CHECK(prt::float_to_half(-0.0f) == 0x8000);
  CHECK(prt::float_to_half(0.1f) == 0x2e66);
  CHECK(prt::float_to_half(65504.0f) == 0x7bff);
  CHECK(prt::float_to_half(65519.99f) == 0x7bff);  // below the midpoint 65520
  CHECK(prt::float_to_half(65520.0f) == 0x7c00);   // tie, rounds to even = 2^16 = Inf
  CHECK(prt::float_to_half(1e10f) == 0x7c00);
  CHECK(prt::float_to_half(-std::numeric_limits<float>::infinity()) == 0xfc00);
  CHECK(prt::float_to_half(0x1p-14f) == 0x0400);             // smallest normal
  CHECK(prt::float_to_half(0x1p-24f) == 0x0001);             // smallest subnormal
  CHECK(prt::float_to_half(0x1p-25f) == 0x0000);             // tie with 0: even is 0
  CHECK(prt::float_to_half(0x1.0002p-25f) == 0x0001);        // just above the tie
  CHECK(prt::float_to_half(3.0f * 0x1p-25f) == 0x0002);      // tie between 1 and 2 ulps: 2
  CHECK(prt::float_to_half(1.0f + 0x1p-11f) == 0x3c00);      // tie: even mantissa 0
  CHECK(prt::float_to_half(1.0f + 3 * 0x1p-11f) == 0x3c02);  // tie: even mantissa 2
  CHECK(prt::float_to_half(0x1.ff8p-15f) == 0x03ff);         // largest subnormal, 1023·2^-24
  CHECK(prt::float_to_half(0x1.ffap-15f) == 0x03ff);         // below the midpoint
  CHECK(prt::float_to_half(0x1.ffcp-15f) == 0x0400);         // tie: even is the smallest normal
  CHECK(prt::float_to_half(1e-30f) == 0x0000);               // far below: zero
  CHECK(prt::float_to_half(std::numeric_limits<float>::denorm_min()) == 0x0000);
  const uint16_t nan = prt::float_to_half(std::numeric_limits<float>::quiet_NaN());
  CHECK((nan & 0x7c00) == 0x7c00);
  CHECK((nan & 0x3ff) != 0);
  CHECK(prt::half_to_float(0x3555) == Approx(0.33325195).epsilon(1e-7));
  CHECK(prt::half_to_float(0x0001) == 0x1p-24f);
  CHECK(prt::half_to_float(0x7bff) == 65504.0f);
  CHECK(std::isinf(prt::half_to_float(0x7c00)));
}

TEST_CASE("float -> half equals an independent rounding model", "[half]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> any_bits;
  std::vector<float> values;
  // Random bit patterns in the half range (exponent 2^-26 .. 2^16) and around ties.
  for (int i = 0; i < 200000; ++i) {
    uint32_t u = any_bits(rng);
    const uint32_t exponent = 101 + (u % 42);  // 2^-26 .. 2^15
    u = (u & 0x807fffffu) | (exponent << 23);
    if (i % 4 == 0) u = (u & ~0x1fffu) | 0x1000u;  // an exact tie for normals
    float f;
    std::memcpy(&f, &u, 4);
    values.push_back(f);
  }
  for (float f : values) {
    const double model = round_to_half_model(f);
    const float got = prt::half_to_float(prt::float_to_half(f));
    INFO("input " << f << " bits " << std::hex << bits_of(f));
    REQUIRE(static_cast<double>(got) == model);
    // The relative round-off bound of normal halves.
    if (std::abs(f) >= 0x1p-14f && std::isfinite(got)) {
      REQUIRE(std::abs(static_cast<double>(got) - f) <= 0x1p-11 * std::abs(f));
    }
  }
}

TEST_CASE("bulk conversions equal the scalar ones bit for bit", "[half]") {
  std::vector<uint16_t> halves(65536);
  for (uint32_t h = 0; h < 65536; ++h) halves[h] = static_cast<uint16_t>(h);
  std::vector<float> floats(halves.size());
  prt::convert_halves_to_floats(halves.data(), halves.size(), floats.data());
  for (uint32_t h = 0; h < 65536; ++h) {
    INFO("half 0x" << std::hex << h);
    REQUIRE(bits_of(floats[h]) == bits_of(prt::half_to_float(halves[h])));
  }
  std::mt19937 rng(3);
  std::uniform_int_distribution<uint32_t> any_bits;
  std::vector<float> in(100003);  // not a multiple of 8: the tail path runs too
  for (float& f : in) {
    const uint32_t u = any_bits(rng);
    std::memcpy(&f, &u, 4);
  }
  std::vector<uint16_t> out(in.size());
  prt::convert_floats_to_halves(in.data(), in.size(), out.data());
  for (std::size_t i = 0; i < in.size(); ++i) {
    INFO("float bits 0x" << std::hex << bits_of(in[i]));
    REQUIRE(out[i] == prt::float_to_half(in[i]));
  }
  INFO("F16C in use: " << prt::cpu_has_f16c());
}

TEST_CASE("half overflow is detected before storing", "[half]") {
  CHECK_FALSE(prt::would_overflow_half(65504.0f));
  CHECK_FALSE(prt::would_overflow_half(65519.0f));  // rounds down to 65504
  CHECK(prt::would_overflow_half(65520.0f));
  CHECK(prt::would_overflow_half(-70000.0f));
  CHECK_FALSE(prt::would_overflow_half(std::numeric_limits<float>::infinity()));  // not finite
  const float values[] = {1.0f, -3.0f, 65504.0f, 70000.0f, 2.0f};
  CHECK(prt::find_half_overflow(values, 5) == 3);
  CHECK(prt::find_half_overflow(values, 3) == 3);  // none in the first three: returns n
}
