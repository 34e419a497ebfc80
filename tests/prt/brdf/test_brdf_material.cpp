// prt::brdf::Material and make_brdf (prt/brdf/material.h): every model made from a Material
// evaluates as the model built directly; the microfacet-over-Lambert material is exactly the sum
// of its two layers; make_brdf refuses what the models refuse, with their one-line messages.
// (The layered material also runs through every property test of analytic_models(): pdf
// integral, sample/pdf agreement, chi-square, albedo ≤ 1.)
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "brdf_test_support.h"
#include "numerics/constants.h"
#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/material.h"
#include "prt/brdf/microfacet.h"
#include "prt/brdf/ward.h"

using namespace prt::brdf;
using brdf_test::Rng;

namespace {

std::shared_ptr<const Brdf> made(const Material& m) {
  auto r = make_brdf(m);
  INFO(describe(m) << ": " << (r ? "" : r.status().message()));
  REQUIRE(r.ok());
  return r.value();
}

// Max relative difference of eval over random direction pairs in the upper hemisphere.
double max_difference(const Brdf& a, const Brdf& b) {
  Rng rng{42};
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 wi = spherical_direction(rng.uniform(), prt::numerics::kTwoPi * rng.uniform());
    const Vec3 wo = spherical_direction(rng.uniform(), prt::numerics::kTwoPi * rng.uniform());
    const Rgb fa = a.eval(wi, wo), fb = b.eval(wi, wo);
    for (double d : {fa.r - fb.r, fa.g - fb.g, fa.b - fb.b}) {
      const double scale = std::max({1e-12, std::fabs(fa.r), std::fabs(fb.r)});
      worst = std::max(worst, std::fabs(d) / scale);
    }
  }
  return worst;
}

Material microfacet_material(Rgb diffuse, Rgb f0, double ax, double ay) {
  Material m;
  m.model = MaterialModel::kMicrofacet;
  m.diffuse = diffuse;
  m.specular = f0;
  m.alpha_x = ax;
  m.alpha_y = ay;
  return m;
}

}  // namespace

TEST_CASE("make_brdf builds each model as its own create() does", "[brdf][material]") {
  Material lambert;
  lambert.diffuse = Rgb{0.7, 0.5, 0.2};
  CHECK(max_difference(*made(lambert), Lambert::create(lambert.diffuse).value()) == 0.0);

  Material phong;
  phong.model = MaterialModel::kBlinnPhong;
  phong.diffuse = grey(0.3);
  phong.specular = Rgb{0.5, 0.4, 0.3};
  phong.exponent = 40;
  CHECK(max_difference(*made(phong), BlinnPhong::create(grey(0.3), phong.specular, 40).value()) ==
        0.0);

  Material ward;
  ward.model = MaterialModel::kWard;
  ward.diffuse = grey(0.2);
  ward.specular = grey(0.5);
  ward.alpha_x = 0.3;
  ward.alpha_y = 0.1;
  CHECK(max_difference(*made(ward), Ward::create(WardParams{grey(0.2), grey(0.5), 0.3, 0.1,
                                                            WardForm::kNormalized})
                                        .value()) == 0.0);
  CHECK_FALSE(ward.isotropic());

  // A pure lobe (no Lambert layer) is the Microfacet itself.
  const Material metal = microfacet_material(grey(0.0), Rgb{0.9, 0.6, 0.3}, 0.2, 0.2);
  MicrofacetParams p;
  p.alpha_x = p.alpha_y = 0.2;
  p.fresnel = FresnelMode::kSchlick;
  p.f0 = metal.specular;
  CHECK(max_difference(*made(metal), Microfacet::create(p).value()) == 0.0);
  CHECK(metal.isotropic());
}

TEST_CASE("the layered microfacet material is the Lambert layer plus the lobe",
          "[brdf][material]") {
  const Material m = microfacet_material(Rgb{0.5, 0.3, 0.1}, grey(0.04), 0.4, 0.1);
  const auto layered = made(m);
  MicrofacetParams p;
  p.alpha_x = 0.4;
  p.alpha_y = 0.1;
  p.fresnel = FresnelMode::kSchlick;
  p.f0 = grey(0.04);
  const Microfacet lobe = Microfacet::create(p).value();
  const Lambert diffuse = Lambert::create(m.diffuse).value();
  Rng rng{7};
  for (int k = 0; k < 500; ++k) {
    const Vec3 wi = spherical_direction(rng.uniform(), prt::numerics::kTwoPi * rng.uniform());
    const Vec3 wo = spherical_direction(rng.uniform(), prt::numerics::kTwoPi * rng.uniform());
    const Rgb f = layered->eval(wi, wo), a = diffuse.eval(wi, wo), b = lobe.eval(wi, wo);
    REQUIRE(f.r == Approx(a.r + b.r).epsilon(1e-12));
    REQUIRE(f.b == Approx(a.b + b.b).epsilon(1e-12));
  }
  // Far from the specular peak the Lambert layer dominates: f ≈ kd/π (within the lobe's share).
  const Rgb far = layered->eval(spherical_direction(0.99, 0.0), spherical_direction(0.2, 3.1));
  CHECK(far.r > 0.5 / prt::numerics::kPi);
  CHECK(layered->reciprocal());
}

TEST_CASE("make_brdf refuses bad parameters with the model's one-line message",
          "[brdf][material]") {
  struct Case {
    Material m;
    std::string expect;
  };
  std::vector<Case> cases;
  cases.push_back({microfacet_material(grey(0.2), grey(0.04), 0.0, 0.0),
                   "alpha_x is 0, must be in [0.001, 1]"});
  cases.push_back({microfacet_material(grey(0.2), grey(0.04), std::nan(""), 0.1), "NaN"});
  cases.push_back({microfacet_material(grey(1.5), grey(0.04), 0.2, 0.2), "must be in [0, 1]"});
  Material phong;
  phong.model = MaterialModel::kBlinnPhong;
  phong.diffuse = grey(0.2);
  phong.specular = grey(0.3);
  phong.exponent = -2;
  cases.push_back({phong, "-2"});
  Material merl;
  merl.model = MaterialModel::kMerl;
  merl.merl_path = std::string(PRT_TEST_OUTPUT_DIR) + "/material_truncated.binary";
  {
    const int32_t dims[3] = {90, 90, 180};
    std::ofstream out(merl.merl_path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(dims), sizeof dims);
    const double some[4] = {1, 2, 3, 4};
    out.write(reinterpret_cast<const char*>(some), sizeof some);
  }
  cases.push_back({merl, "truncated MERL file"});
  for (const Case& c : cases) {
    const auto r = make_brdf(c.m);
    INFO(describe(c.m));
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message());
    CHECK(r.status().message().find(c.expect) != std::string::npos);
    CHECK(r.status().message().find('\n') == std::string::npos);
  }
}

TEST_CASE("describe names the model and its parameters", "[brdf][material]") {
  const Material m = microfacet_material(grey(0.0), Rgb{0.9, 0.6, 0.3}, 0.3, 0.1);
  CHECK(describe(m) == "ggx(alpha 0.3x0.1, F0 0.9,0.6,0.3, diffuse 0)");
  Material lambert;
  CHECK(describe(lambert) == "lambert(0.8)");
}
