// brdf_furnace — white-furnace and sampling tables of the BRDF library (prt/brdf): the
// figures of docs/BRDF.md, printed as Markdown.
//
// Usage: brdf_furnace [strata=512]
// Each albedo is a(ωo) = ∫ f cos θi dωi under a uniform white environment, estimated with
// strata × strata jittered importance samples (seed 1); "±" is the i.i.d. standard error, an
// upper bound for the stratified estimate. The discarded fraction is the share of draws that
// sample() rejects (reflected below the horizon or a back-facing micro-normal).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/fresnel.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/microfacet.h"
#include "prt/brdf/ward.h"
#include "sh/constants.h"

using namespace prt::brdf;

namespace {

using prt::sh::kPi;
const double kThetas[] = {0.0, 30.0, 60.0, 75.0, 85.0, 89.0};

Vec3 outgoing(double deg, double phi) {
  return spherical_direction(std::cos(deg * kPi / 180.0), phi);
}

double discarded_fraction(const Brdf& b, const Vec3& wo, int n) {
  int none = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (!(b.sample(wo, (i + 0.5) / n, (j + 0.5) / n).pdf > 0.0)) ++none;
    }
  }
  return double(none) / (double(n) * n);
}

void header(const char* first) {
  std::printf("| %s |", first);
  for (double t : kThetas) std::printf(" θo=%g° |", t);
  std::printf("\n|---|");
  for (std::size_t i = 0; i < std::size(kThetas); ++i) std::printf("---|");
  std::printf("\n");
}

void albedo_row(const std::string& label, const Brdf& b, int n, double phi = 0.7) {
  std::printf("| %s |", label.c_str());
  double worst_se = 0.0;
  for (double t : kThetas) {
    double se = 0.0;
    const Rgb a = directional_albedo(b, outgoing(t, phi), n, 1, &se);
    worst_se = std::fmax(worst_se, se);
    std::printf(" %.4f |", a.r);
  }
  std::printf(" <!-- max se %.4f -->\n", worst_se);
}

void discard_row(const std::string& label, const Brdf& b, int n) {
  std::printf("| %s |", label.c_str());
  for (double t : kThetas) std::printf(" %.4f |", discarded_fraction(b, outgoing(t, 0.7), n));
  std::printf("\n");
}

Microfacet microfacet(NormalDistribution d, double ax, double ay) {
  MicrofacetParams p;
  p.distribution = d;
  p.alpha_x = ax;
  p.alpha_y = ay;
  return Microfacet::create(p).value();
}

Ward ward(WardForm form, double a) {
  WardParams p;
  p.form = form;
  p.alpha_x = p.alpha_y = a;
  return Ward::create(p).value();
}

const double kAlphas[] = {0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0};

void microfacet_tables(int n) {
  std::printf(
      "\n### Microfacet, F = 1 (white furnace; 1 − albedo is the single-scattering loss)\n\n");
  header("model, α");
  for (auto d : {NormalDistribution::kGgx, NormalDistribution::kBeckmann}) {
    for (double a : kAlphas) {
      albedo_row(std::string(distribution_name(d)) + " " + std::to_string(a).substr(0, 4),
                 microfacet(d, a, a), n);
    }
  }
  for (auto d : {NormalDistribution::kGgx, NormalDistribution::kBeckmann}) {
    albedo_row(std::string(distribution_name(d)) + " (0.1, 0.5), φo = 0", microfacet(d, 0.1, 0.5),
               n, 0.0);
    albedo_row(std::string(distribution_name(d)) + " (0.1, 0.5), φo = 90°", microfacet(d, 0.1, 0.5),
               n, 0.5 * kPi);
  }
  std::printf("\n### Microfacet: fraction of draws discarded by sample()\n\n");
  header("model, α");
  for (auto d : {NormalDistribution::kGgx, NormalDistribution::kBeckmann}) {
    for (double a : kAlphas) {
      discard_row(std::string(distribution_name(d)) + " " + std::to_string(a).substr(0, 4),
                  microfacet(d, a, a), n);
    }
  }
}

void ward_tables(int n) {
  std::printf("\n### Ward, ρd = 0, ρs = 1 (isotropic)\n\n");
  header("form, α");
  for (auto form : {WardForm::kNormalized, WardForm::kOriginal, WardForm::kDuer}) {
    const char* name = form == WardForm::kNormalized ? "normalised"
                       : form == WardForm::kOriginal ? "original"
                                                     : "Dür";
    for (double a : {0.05, 0.1, 0.2, 0.3, 0.5, 1.0}) {
      albedo_row(std::string(name) + " " + std::to_string(a).substr(0, 4), ward(form, a), n);
    }
  }
}

void blinn_phong_table(int n) {
  std::printf("\n### Normalised Blinn-Phong, k_L = 0, k_G = 1\n\n");
  std::printf("Closed-form normal-incidence albedo: ");
  for (double s : {0.0, 1.0, 4.0, 8.0, 16.0, 32.0, 128.0, 1024.0}) {
    std::printf("s=%g: %.4f; ", s, blinn_phong_normal_albedo(s));
  }
  std::printf("\n\n");
  header("exponent s");
  for (double s : {1.0, 8.0, 32.0, 128.0, 1024.0}) {
    albedo_row(std::to_string(static_cast<int>(s)), BlinnPhong::create(grey(0), grey(1), s).value(),
               n);
  }
}

void fresnel_table() {
  std::printf("\n### Schlick against the exact dielectric Fresnel\n\n");
  std::printf("| η | F0 | max abs error | at cos θ |\n|---|---|---|---|\n");
  for (double eta : {1.33, 1.5, 2.0, 2.4}) {
    double worst = 0.0, at = 0.0;
    for (int i = 0; i <= 10000; ++i) {
      const double c = i / 10000.0;
      const double e = std::abs(fresnel_schlick(c, fresnel_f0(eta)) - fresnel_dielectric(c, eta));
      if (e > worst) worst = e, at = c;
    }
    std::printf("| %.2f | %.4f | %.4f | %.4f |\n", eta, fresnel_f0(eta), worst, at);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 512;
  if (n < 1) {
    std::fprintf(stderr, "brdf_furnace: strata must be a positive integer\n");
    return 1;
  }
  std::printf("<!-- brdf_furnace %d: %d samples per entry -->\n", n, n * n);
  std::printf("\n### Lambert, ρ = 1\n\n");
  header("model");
  albedo_row("lambert", Lambert::create(grey(1.0)).value(), n);
  microfacet_tables(n);
  ward_tables(n);
  blinn_phong_table(n);
  fresnel_table();
  return 0;
}
