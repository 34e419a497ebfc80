// The dipole BSSRDF (prt/subsurface/dipole.h): the profile integrated over the plane against the
// closed-form total diffuse reflectance, the paper's measured materials against its listed
// reflectance column, the inversion round trip and the refusals.
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "prt/subsurface/dipole.h"

using namespace prt::subsurface;
using prt::Result;

namespace {

// ∫_0^∞ 2π r R_d(r) dr by composite Gauss–Legendre on geometric panels: [0, z_r/1000], then
// panels doubling in length up to 10¹² z_v. The integrand is smooth on each panel (it varies on
// the scale of r itself), and the tail beyond R is below (α′/2)(z_r + z_v)/R ≤ 10⁻¹² R_total.
double integrate_profile(const DipoleProfile& p) {
  std::vector<double> x, w;
  double a = 0, b = p.z_r() * 1e-3;
  const double end = p.z_v() * 1e12;
  while (a < end) {
    prt::numerics::append_gauss_legendre(24, a, b, &x, &w);
    a = b;
    b *= 2;
  }
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i)
    sum += w[i] * prt::numerics::kTwoPi * x[i] * p.profile(x[i]);
  return sum;
}

}  // namespace

TEST_CASE("dipole profile integrates over the plane to the closed-form total reflectance") {
  // Several reduced albedos (from strongly absorbing to none at all) and indices.
  const double sigma_s = 1.7;
  for (double alpha : {0.05, 0.3, 0.6, 0.9, 0.99, 0.9999, 1.0}) {
    for (double eta : {1.0, 1.3, 1.5, 2.0}) {
      const double sigma_t = sigma_s / alpha;
      const DipoleProfile p(sigma_t - sigma_s, sigma_s, eta);
      CAPTURE(alpha, eta);
      REQUIRE(p.alpha_prime() == Approx(alpha).epsilon(1e-12));
      // 1e-4 is the bound; the quadrature reaches ~1e-10, so a wrong factor anywhere
      // (the 4π, a source depth, a sign of the virtual source) fails by orders of magnitude.
      REQUIRE(std::abs(integrate_profile(p) - p.total()) < 1e-4);
      REQUIRE(std::abs(integrate_profile(p) - p.total()) < 1e-8);
    }
  }
}

TEST_CASE("dipole total reflectance: limits and the tail radius") {
  // No absorption: everything that enters leaves, R_total = 1 for any η.
  for (double eta : {1.0, 1.3, 2.0}) REQUIRE(DipoleProfile(0.0, 2.0, eta).total() == Approx(1.0));
  // Index matched (η = 1: F_dr = 0.0016 by the fit, A ≈ 1.003) against the formula by hand.
  const double a = boundary_factor(1.0);
  REQUIRE(a == Approx((1 + 0.0016) / (1 - 0.0016)).epsilon(1e-12));
  // The radius holding all but 1% of the reflectance: the tail integral there is 1%.
  const DipoleProfile p(0.0041, 2.62, 1.3);
  const double r = p.radius_for_tail(0.01);
  std::vector<double> x, w;
  prt::numerics::append_gauss_legendre(400, 0.0, r, &x, &w);
  double inside = 0;
  for (size_t i = 0; i < x.size(); ++i)
    inside += w[i] * prt::numerics::kTwoPi * x[i] * p.profile(x[i]);
  REQUIRE(inside / p.total() == Approx(0.99).margin(2e-4));
}

TEST_CASE("dipole diffuse Fresnel: the exact mean against the paper's polynomial fit") {
  // F_dr is the diffuse reflectance of the boundary seen from inside (relative index 1/η, with
  // total internal reflection); the paper's fit is good to about 0.01 of the exact mean over η in
  // [1.2, 2]. The exact mean at η = 1 is exactly 1 (no interface), and reciprocity gives
  // T(1/η) = T(η)/η².
  REQUIRE(diffuse_fresnel_transmittance(1.0) == Approx(1.0).margin(1e-12));
  for (double eta : {1.2, 1.3, 1.5, 2.0}) {
    CAPTURE(eta);
    const double inside = diffuse_fresnel_transmittance(1.0 / eta);
    REQUIRE(1.0 - inside == Approx(diffuse_fresnel_reflectance_fit(eta)).margin(0.01));
    REQUIRE(inside == Approx(diffuse_fresnel_transmittance(eta) / (eta * eta)).epsilon(1e-6));
  }
  // Normal incidence: 1 − ((η−1)/(η+1))².
  REQUIRE(fresnel_transmittance(1.0, 1.3) == Approx(1.0 - std::pow(0.3 / 2.3, 2)).epsilon(1e-12));
}

