// BRDF pieces against their closed forms: Lambert's albedo, the Blinn-Phong normalisation,
// NDF normalisation, Smith's projected-area identity, Fresnel at normal incidence and
// Schlick against the exact formula.
#include <cmath>

#include <catch2/catch.hpp>

#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/fresnel.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/microfacet_distribution.h"
#include "sh/constants.h"

using namespace prt::brdf;

namespace {

using prt::sh::kPi;

// ∫ g(m) dm over the upper hemisphere by the midpoint rule in (θ, φ), dm = sin θ dθ dφ.
template <class F>
double hemisphere_integral(F g, int n_theta, int n_phi) {
  double sum = 0.0;
  const double dt = 0.5 * kPi / n_theta, dp = 2.0 * kPi / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double t = (i + 0.5) * dt;
    double row = 0.0;
    for (int j = 0; j < n_phi; ++j) {
      row += g(spherical_direction(std::cos(t), (j + 0.5) * dp));
    }
    sum += row * std::sin(t);
  }
  return sum * dt * dp;
}

}  // namespace

TEST_CASE("Lambert's directional albedo is its reflectance", "[brdf][closed]") {
  const Lambert l = Lambert::create({0.2, 0.5, 0.9}).value();
  for (double deg : {0.0, 45.0, 89.0}) {
    const Vec3 wo = spherical_direction(std::cos(deg * kPi / 180.0), 1.0);
    // Importance sampling: every weight f cos/pdf is exactly ρ, so only rounding remains.
    const Rgb a = directional_albedo(l, wo, 64);
    CHECK(a.r == Approx(0.2).epsilon(1e-12));
    CHECK(a.b == Approx(0.9).epsilon(1e-12));
    // Independently, by quadrature of f cos θi (midpoint rule, error ~1e-6 at 2000 × 16).
    const double q =
        hemisphere_integral([&](const Vec3& wi) { return l.eval(wi, wo).g * wi.z; }, 2000, 16);
    CHECK(q == Approx(0.5).epsilon(1e-5));
  }
}

// The glossy lobe's cosine-weighted integral at normal incidence, by 1-D quadrature of the
// library's eval (ωo = n, so the integrand depends on θi only), against the closed form in
// blinn_phong.h — which is exactly 1 at s = 0 and tends to 1 as s grows.
TEST_CASE("normalised Blinn-Phong matches its closed-form normal-incidence albedo",
          "[brdf][closed]") {
  CHECK(blinn_phong_normal_albedo(0.0) == Approx(1.0).epsilon(1e-15));
  CHECK(blinn_phong_normal_albedo(1e6) == Approx(1.0).epsilon(1e-4));
  for (double s : {0.0, 1.0, 8.0, 50.0, 500.0, 5000.0}) {
    const BlinnPhong bp = BlinnPhong::create(grey(0.0), grey(1.0), s).value();
    const Vec3 wo{0, 0, 1};
    const int n = 200000;  // midpoint rule in θ; the s = 5000 lobe is ~0.06 rad wide
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) * 0.5 * kPi / n;
      const Vec3 wi = spherical_direction(std::cos(t), 0.0);
      sum += bp.eval(wi, wo).r * wi.z * std::sin(t);
    }
    const double numeric = sum * 2.0 * kPi * 0.5 * kPi / n;
    INFO("s = " << s << ": quadrature " << numeric);
    CHECK(numeric == Approx(blinn_phong_normal_albedo(s)).epsilon(1e-6));
  }
  // The approximation overshoots between the ends: about 1.075 at s = 8.
  CHECK(blinn_phong_normal_albedo(8.0) == Approx(1.075).epsilon(1e-3));
}

// ∫ D(m) (m·n) dm = 1: midpoint rule with 10000 θ steps (the α = 0.05 lobe spans ~300) and
// 512 φ steps (the α = (0.1, 0.6) lobe is narrow in φ); tolerance 2e-5.
TEST_CASE("GGX and Beckmann distributions are normalised", "[brdf][closed]") {
  for (auto type : {NormalDistribution::kGgx, NormalDistribution::kBeckmann}) {
    for (auto [ax, ay] :
         {std::pair{0.05, 0.05}, {0.2, 0.2}, {0.5, 0.5}, {1.0, 1.0}, {0.1, 0.6}, {0.8, 0.3}}) {
      const MicrofacetDistribution d{type, ax, ay};
      const double integral =
          hemisphere_integral([&](const Vec3& m) { return d.d(m) * m.z; }, 10000, 512);
      INFO(distribution_name(type) << " alpha = (" << ax << ", " << ay << "): " << integral);
      // GGX's tail beyond θ = π/2 − 1e-5 (cut off by the midpoint rule) is below 1e-10.
      CHECK(integral == Approx(1.0).margin(2e-5));
    }
  }
}

