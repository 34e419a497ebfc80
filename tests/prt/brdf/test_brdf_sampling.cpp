// Samplers against their pdfs: the pdf's integral over the sphere, sample()'s pdf equal to
// pdf(), and a chi-square goodness-of-fit test of every sampler (pbrt/Mitsuba style).
#include <cmath>
#include <cstdio>

#include <catch2/catch.hpp>

#include "brdf_test_support.h"
#include "sh/constants.h"

using namespace brdf_test;

namespace {
using prt::sh::kPi;
}

// ∫ pdf over the sphere = 1 − P(no sample). The no-sample probability is estimated from 2e5
// draws (standard error ≤ 0.0011), the integral by 6×6 Gauss–Legendre on 2×2 sub-cells of a
// 32×64 grid (converged to ~1e-5 for these lobes); tolerance 0.006 ≈ 5 standard errors.
TEST_CASE("each pdf integrates to 1 minus its discarded fraction", "[brdf][pdf]") {
  for (const NamedBrdf& m : analytic_models()) {
    for (const Vec3& wo : test_outgoing_directions()) {
      const double integral = integrate_pdf_sphere(*m.brdf, wo, 32, 2);
      Rng rng{12345};
      const int n = 200000;
      int none = 0;
      for (int k = 0; k < n; ++k) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        if (!(m.brdf->sample(wo, u1, u2).pdf > 0.0)) ++none;
      }
      INFO(m.name << ", cos(theta_o) = " << wo.z << ": integral " << integral << ", no-sample "
                  << double(none) / n);
      CHECK(integral <= 1.0 + 1e-4);
      CHECK(integral + double(none) / n == Approx(1.0).margin(0.006));
    }
  }
}

// The pdf a sample carries must be pdf() at that direction, and its f must be eval() there.
TEST_CASE("sample() returns the pdf and value of the direction it draws", "[brdf][pdf]") {
  for (const NamedBrdf& m : analytic_models()) {
    for (const Vec3& wo : test_outgoing_directions()) {
      Rng rng{99};
      for (int k = 0; k < 2000; ++k) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        const prt::brdf::BrdfSample s = m.brdf->sample(wo, u1, u2);
        if (!(s.pdf > 0.0)) continue;
        INFO(m.name << " wo.z=" << wo.z);
        REQUIRE(s.wi.z > 0.0);
        REQUIRE(std::abs(prt::brdf::length(s.wi) - 1.0) < 1e-12);
        REQUIRE(s.pdf == Approx(m.brdf->pdf(wo, s.wi)).epsilon(1e-9));
        const prt::brdf::Rgb f = m.brdf->eval(s.wi, wo);
        REQUIRE(s.f.r == f.r);
        REQUIRE(s.f.b == f.b);
      }
    }
  }
}

// Chi-square goodness of fit: 1e6 samples per (model, ωo) on a 32 (cos θ over [0, 1]) × 64 (φ)
// grid plus a no-sample cell, expected counts from 6×6 Gauss–Legendre on 2×2 sub-cells, cells
// expected below 5 pooled. Fixed seeds. The family-wise significance level is 1% over all
// (model, ωo) pairs, Šidák-corrected per test.
TEST_CASE("every sampler passes a chi-square test against its pdf", "[brdf][chi2]") {
  const auto models = analytic_models();
  const auto dirs = test_outgoing_directions();
  const double tests = double(models.size() * dirs.size());
  const double threshold = 1.0 - std::pow(1.0 - 0.01, 1.0 / tests);
  uint64_t seed = 1000;
  std::printf("chi-square: per-test threshold p >= %.3g (%d tests)\n", threshold, int(tests));
  std::printf("%-36s %7s %9s %5s %8s %8s\n", "model", "theta_o", "chi2", "dof", "p", "discarded");
  for (const NamedBrdf& m : models) {
    for (const Vec3& wo : dirs) {
      const ChiSquareResult r = chi_square(*m.brdf, wo, 1000000, ++seed, 32, 2);
      std::printf("%-36s %7.1f %9.1f %5d %8.4f %8.4f\n", m.name.c_str(),
                  std::acos(wo.z) * 180.0 / kPi, r.statistic, r.dof, r.p_value,
                  double(r.no_sample) / double(r.samples));
      INFO(m.name << " theta_o=" << std::acos(wo.z) * 180.0 / kPi << " chi2=" << r.statistic
                  << " dof=" << r.dof << " p=" << r.p_value << " " << r.failure);
      CHECK(r.failure.empty());
      CHECK(r.p_value >= threshold);
    }
  }
}

// The chi-square machinery must be able to fail: a sampler whose pdf() is off by a factor
// (here a Lambert whose sampling is cosine but whose pdf claims uniform-hemisphere) is rejected.
namespace {
class WrongPdf final : public prt::brdf::Brdf {
 public:
  prt::brdf::Rgb eval(const Vec3&, const Vec3&) const override { return {}; }
  prt::brdf::BrdfSample sample(const Vec3& wo, double u1, double u2) const override {
    prt::brdf::BrdfSample s;
    s.wi = prt::brdf::spherical_direction(std::sqrt(1.0 - u1), 2.0 * kPi * u2);
    s.pdf = pdf(wo, s.wi);
    return s;
  }
  double pdf(const Vec3&, const Vec3& wi) const override {
    return wi.z > 0.0 ? 1.0 / (2.0 * kPi) : 0.0;
  }
  bool reciprocal() const override { return true; }
};
}  // namespace

TEST_CASE("the chi-square test rejects a sampler that does not match its pdf", "[brdf][chi2]") {
  WrongPdf wrong;
  const ChiSquareResult r = chi_square(wrong, {0, 0, 1}, 100000, 7, 16, 1);
  CHECK(r.p_value < 1e-6);
}

TEST_CASE("gamma_q gives known chi-square tail probabilities", "[brdf][chi2]") {
  // Chi-square quantiles (standard tables): P(χ²_1 > 3.841459) = 0.05, P(χ²_10 > 23.209251)
  // = 0.01, P(χ²_100 > 124.342113) = 0.05; Q(1, x) = exp(−x).
  CHECK(gamma_q(0.5, 3.841459 / 2) == Approx(0.05).epsilon(1e-5));
  CHECK(gamma_q(5.0, 23.209251 / 2) == Approx(0.01).epsilon(1e-5));
  CHECK(gamma_q(50.0, 124.342113 / 2) == Approx(0.05).epsilon(1e-5));
  CHECK(gamma_q(1.0, 2.5) == Approx(std::exp(-2.5)).epsilon(1e-12));
}