TEST_CASE("dipole presets reproduce the reflectance column of the paper's table") {
  // The table prints R_d with two decimals. Its own coefficients, through its own formula (η =
  // 1.3, F_dr by the fit), give those digits to ±0.005 for most entries (20 of 29) and to ±0.01 for
  // all but four: chicken1 blue (0.126 listed 0.10) and the three marble channels (0.8665, 0.8338,
  // 0.8010 listed 0.83, 0.79, 0.75). Those four are asserted as the documented discrepancies
  // (docs/SUBSURFACE.md), so any change to the coefficients or the formula fails here.
  struct Known {
    const char* name;
    int channel;
    double computed;
  };
  const Known known[] = {
      {"chicken1", 2, 0.1264}, {"marble", 0, 0.8665}, {"marble", 1, 0.8338}, {"marble", 2, 0.8010}};
  REQUIRE(subsurface_presets().size() == 11);
  int within_half_unit = 0, checked = 0;
  for (const SubsurfaceMaterial& m : subsurface_presets()) {
    Result<DipoleMaterial> d = make_dipole(m.coefficients);
    REQUIRE(d.ok());
    for (int ch = 0; ch < 3; ++ch) {
      const double computed = d->channels[ch].total();
      CAPTURE(m.name, ch, computed, m.listed_reflectance[ch]);
      bool is_known = false;
      for (const Known& k : known) {
        if (m.name == k.name && ch == k.channel) {
          is_known = true;
          REQUIRE(computed == Approx(k.computed).margin(1e-4));
        }
      }
      if (is_known) continue;
      ++checked;
      REQUIRE(std::abs(computed - m.listed_reflectance[ch]) <= 0.01);
      if (std::abs(computed - m.listed_reflectance[ch]) <= 0.005 + 1e-12) ++within_half_unit;
    }
  }
  REQUIRE(checked == 29);
  // Most entries to the printed digit (rounding half a unit of 0.01).
  REQUIRE(within_half_unit == 20);
}

TEST_CASE("dipole preset lookup is case-insensitive and refuses unknown names") {
  REQUIRE(find_subsurface_preset("Marble").ok());
  REQUIRE(find_subsurface_preset("SKIN1")->coefficients.sigma_a[2] == 0.48);
  Result<SubsurfaceMaterial> r = find_subsurface_preset("jade");
  REQUIRE_FALSE(r.ok());
  REQUIRE(r.status().message().find("unknown subsurface preset 'jade'") != std::string::npos);
  REQUIRE(r.status().message().find("marble") != std::string::npos);
}

TEST_CASE("dipole inversion from a colour and a mean free path round-trips") {
  for (double eta : {1.0, 1.3, 1.6}) {
    const Rgb color = {0.83, 0.45, 0.02};
    const Rgb mfp = {8.0, 1.5, 0.3};
    Result<DipoleCoefficients> c = coefficients_from_color(color, mfp, eta);
    REQUIRE(c.ok());
    Result<DipoleMaterial> d = make_dipole(*c);
    REQUIRE(d.ok());
    for (int ch = 0; ch < 3; ++ch) {
      CAPTURE(eta, ch);
      REQUIRE(d->channels[ch].total() == Approx(color[ch]).epsilon(1e-10));
      REQUIRE(1.0 / d->channels[ch].sigma_tr() == Approx(mfp[ch]).epsilon(1e-10));
    }
  }
  // And the other way: a preset's own R_total and 1/σ_tr give back its coefficients.
  const DipoleCoefficients skin = find_subsurface_preset("skin2")->coefficients;
  const DipoleMaterial d = *make_dipole(skin);
  Rgb color{}, mfp{};
  for (int ch = 0; ch < 3; ++ch) {
    color[ch] = d.channels[ch].total();
    mfp[ch] = 1.0 / d.channels[ch].sigma_tr();
  }
  const DipoleCoefficients back = *coefficients_from_color(color, mfp, skin.eta);
  for (int ch = 0; ch < 3; ++ch) {
    REQUIRE(back.sigma_a[ch] == Approx(skin.sigma_a[ch]).epsilon(1e-8));
    REQUIRE(back.sigma_s_prime[ch] == Approx(skin.sigma_s_prime[ch]).epsilon(1e-8));
  }
}

TEST_CASE("dipole refuses bad coefficients with a message") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  DipoleCoefficients good;
  good.sigma_a = {0.01, 0.02, 0.03};
  good.sigma_s_prime = {1, 1, 1};
  REQUIRE(validate(good).ok());
  good.sigma_a = {0, 0, 0};
  REQUIRE(validate(good).ok());  // no absorption is a valid limit

  DipoleCoefficients c = good;
  c.sigma_a[1] = -0.1;
  REQUIRE(validate(c).message() == "sigma_a (green) must be finite and >= 0, got -0.100000");
  c = good;
  c.sigma_s_prime[2] = 0;
  REQUIRE(validate(c).message().find("sigma_s' (blue) must be finite and > 0") == 0);
  c = good;
  c.sigma_s_prime[0] = nan;
  REQUIRE(validate(c).message().find("got NaN") != std::string::npos);
  c = good;
  c.eta = 0.9;
  REQUIRE(validate(c).message().find("eta must be finite and >= 1") == 0);
  REQUIRE_FALSE(make_dipole(c).ok());

  REQUIRE_FALSE(invert_total_reflectance(1.0, 1.3).ok());
  REQUIRE_FALSE(invert_total_reflectance(0.0, 1.3).ok());
  REQUIRE_FALSE(invert_total_reflectance(nan, 1.3).ok());
  REQUIRE_FALSE(invert_total_reflectance(0.5, 0.8).ok());
  REQUIRE_FALSE(coefficients_from_color({0.5, 0.5, 0.5}, {1, -1, 1}, 1.3).ok());
  REQUIRE(coefficients_from_color({0.5, 1.2, 0.5}, {1, 1, 1}, 1.3)
              .status()
              .message()
              .find("green channel") == 0);
}