// Smith's Λ is defined by ∫ D(m) max(0, ω·m) dm = ω_z (1 + Λ(ω)): the closed forms in
// microfacet_distribution.h must agree with this integral. Quadrature as above; the kink of
// max(0, ·) limits it to ~1e-5, the tolerance is 2e-4 relative.
TEST_CASE("Smith G1 closed forms satisfy the projected-area identity", "[brdf][closed]") {
  for (auto type : {NormalDistribution::kGgx, NormalDistribution::kBeckmann}) {
    for (auto [ax, ay] : {std::pair{0.1, 0.1}, {0.5, 0.5}, {1.0, 1.0}, {0.2, 0.7}}) {
      const MicrofacetDistribution d{type, ax, ay};
      for (double deg : {0.0, 40.0, 70.0, 85.0, 89.0}) {
        const Vec3 w = spherical_direction(std::cos(deg * kPi / 180.0), 0.4);
        const double projected = hemisphere_integral(
            [&](const Vec3& m) { return d.d(m) * std::fmax(0.0, dot(w, m)); }, 6000, 384);
        INFO(distribution_name(type) << " alpha = (" << ax << ", " << ay << "), theta = " << deg
                                     << ": integral " << projected << ", closed " << w.z / d.g1(w));
        CHECK(projected == Approx(w.z / d.g1(w)).epsilon(2e-4));
      }
    }
  }
  // G1 → 1 along the normal and height-correlated G2 ≤ min(G1(ωi), G1(ωo)).
  const MicrofacetDistribution ggx{NormalDistribution::kGgx, 0.5, 0.5};
  CHECK(ggx.g1({0, 0, 1}) == 1.0);
  const Vec3 a = spherical_direction(0.3, 0.2), b = spherical_direction(0.7, 2.0);
  CHECK(ggx.g2(a, b) <= std::fmin(ggx.g1(a), ggx.g1(b)));
  CHECK(ggx.g2(a, b) >= ggx.g1(a) * ggx.g1(b));  // correlation never reduces G2 below the product
}

TEST_CASE("Fresnel: normal incidence, grazing, total internal reflection, reciprocity",
          "[brdf][closed]") {
  for (double eta : {1.2, 1.33, 1.5, 2.4}) {
    const double f0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
    CHECK(fresnel_dielectric(1.0, eta) == Approx(f0).epsilon(1e-14));
    CHECK(fresnel_f0(eta) == Approx(f0).epsilon(1e-14));
    CHECK(fresnel_dielectric(0.0, eta) == Approx(1.0).epsilon(1e-14));
    // Stokes relation: the same interface seen from the other side, at the refracted angle,
    // reflects the same fraction: F(θi, η) = F(θt, 1/η) with sin θt = sin θi / η.
    for (double c : {0.1, 0.5, 0.9}) {
      const double ct = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
      CHECK(fresnel_dielectric(ct, 1.0 / eta) == Approx(fresnel_dielectric(c, eta)).epsilon(1e-12));
    }
  }
  // Past the critical angle (sin θc = 1/1.5) from inside glass: total internal reflection.
  CHECK(fresnel_dielectric(0.7, 1.0 / 1.5) == 1.0);  // sin θ = 0.714 > 0.667
  CHECK(fresnel_dielectric(0.8, 1.0 / 1.5) < 1.0);   // sin θ = 0.6 < 0.667
  // Matched indices reflect nothing.
  CHECK(fresnel_dielectric(0.3, 1.0) == Approx(0.0).margin(1e-15));
}

// Schlick is exact at both ends and close in between. Measured maximum absolute error over
// cos θ in [0, 1] (10001 points): η = 1.33: 0.0599, η = 1.5: 0.0357, η = 2.4: 0.0740, all near
// grazing (docs/BRDF.md); the bounds leave about 10% slack.
TEST_CASE("Schlick's approximation against the exact dielectric Fresnel", "[brdf][closed]") {
  for (auto [eta, bound] : {std::pair{1.33, 0.066}, {1.5, 0.040}, {2.4, 0.082}}) {
    const double f0 = fresnel_f0(eta);
    CHECK(fresnel_schlick(1.0, f0) == f0);
    CHECK(fresnel_schlick(0.0, f0) == 1.0);
    double worst = 0.0;
    for (int i = 0; i <= 10000; ++i) {
      const double c = i / 10000.0;
      worst = std::fmax(worst, std::abs(fresnel_schlick(c, f0) - fresnel_dielectric(c, eta)));
    }
    INFO("eta = " << eta << ": max |Schlick - exact| = " << worst);
    CHECK(worst < bound);
    CHECK(worst > 0.0);
  }
}
