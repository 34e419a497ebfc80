// The white-furnace check (prt/brdf/energy_check.h): its quadrature against exact albedos
// (Lambert: ρ; GGX with F = 1 against the reference values of independent quadrature and
// against a 512² importance-sampled estimate), and its verdicts and message for every model.
#include <chrono>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/energy_check.h"
#include "prt/brdf/microfacet.h"

using namespace prt::brdf;

namespace {

Vec3 at(double cos_theta) {
  return {std::sqrt(1.0 - cos_theta * cos_theta), 0.0, cos_theta};
}

Material ggx(double roughness, double kd, double f0) {
  Material m;
  m.model = MaterialModel::kMicrofacet;
  m.fresnel = FresnelMode::kSchlick;
  m.alpha_x = m.alpha_y = roughness * roughness;
  m.diffuse = grey(kd);
  m.specular = grey(f0);
  return m;
}

}  // namespace

TEST_CASE("energy check: Lambert's albedo is its reflectance", "[brdf][energy_check]") {
  Material m;
  m.diffuse = {0.25, 0.5, 1.0};
  const auto f = make_brdf(m);
  REQUIRE(f);
  for (double mu : {1.0, 0.7, 0.3, 0.05, 0.017}) {
    const Rgb a = furnace_albedo(*f.value(), at(mu));
    INFO("cos theta_o " << mu);
    CHECK(a.r == Approx(0.25).margin(0.25 * kAlbedoQuadratureError));
    CHECK(a.b == Approx(1.0).margin(kAlbedoQuadratureError));
  }
  CHECK(check_energy_conservation(m));
}

// GUIDE reference values (3 digits, independent quadrature) and E(1) = 1 − ln 2 at α = 1.
TEST_CASE("energy check: GGX furnace albedos (F = 1) match independent references",
          "[brdf][energy_check]") {
  struct Ref {
    double alpha, mu, albedo;
  };
  const Ref refs[] = {{0.10, 1.0, 0.988}, {0.10, 0.5, 0.969},
                      {0.10, 0.2, 0.905}, {0.25, 1.0, 0.916},
                      {0.25, 0.5, 0.857}, {0.25, 0.2, 0.848},
                      {0.50, 1.0, 0.688}, {0.50, 0.5, 0.698},
                      {0.50, 0.2, 0.790}, {1.00, 1.0, 1.0 - std::log(2.0)},
                      {1.00, 0.5, 0.451}, {1.00, 0.2, 0.642}};
  for (const Ref& r : refs) {
    MicrofacetParams p;
    p.alpha_x = p.alpha_y = r.alpha;
    p.fresnel = FresnelMode::kNone;
    const Microfacet f = Microfacet::create(p).value();
    const double a = furnace_albedo(f, at(r.mu)).r;
    INFO("alpha " << r.alpha << " mu " << r.mu << ": " << a << " against " << r.albedo);
    // The references' own rounding (5e-4) plus the quadrature's bound.
    CHECK(a == Approx(r.albedo).margin(5e-4 + kAlbedoQuadratureError));
  }
  // The sharpest lobe prt accepts: a mirror's albedo, 1.
  MicrofacetParams p;
  p.alpha_x = p.alpha_y = 1e-3;
  p.fresnel = FresnelMode::kNone;
  const Microfacet sharp = Microfacet::create(p).value();
  for (double mu : {1.0, 0.5, 0.2})
    CHECK(furnace_albedo(sharp, at(mu)).r == Approx(1.0).margin(kAlbedoQuadratureError));
}

// Anisotropic and Beckmann lobes against 512² visible-normal / importance-sampled estimates
// (standard error ≤ 1e-3): within the bound plus 4 standard errors.
TEST_CASE("energy check: quadrature agrees with importance sampling on other lobes",
          "[brdf][energy_check]") {
  Material beckmann = ggx(0.5, 0.3, 0.5);
  beckmann.distribution = NormalDistribution::kBeckmann;
  Material aniso = ggx(0.3, 0.2, 0.9);
  aniso.alpha_y = 0.6;
  Material ward;
  ward.model = MaterialModel::kWard;
  ward.diffuse = grey(0.3);
  ward.specular = grey(0.6);
  ward.alpha_x = 0.1;
  ward.alpha_y = 0.3;
  Material phong;
  phong.model = MaterialModel::kBlinnPhong;
  phong.diffuse = grey(0.3);
  phong.specular = grey(0.5);
  phong.exponent = 200;
  for (const Material& m : {beckmann, aniso, ward, phong}) {
    const auto f = make_brdf(m);
    REQUIRE(f);
    for (double mu : {0.9, 0.4, 0.1}) {
      const Vec3 wo{std::sqrt(1 - mu * mu) * 0.6, std::sqrt(1 - mu * mu) * 0.8, mu};
      double se = 0.0;
      const Rgb mc = directional_albedo(*f.value(), wo, 512, 3, &se);
      const Rgb q = furnace_albedo(*f.value(), wo);
      INFO(describe(m) << " mu " << mu << ": quadrature " << q.r << ", sampled " << mc.r << " +- "
                       << se);
      CHECK(q.r == Approx(mc.r).margin(kAlbedoQuadratureError + 4.0 * se));
    }
  }
}

TEST_CASE("energy check: refuses every model that reflects more than arrives, names the angle",
          "[brdf][energy_check]") {
  const prt::Status bad = check_energy_conservation(ggx(0.9, 0.95, 0.95));
  REQUIRE_FALSE(bad);
  CAPTURE(bad.message());
  CHECK(bad.message().find("reflects ") != std::string::npos);
  CHECK(bad.message().find("x the light arriving at ") != std::string::npos);
  CHECK(bad.message().find("°: directional albedo must not exceed 1") != std::string::npos);
  CHECK(bad.message().find('\n') == std::string::npos);
  CHECK(check_energy_conservation(ggx(0.9, 0.3, 0.04)));
  CHECK(check_energy_conservation(ggx(0.5, 0.0, 1.0)));  // a white metal: ≤ 1, lost to shadowing

  Material ward;
  ward.model = MaterialModel::kWard;
  ward.ward_form = WardForm::kDuer;  // over-corrects at grazing angles
  ward.diffuse = grey(0.0);
  ward.specular = grey(1.0);
  ward.alpha_x = ward.alpha_y = 0.3;
  const prt::Status duer = check_energy_conservation(ward);
  REQUIRE_FALSE(duer);
  ward.ward_form = WardForm::kNormalized;
  CHECK(check_energy_conservation(ward));
  ward.alpha_y = 0.05;  // anisotropic: the azimuth is named
  ward.ward_form = WardForm::kDuer;
  const prt::Status aniso = check_energy_conservation(ward);
  REQUIRE_FALSE(aniso);
  CHECK(aniso.message().find("azimuth") != std::string::npos);

  Material phong;  // (8 + s)/(8π) overshoots near s = 10: kd + ks = 1 is above 1
  phong.model = MaterialModel::kBlinnPhong;
  phong.diffuse = grey(0.5);
  phong.specular = grey(0.5);
  phong.exponent = 10;
  CHECK(blinn_phong_normal_albedo(10) > 1.03);
  CHECK_FALSE(check_energy_conservation(phong));
  phong.specular = grey(0.4);
  CHECK(check_energy_conservation(phong));
}

// "ms per material": one isotropic material's check (13 angles, 10240 nodes each).
TEST_CASE("energy check: an isotropic material takes well under 0.2 s", "[brdf][energy_check]") {
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(check_energy_conservation(ggx(0.4, 0.5, 0.04)));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(s < 0.2);
}
