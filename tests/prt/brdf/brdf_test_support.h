// Shared helpers of the BRDF tests: the model configurations under test, quadrature of a pdf
// over (cos θ, φ) cells, and the chi-square goodness-of-fit test of a sampler against its pdf.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "numerics/rng.h"
#include "prt/brdf/brdf.h"

namespace brdf_test {

using prt::brdf::Brdf;
using prt::brdf::Vec3;

struct NamedBrdf {
  std::string name;
  std::shared_ptr<const Brdf> brdf;
  bool energy_conserving;  // whether its albedo is claimed to stay ≤ 1 for every ωo
};

// Every analytic configuration the property tests run over (Lambert, Blinn-Phong, Ward in both
// forms, GGX and Beckmann iso/aniso, with and without Fresnel). Fails the test if a create()
// refuses one.
std::vector<NamedBrdf> analytic_models();

// Outgoing directions the tests use: normal incidence, 30°, 60°, 80° and 88° from the normal, at
// an azimuth that is not a symmetry axis of the anisotropic models.
std::vector<Vec3> test_outgoing_directions();

// ∫ over the cell [c0, c1] × [p0, p1] of (cos θ, φ) of pdf(wo, ω) dω (dω = dcos θ dφ), by
// `sub` × `sub` sub-cells of 6 × 6 Gauss–Legendre points each, each refined adaptively (2 × 2
// splits, up to 8 levels) until its children agree with it to 1e-9 — the reflection samplers'
// pdfs carry a 1/|ωi + ωo| factor that peaks sharply near the horizon at grazing ωo.
double integrate_pdf_cell(const Brdf& brdf, const Vec3& wo, double c0, double c1, double p0,
                          double p1, int sub);

// ∫ pdf over the whole sphere on a res_theta × 2 res_theta cell grid.
double integrate_pdf_sphere(const Brdf& brdf, const Vec3& wo, int res_theta, int sub);

struct ChiSquareResult {
  double statistic = 0;
  int dof = 0;
  double p_value = 0;
  long long samples = 0;
  long long no_sample = 0;      // draws that returned pdf = 0
  long long below_horizon = 0;  // draws with pdf > 0 but ωi·n ≤ 0 (a failure)
  double pdf_integral = 0;      // ∫ pdf over the upper hemisphere, from the cells
  std::string failure;          // non-empty when a cell with zero expectation was hit
};

// Draws `samples` directions from brdf.sample(wo, ·) with a fixed-seed generator, bins them on a
// res_theta (cos θ in [0, 1]) × 2 res_theta (φ) grid plus one "no sample" cell, takes expected
// counts from integrate_pdf_cell, pools cells expected below 5 (in ascending order of
// expectation) and computes Pearson's statistic and its p-value.
ChiSquareResult chi_square(const Brdf& brdf, const Vec3& wo, long long samples, uint64_t seed,
                           int res_theta, int sub);

// The regularised upper incomplete gamma function Q(a, x); the chi-square p-value with k
// degrees of freedom is Q(k/2, χ²/2).
double gamma_q(double a, double x);

// A reproducible uniform generator in [0, 1): rng.uniform() (numerics/rng.h, 53 bits).
using Rng = prt::numerics::SplitMix64;

}  // namespace brdf_test
