// Tests of prt/diffuse/relighter.h: the blocked kernel against the double vertex-major reference,
// order rules, the AVX2 path against the portable one, sRGB output, and an analytic case.
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "lighting_fixtures.h"
#include "prt/core/half.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/transfer_file.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "transfer_fixtures.h"

using prt::KernelPath;
using prt::Precision;
using prt::Relighter;
using prt::ShLighting;
using prt::TransferData;
using prt::sh::kPi;

namespace {

using prt::test::random_lighting;

// The data as the kernel stores it: binary16 storage rounds every coefficient.
TransferData as_stored(TransferData d, Precision storage) {
  if (storage == Precision::F16) {
    for (float& x : d.coefficients) x = prt::half_to_float(prt::float_to_half(x));
  }
  return d;
}

// Σ_k |T_k L_k| for output channel c of vertex v: the scale of the float rounding error.
double magnitude(const TransferData& d, const ShLighting& light, std::size_t v, int c) {
  const int order = std::min<int>(d.order, light.order());
  const std::size_t tc = d.channels == 1 ? 0 : c;
  const float* t = d.coefficients.data() + (v * d.channels + tc) * d.order * d.order;
  double sum = 0;
  for (int k = 0; k < order * order; ++k) sum += std::abs(t[k] * light.coefficients_double(c)[k]);
  return sum;
}

// Shades [first, first + count) and compares every value with shade_reference.
void require_matches_reference(const Relighter& r, const TransferData& stored,
                               const ShLighting& light, std::size_t first, std::size_t count,
                               KernelPath path) {
  std::vector<float> out(3 * count + 3, -12345.0f);
  const prt::Status s = r.shade_using(path, light, first, count, out.data());
  REQUIRE(s.ok());
  const int k_used =
      std::min<int>(stored.order, light.order()) * std::min<int>(stored.order, light.order());
  for (std::size_t i = 0; i < count; ++i) {
    double ref[3];
    REQUIRE(prt::shade_reference(stored, light, first + i, ref).ok());
    for (int c = 0; c < 3; ++c) {
      // Float accumulation of k_used products plus the float rounding of L: each term carries
      // at most (k_used + 2) units of 2^-24 relative to Σ|T L| (Higham, Thm 3.1); we allow 2×.
      const double tolerance = (k_used + 2) * 0x1p-23 * magnitude(stored, light, first + i, c);
      INFO("vertex " << first + i << " channel " << c);
      REQUIRE(std::abs(out[3 * i + c] - ref[c]) <= tolerance + 1e-30);
    }
  }
  // Nothing written past the range.
  REQUIRE(out[3 * count] == -12345.0f);
}

}  // namespace

TEST_CASE("shade equals the double reference for f32/f16, 1/3 channels, odd ranges",
          "[relighter]") {
  for (Precision storage : {Precision::F32, Precision::F16}) {
    for (uint32_t channels : {1u, 3u}) {
      const TransferData d = prt::test::make_transfer_data(100, 4, channels, storage, 21);
      const auto r = Relighter::create(d);
      REQUIRE(r.ok());
      CHECK(r->vertex_count() == 100);
      CHECK(r->order() == 4);
      CHECK(r->channels() == static_cast<int>(channels));
      CHECK(r->storage() == storage);
      const TransferData stored = as_stored(d, storage);
      const ShLighting light = random_lighting(4, 5);
      for (KernelPath path : {KernelPath::Portable, KernelPath::Auto}) {
        const std::size_t ranges[][2] = {{0, 100}, {5, 37},  {17, 1}, {31, 33},
                                         {99, 1},  {16, 16}, {0, 0},  {100, 0}};
        for (const auto& range : ranges) {
          INFO("storage " << int(storage) << " channels " << channels << " range " << range[0]
                          << "+" << range[1]);
          require_matches_reference(*r, stored, light, range[0], range[1], path);
        }
      }
    }
  }
}

