// BrdfProjection::evaluate_many() (prt/glossy/brdf_projection.h) against the per-view float
// evaluate(): the batched isotropic-table path replaces acosf by a polynomial and fuses the lerp
// with the rotation about +z, so it may differ in the last bits only; the other methods fall back
// to the per-view code and must give its bits.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "prt/glossy/brdf_projection.h"

using prt::BrdfProjection;
using prt::BrdfProjectionMethod;
using prt::brdf::Material;
using prt::brdf::MaterialModel;

namespace {

using prt::numerics::kPi;

Material ggx(double alpha, prt::brdf::Rgb f0, double kd) {
  Material m;
  m.model = MaterialModel::kMicrofacet;
  m.alpha_x = m.alpha_y = alpha;
  m.specular = f0;
  m.diffuse = prt::brdf::grey(kd);
  return m;
}

void push(std::vector<float>* w, double theta, double phi, double length = 1.0) {
  w->push_back(float(length * std::sin(theta) * std::cos(phi)));
  w->push_back(float(length * std::sin(theta) * std::sin(phi)));
  w->push_back(float(length * std::cos(theta)));
}

// Views (3 floats each, not all unit): uniform on the hemisphere, near the pole (θo < 10⁻³ and
// exactly on it), near the horizon (cos θo down to 10⁻⁷), φo near ±π, every table node and
// midpoint in θo, lengths from 10⁻³ to 10³; then invalid ones, which must give zeros.
std::vector<float> views(std::size_t* valid) {
  std::mt19937 rng(20261202);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<float> w;
  for (int k = 0; k < 2000; ++k) push(&w, std::acos(u(rng)), 2 * kPi * u(rng) - kPi);
  for (int k = 0; k < 300; ++k) push(&w, 1e-3 * u(rng), 2 * kPi * u(rng) - kPi);
  for (int k = 0; k < 300; ++k) push(&w, std::acos(std::pow(10.0, -7 * u(rng))), 2 * kPi * u(rng));
  for (int k = 0; k < 300; ++k)
    push(&w, 0.5 * kPi * u(rng), (k % 2 ? 1 : -1) * (kPi - std::pow(10.0, -6 * u(rng))));
  for (int t = 0; t <= 180; ++t) push(&w, 0.25 * kPi * t / 90, 0.3 + t);
  for (int k = 0; k < 300; ++k)
    push(&w, std::acos(u(rng)), 2 * kPi * u(rng), std::pow(10.0, 6 * u(rng) - 3));
  const float special[][3] = {{0.f, 0.f, 1.f},     {0.f, 0.f, 1e-30f},   {1e-20f, -1e-20f, 1.f},
                              {-1.f, 1e-7f, 0.3f}, {-1.f, -1e-7f, 0.3f}, {-1.f, 0.f, 1e-6f}};
  for (const auto& v : special) w.insert(w.end(), v, v + 3);
  *valid = w.size() / 3;
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  const float invalid[][3] = {{0.f, 0.f, 0.f},  {0.3f, 0.2f, 0.f}, {0.3f, 0.2f, -0.f},
                              {0.f, 0.f, -1.f}, {nan, 0.f, 1.f},   {0.f, 0.f, nan},
                              {inf, 0.f, 1.f},  {0.f, 0.f, inf},   {1e30f, 1e30f, 1e30f}};
  for (const auto& v : invalid) w.insert(w.end(), v, v + 3);
  return w;
}

}  // namespace

TEST_CASE("Batched b equals the per-view float b to float rounding", "[glossy][projection]") {
  // Tolerance: the polynomial arccosine (Abramowitz & Stegun 4.4.46, 2·10⁻⁸ exact, a few float
  // ulp evaluated) moves θo by < 10⁻⁶ rad, i.e. < 6·10⁻⁵ of a 1° table step, so b moves by that
  // fraction of one step's change, far below 2·10⁻⁶ of max |b|; the remaining differences are
  // float rounding. A wrong rotation sign, a swapped (m, −m) pair or an arccosine off by 10⁻⁴ rad
  // exceeds it (measured: at most 5.2·10⁻⁷ of max |b|; 1.5·10⁻⁴ with a0 off by 10⁻⁴).
  struct Case {
    Material m;
    int order;
  };
  const Case cases[] = {{ggx(0.3, prt::brdf::grey(0.04), 0.3), 5},  // grey, unrolled order
                        {ggx(0.1, {0.95, 0.64, 0.54}, 0.0), 4},     // coloured, unrolled
                        {ggx(0.3, prt::brdf::grey(0.04), 0.3), 7},  // generic order
                        {ggx(0.5, {0.9, 0.5, 0.2}, 0.2), 2}};
  std::size_t valid = 0;
  const std::vector<float> w = views(&valid);
  const std::size_t count = w.size() / 3;
  for (const Case& c : cases) {
    auto p = BrdfProjection::create(c.m, c.order);
    REQUIRE(p.ok());
    REQUIRE(p->method() == BrdfProjectionMethod::kIsotropicTable);
    const std::size_t n2 = std::size_t(c.order) * c.order;
    std::vector<float> scratch(p->scratch_floats() + 1), single(3 * n2 * count);
    for (std::size_t k = 0; k < count; ++k)
      p->evaluate(&w[3 * k], &single[3 * n2 * k], scratch.data());
    float scale = 0.f;
    for (float x : single) scale = std::max(scale, std::abs(x));
    REQUIRE(scale > 0.f);
    for (int channels : {3, 1}) {
      std::vector<float> batch(channels * n2 * count, -1.f);
      p->evaluate_many(w.data(), count, batch.data(), scratch.data(), channels);
      float worst = 0.f;
      for (std::size_t k = 0; k < count; ++k)
        for (std::size_t i = 0; i < channels * n2; ++i) {
          const float a = batch[channels * n2 * k + i], b = single[3 * n2 * k + i];
          if (k >= valid) REQUIRE(a == 0.f);  // invalid views: zeros, as evaluate() gives
          REQUIRE(std::isfinite(a));
          worst = std::max(worst, std::abs(a - b));
        }
      INFO(prt::brdf::describe(c.m)
           << " order " << c.order << ", " << channels
           << " channels: largest |batched - single| / max|b| = " << worst / scale);
      REQUIRE(worst <= 2e-6f * scale);
    }
  }
}

TEST_CASE("Batched b of the other methods is the per-view b bit for bit", "[glossy][projection]") {
  Material lambert;
  lambert.diffuse = prt::brdf::grey(0.7);
  Material aniso = ggx(0.3, {0.9, 0.6, 0.5}, 0.1);
  aniso.alpha_y = 0.1;
  prt::BrdfProjectionOptions coarse;
  coarse.inner_theta = 16;
  coarse.inner_phi = 32;
  std::size_t valid = 0;
  const std::vector<float> w = views(&valid);
  const std::size_t count = w.size() / 3;
  for (const Material& m : {lambert, aniso}) {
    auto p = BrdfProjection::create(m, 3, coarse);
    REQUIRE(p.ok());
    REQUIRE(p->method() != BrdfProjectionMethod::kIsotropicTable);
    const std::size_t n2 = 9;
    std::vector<float> scratch(p->scratch_floats()), single(3 * n2), batch(3 * n2 * count);
    p->evaluate_many(w.data(), count, batch.data(), scratch.data(), 3);
    for (std::size_t k = 0; k < count; ++k) {
      p->evaluate(&w[3 * k], single.data(), scratch.data());
      for (std::size_t i = 0; i < 3 * n2; ++i) REQUIRE(batch[3 * n2 * k + i] == single[i]);
    }
  }
}
