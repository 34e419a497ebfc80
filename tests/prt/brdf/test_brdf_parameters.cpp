// Bad parameters are refused at creation with a one-line message naming the parameter.
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/microfacet.h"
#include "prt/brdf/ward.h"

using namespace prt::brdf;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

template <class T>
void refused(const prt::Result<T>& r, const std::string& must_contain) {
  INFO("expected an error mentioning '" << must_contain << "'");
  REQUIRE_FALSE(r.ok());
  const std::string msg = r.status().message();
  INFO(msg);
  CHECK(msg.find(must_contain) != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

MicrofacetParams micro(double ax, double ay) {
  MicrofacetParams p;
  p.alpha_x = ax;
  p.alpha_y = ay;
  return p;
}

WardParams ward(double ax, double ay) {
  WardParams p;
  p.alpha_x = ax;
  p.alpha_y = ay;
  return p;
}

}  // namespace

TEST_CASE("roughness 0, NaN, infinite, negative or above 1 is refused", "[brdf][params]") {
  for (double bad : {0.0, -0.1, kNaN, kInf, 1e-4, 1.5}) {
    refused(Microfacet::create(micro(bad, 0.5)), "alpha_x");
    refused(Microfacet::create(micro(0.5, bad)), "alpha_y");
    refused(Ward::create(ward(bad, 0.5)), "alpha_x");
    refused(Ward::create(ward(0.5, bad)), "alpha_y");
  }
  refused(Microfacet::create(micro(kNaN, 0.5)), "is NaN");
  CHECK(Microfacet::create(micro(0.001, 1.0)).ok());  // the ends of the range are accepted
}

TEST_CASE("Blinn-Phong: negative or NaN exponent, weights out of range are refused",
          "[brdf][params]") {
  refused(BlinnPhong::create(grey(0.2), grey(0.5), -1.0), "exponent is -1");
  refused(BlinnPhong::create(grey(0.2), grey(0.5), kNaN), "exponent is NaN");
  refused(BlinnPhong::create(grey(0.2), grey(0.5), kInf), "exponent");
  refused(BlinnPhong::create({0.2, -0.1, 0.2}, grey(0.5), 10.0), "k_L (green)");
  refused(BlinnPhong::create(grey(0.6), grey(0.5), 10.0), "k_L + k_G");
  CHECK(BlinnPhong::create(grey(0.5), grey(0.5), 0.0).ok());
}

TEST_CASE("reflectances outside [0, 1] or NaN are refused", "[brdf][params]") {
  refused(Lambert::create({1.2, 0.5, 0.5}), "reflectance (red)");
  refused(Lambert::create({0.5, 0.5, kNaN}), "reflectance (blue)");
  WardParams w = ward(0.2, 0.2);
  w.rho_d = grey(0.5);
  w.rho_s = grey(0.6);
  refused(Ward::create(w), "rho_d + rho_s");
  MicrofacetParams m = micro(0.2, 0.2);
  m.fresnel = FresnelMode::kSchlick;
  m.f0 = {0.5, 2.0, 0.5};
  refused(Microfacet::create(m), "f0 (green)");
  m.fresnel = FresnelMode::kDielectric;
  m.eta = kNaN;
  refused(Microfacet::create(m), "eta is NaN");
  m.eta = 1.0;
  refused(Microfacet::create(m), "eta");
  m.eta = 1.5;
  CHECK(Microfacet::create(m).ok());
}