TEST_CASE("a relighter from file bytes equals one from TransferData", "[relighter]") {
  for (Precision storage : {Precision::F32, Precision::F16}) {
    const TransferData d = prt::test::make_transfer_data(45, 3, 3, storage, 2);
    const auto bytes = prt::encode_transfer_file(d, "mem");
    REQUIRE(bytes.ok());
    const auto from_bytes = Relighter::from_file_bytes(bytes->data(), bytes->size(), "mem");
    const auto from_data = Relighter::create(d);
    REQUIRE(from_bytes.ok());
    REQUIRE(from_data.ok());
    const ShLighting light = random_lighting(3, 8);
    std::vector<float> a(3 * 45), b(3 * 45);
    REQUIRE(from_bytes->shade(light, 0, 45, a.data()).ok());
    REQUIRE(from_data->shade(light, 0, 45, b.data()).ok());
    REQUIRE(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
  }
}

TEST_CASE("lighting of lower order is zero-extended, higher order truncated", "[relighter]") {
  const TransferData d = prt::test::make_transfer_data(40, 4, 3, Precision::F32, 13);
  const auto r = Relighter::create(d);
  REQUIRE(r.ok());
  // Lower order (2): only the first 4 coefficients of the file count; compare with the
  // reference and with a lighting of order 4 whose bands 2, 3 are zero (must be identical).
  const ShLighting low = random_lighting(2, 3);
  require_matches_reference(*r, d, low, 0, 40, KernelPath::Auto);
  std::vector<float> padded(3 * 16, 0.0f);
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 4; ++k) padded[c * 16 + k] = low.coefficients(c)[k];
  }
  const auto low_padded = ShLighting::from_coefficients(4, padded.data());
  REQUIRE(low_padded.ok());
  std::vector<float> a(120), b(120);
  REQUIRE(r->shade(low, 0, 40, a.data()).ok());
  REQUIRE(r->shade(*low_padded, 0, 40, b.data()).ok());
  // The padded bands add t·0 = ±0 to the float sums, which changes nothing: identical bits.
  REQUIRE(a == b);
  // Higher order (6): the bands the file lacks are ignored, exactly.
  const ShLighting high = random_lighting(6, 4);
  std::vector<float> truncated(3 * 16);
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 16; ++k) truncated[c * 16 + k] = high.coefficients(c)[k];
  }
  const auto high_truncated = ShLighting::from_coefficients(4, truncated.data());
  REQUIRE(high_truncated.ok());
  REQUIRE(r->shade(high, 0, 40, a.data()).ok());
  REQUIRE(r->shade(*high_truncated, 0, 40, b.data()).ok());
  REQUIRE(a == b);
  require_matches_reference(*r, d, high, 3, 30, KernelPath::Auto);
}

TEST_CASE("the AVX2 path equals the portable path bit for bit", "[relighter]") {
  if (!Relighter::avx2_path_available()) {
    WARN("skipping: this CPU has no AVX2/F16C/FMA");
    return;
  }
  for (Precision storage : {Precision::F32, Precision::F16}) {
    for (uint32_t channels : {1u, 3u}) {
      const TransferData d = prt::test::make_transfer_data(333, 5, channels, storage, 17);
      const auto r = Relighter::create(d);
      REQUIRE(r.ok());
      for (int light_order : {3, 5, 7}) {
        const ShLighting light = random_lighting(light_order, 9);
        std::vector<float> a(3 * 333), b(3 * 333);
        REQUIRE(r->shade_using(KernelPath::Portable, light, 0, 333, a.data()).ok());
        REQUIRE(r->shade_using(KernelPath::Avx2, light, 0, 333, b.data()).ok());
        INFO("storage " << int(storage) << " channels " << channels << " order " << light_order);
        REQUIRE(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
      }
    }
  }
}

TEST_CASE("shading from several threads gives the single-thread result", "[relighter]") {
  const TransferData d = prt::test::make_transfer_data(1000, 3, 3, Precision::F16, 23);
  const auto r = Relighter::create(d);
  REQUIRE(r.ok());
  const ShLighting light = random_lighting(3, 1);
  std::vector<float> whole(3000), split(3000);
  REQUIRE(r->shade(light, 0, 1000, whole.data()).ok());
  bool ok_a = false, ok_b = false;
  std::thread a([&] { ok_a = r->shade(light, 0, 488, split.data()).ok(); });
  std::thread b([&] { ok_b = r->shade(light, 488, 512, split.data() + 3 * 488).ok(); });
  a.join();
  b.join();
  REQUIRE(ok_a);
  REQUIRE(ok_b);
  REQUIRE(whole == split);
}

TEST_CASE("unshadowed diffuse transfer under a constant sky gives albedo x radiance",
          "[relighter]") {
  // Analytic (Ramamoorthi & Hanrahan 2001): T_lm = ρ/π · A_l · Y_lm(n) with A_0 = π,
  // A_1 = 2π/3, A_2 = π/4, and a sky of constant radiance c has L_00 = √(4π)·c, so
  // B = ρ/π · π · Y_00 · √(4π) c = ρ c for any n.
  const double rho[3] = {0.8, 0.5, 0.2}, sky[3] = {1.5, 2.0, 4.0};
  const double a_l[3] = {kPi, 2 * kPi / 3, kPi / 4};
  TransferData d;
  d.order = 3;
  d.channels = 3;
  d.vertex_count = 20;
  std::mt19937 rng(2);
  std::normal_distribution<double> gauss;
  for (std::size_t v = 0; v < 20; ++v) {
    double n[3] = {gauss(rng), gauss(rng), gauss(rng)};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double y[9];
    prt::sh::evaluate(3, n[0] / len, n[1] / len, n[2] / len, y);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 9; ++k) {
        const int l = k < 1 ? 0 : (k < 4 ? 1 : 2);
        d.coefficients.push_back(static_cast<float>(rho[c] / kPi * a_l[l] * y[k]));
      }
    }
  }
  std::vector<double> l(27, 0.0);
  for (int c = 0; c < 3; ++c) l[c * 9] = std::sqrt(4 * kPi) * sky[c];
  const auto light = ShLighting::from_coefficients(3, l.data());
  REQUIRE(light.ok());
  const auto r = Relighter::create(d);
  REQUIRE(r.ok());
  std::vector<float> out(60);
  REQUIRE(r->shade(*light, 0, 20, out.data()).ok());
  for (std::size_t v = 0; v < 20; ++v) {
    for (int c = 0; c < 3; ++c) {
      // float storage of T and L: a few 2^-24 relative.
      REQUIRE(out[3 * v + c] == Approx(rho[c] * sky[c]).epsilon(1e-6));
    }
  }
}

TEST_CASE("rgba8 output follows the sRGB formula", "[relighter]") {
  // One channel, order 1: B = T_0 · L_0 with L_0 = 1, so each vertex's radiance is T_0.
  const float values[] = {0.0f,  0.001f, 0.0031308f, 0.01f, 0.18f, 0.5f,
                          0.75f, 1.0f,   2.0f,       -1.0f, 0.25f, 1e-7f};
  const std::size_t n = sizeof values / sizeof values[0];
  TransferData d;
  d.order = 1;
  d.channels = 1;
  d.vertex_count = n;
  d.coefficients.assign(values, values + n);
  const auto r = Relighter::create(d);
  REQUIRE(r.ok());
  const double ones[3] = {1.0, 1.0, 1.0};
  const auto light = ShLighting::from_coefficients(1, ones);
  REQUIRE(light.ok());
  auto srgb = [](double x) {  // IEC 61966-2-1, clamped, rounded to 8 bits
    x = std::min(1.0, std::max(0.0, x));
    const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
    return static_cast<int>(std::floor(s * 255 + 0.5));
  };
  for (float ev : {0.0f, 1.0f, -2.0f}) {
    std::vector<uint8_t> rgba(4 * n, 7);
    REQUIRE(r->shade_rgba8(*light, 0, n, ev, rgba.data()).ok());
    for (std::size_t i = 0; i < n; ++i) {
      const int want = srgb(static_cast<double>(values[i]) * std::exp2(ev));
      INFO("value " << values[i] << " ev " << ev);
      REQUIRE(rgba[4 * i] == want);
      REQUIRE(rgba[4 * i + 1] == want);
      REQUIRE(rgba[4 * i + 2] == want);
      REQUIRE(rgba[4 * i + 3] == 255);
    }
  }
  // Well-known 8-bit sRGB values: 0.5 -> 188, 0.18 (mid grey) -> 118, 1 -> 255, 0 -> 0.
  CHECK(prt::encode_srgb8(0.5f) == 188);
  CHECK(prt::encode_srgb8(0.18f) == 118);
  CHECK(prt::encode_srgb8(1.0f) == 255);
  CHECK(prt::encode_srgb8(0.0f) == 0);
  CHECK(prt::encode_srgb8(NAN) == 0);
  // A range that does not start at 0, and an exposure that is not finite.
  std::vector<uint8_t> part(8);
  REQUIRE(r->shade_rgba8(*light, 5, 2, 0.0f, part.data()).ok());
  CHECK(part[0] == srgb(values[5]));
  CHECK(part[4] == srgb(values[6]));
  CHECK_FALSE(r->shade_rgba8(*light, 0, 1, INFINITY, part.data()).ok());
}

TEST_CASE("shade refuses bad ranges and bad transfer data", "[relighter]") {
  const TransferData d = prt::test::make_transfer_data(10, 2, 1, Precision::F32, 1);
  const auto r = Relighter::create(d);
  REQUIRE(r.ok());
  const ShLighting light = random_lighting(2, 1);
  std::vector<float> out(100);
  CHECK_FALSE(r->shade(light, 5, 6, out.data()).ok());
  CHECK_FALSE(r->shade(light, 11, 0, out.data()).ok());
  CHECK_FALSE(r->shade(light, 1, ~std::size_t{0}, out.data()).ok());  // overflowing range
  CHECK_FALSE(r->shade(light, 0, 1, nullptr).ok());
  CHECK(r->shade(light, 10, 0, nullptr).ok());  // empty range at the end is fine
  TransferData bad = d;
  bad.coefficients[3] = 1e6f;
  const auto overflow = Relighter::create(bad, Precision::F16);
  REQUIRE_FALSE(overflow.ok());
  CHECK(overflow.status().message().find("1000000") != std::string::npos);
  CHECK(Relighter::create(bad, Precision::F32).ok());
  bad.coefficients.pop_back();
  CHECK_FALSE(Relighter::create(bad).ok());
  // An empty relighter shades nothing without error.
  const Relighter empty;
  CHECK(empty.shade(light, 0, 0, nullptr).ok());
  CHECK_FALSE(empty.shade(light, 0, 1, out.data()).ok());
}

TEST_CASE("encode_srgb8 equals the sRGB formula across the float range", "[relighter]") {
  // The library uses a threshold table; this checks it against the formula, evaluated here
  // independently, on every 97th float bit pattern in [0, 1] plus each threshold neighbourhood.
  auto formula = [](float xf) {
    const double x = xf;
    if (!(x > 0)) return 0;
    if (x >= 1) return 255;
    const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
    return static_cast<int>(std::floor(s * 255 + 0.5));
  };
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 97) {
    float x;
    std::memcpy(&x, &bits, 4);
    REQUIRE(prt::encode_srgb8(x) == formula(x));
  }
  for (int j = 1; j <= 255; ++j) {
    const double s = (j - 0.5) / 255.0;
    const float x =
        static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
    float y = x;
    for (int i = 0; i < 8; ++i) y = std::nextafter(y, 0.0f);
    for (int i = 0; i < 16; ++i, y = std::nextafter(y, 2.0f)) {
      INFO("j " << j << " x " << y);
      REQUIRE(prt::encode_srgb8(y) == formula(y));
    }
  }
  CHECK(prt::encode_srgb8(-0.0f) == 0);
  CHECK(prt::encode_srgb8(INFINITY) == 255);
  CHECK(prt::encode_srgb8(1e30f) == 255);
}
