// Shared helpers of the BRDF tests.
#include "brdf_test_support.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/material.h"
#include "prt/brdf/microfacet.h"
#include "prt/brdf/ward.h"
#include "sh/constants.h"

namespace brdf_test {

using namespace prt::brdf;

namespace {

using prt::sh::kPi;

template <class T>
std::shared_ptr<const Brdf> must(prt::Result<T> r) {
  if (!r) throw std::runtime_error("test model refused: " + r.status().message());
  return std::make_shared<T>(std::move(r).value());
}

// GGX + Schlick over a Lambert layer, through make_brdf.
std::shared_ptr<const Brdf> layered(Rgb diffuse, Rgb f0, double ax, double ay) {
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kMicrofacet;
  m.distribution = NormalDistribution::kGgx;
  m.fresnel = FresnelMode::kSchlick;
  m.diffuse = diffuse;
  m.specular = f0;
  m.alpha_x = ax;
  m.alpha_y = ay;
  prt::Result<std::shared_ptr<const Brdf>> made = prt::brdf::make_brdf(m);
  if (!made) throw std::runtime_error("test model refused: " + made.status().message());
  return std::move(made).value();
}

std::shared_ptr<const Brdf> microfacet(NormalDistribution d, double ax, double ay,
                                       FresnelMode f = FresnelMode::kNone) {
  MicrofacetParams p;
  p.distribution = d;
  p.alpha_x = ax;
  p.alpha_y = ay;
  p.fresnel = f;
  return must(Microfacet::create(p));
}

std::shared_ptr<const Brdf> ward(WardForm form, double rd, double rs, double ax, double ay) {
  WardParams p;
  p.form = form;
  p.rho_d = grey(rd);
  p.rho_s = grey(rs);
  p.alpha_x = ax;
  p.alpha_y = ay;
  return must(Ward::create(p));
}

// 6-point Gauss–Legendre nodes and weights on [−1, 1].
constexpr double kGlX[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                            0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
constexpr double kGlW[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                            0.4679139345726910, 0.3607615730481386, 0.1713244923791704};

}  // namespace

std::vector<NamedBrdf> analytic_models() {
  const auto ggx = NormalDistribution::kGgx;
  const auto beck = NormalDistribution::kBeckmann;
  std::vector<NamedBrdf> m;
  m.push_back({"lambert rho=0.8", must(Lambert::create(grey(0.8))), true});
  m.push_back({"blinn-phong kL=0.3 kG=0.7 s=1", must(BlinnPhong::create(grey(0.3), grey(0.7), 1.0)),
               false});
  m.push_back({"blinn-phong kL=0.3 kG=0.7 s=20",
               must(BlinnPhong::create(grey(0.3), grey(0.7), 20.0)), false});
  m.push_back({"blinn-phong kL=0 kG=1 s=200", must(BlinnPhong::create(grey(0.0), grey(1.0), 200.0)),
               false});
  m.push_back({"ward normalized a=0.1", ward(WardForm::kNormalized, 0, 1, 0.1, 0.1), true});
  m.push_back({"ward normalized a=0.5", ward(WardForm::kNormalized, 0, 1, 0.5, 0.5), true});
  m.push_back({"ward normalized rd=0.2 a=(0.1,0.4)",
               ward(WardForm::kNormalized, 0.2, 0.8, 0.1, 0.4), true});
  m.push_back({"ward original a=(0.3,0.1)", ward(WardForm::kOriginal, 0, 1, 0.3, 0.1), false});
  m.push_back({"ward duer rd=0.3 a=0.2", ward(WardForm::kDuer, 0.3, 0.7, 0.2, 0.2), false});
  m.push_back({"ggx a=0.1", microfacet(ggx, 0.1, 0.1), true});
  m.push_back({"ggx a=0.5", microfacet(ggx, 0.5, 0.5), true});
  m.push_back({"ggx a=1", microfacet(ggx, 1.0, 1.0), true});
  m.push_back({"ggx a=(0.1,0.5)", microfacet(ggx, 0.1, 0.5), true});
  m.push_back({"ggx a=0.3 dielectric", microfacet(ggx, 0.3, 0.3, FresnelMode::kDielectric), true});
  m.push_back({"beckmann a=0.1", microfacet(beck, 0.1, 0.1), true});
  m.push_back({"beckmann a=0.5", microfacet(beck, 0.5, 0.5), true});
  m.push_back({"beckmann a=1", microfacet(beck, 1.0, 1.0), true});
  m.push_back(
      {"beckmann a=(0.5,0.15) schlick", microfacet(beck, 0.5, 0.15, FresnelMode::kSchlick), true});
  // Microfacet lobes over a Lambert layer, built as scenes build them (prt/brdf/material.h):
  // a glTF dielectric (F0 0.04) and an anisotropic coloured one.
  m.push_back(
      {"layered ggx kd=0.4 F0=0.04 a=0.09", layered(grey(0.4), grey(0.04), 0.09, 0.09), true});
  m.push_back({"layered ggx kd=0.3 F0=.5/.4/.3 a=(0.6,0.15)",
               layered(grey(0.3), Rgb{0.5, 0.4, 0.3}, 0.6, 0.15), true});
  // glTF 2.0's BRDF (prt/brdf/gltf_pbr.h), as the glTF loader makes it: a half-metallic plastic
  // (sampling, pdf and reciprocity; its albedo exceeds 1 towards grazing angles for bright base
  // colours, so no energy claim) and an anisotropic metal (albedo ≤ 1: F ≤ 1 times the lobe).
  const auto gltf = [](Rgb base, double metallic, double ax, double ay) {
    prt::brdf::Material g;
    g.model = prt::brdf::MaterialModel::kGltf;
    g.diffuse = base;
    g.metallic = metallic;
    g.alpha_x = ax;
    g.alpha_y = ay;
    g.specular = grey(0.04);
    return prt::brdf::make_brdf(g).value();
  };
  m.push_back(
      {"gltf base=.2/.4/.8 m=0.5 a=0.16", gltf(Rgb{0.2, 0.4, 0.8}, 0.5, 0.16, 0.16), false});
  m.push_back(
      {"gltf metal base=.9/.6/.3 a=(0.4,0.1)", gltf(Rgb{0.9, 0.6, 0.3}, 1.0, 0.4, 0.1), true});
  return m;
}

std::vector<Vec3> test_outgoing_directions() {
  std::vector<Vec3> out;
  for (double deg : {0.0, 30.0, 60.0, 80.0, 88.0}) {
    out.push_back(spherical_direction(std::cos(deg * kPi / 180.0), 0.7));
  }
  return out;
}

namespace {

// 6×6 Gauss–Legendre over one cell.
double gauss_cell(const Brdf& brdf, const Vec3& wo, double c0, double c1, double p0, double p1) {
  double sum = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double c = c0 + 0.5 * (c1 - c0) * (kGlX[i] + 1.0);
    for (int j = 0; j < 6; ++j) {
      const double p = p0 + 0.5 * (p1 - p0) * (kGlX[j] + 1.0);
      sum += kGlW[i] * kGlW[j] * brdf.pdf(wo, spherical_direction(c, p));
    }
  }
  return sum * 0.25 * (c1 - c0) * (p1 - p0);
}

// Adaptive refinement: split into 2×2 while the children disagree with the parent by more than
// tol (absolute, in probability), halving nothing — each child keeps tol, so the error bound
// per leaf is tol, and at most max_depth levels.
double adaptive_cell(const Brdf& brdf, const Vec3& wo, double c0, double c1, double p0, double p1,
                     double whole, double tol, int depth) {
  const double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1);
  const double q[4] = {gauss_cell(brdf, wo, c0, cm, p0, pm), gauss_cell(brdf, wo, cm, c1, p0, pm),
                       gauss_cell(brdf, wo, c0, cm, pm, p1), gauss_cell(brdf, wo, cm, c1, pm, p1)};
  const double sum = q[0] + q[1] + q[2] + q[3];
  if (depth <= 0 || std::abs(sum - whole) <= tol) return sum;
  return adaptive_cell(brdf, wo, c0, cm, p0, pm, q[0], tol, depth - 1) +
         adaptive_cell(brdf, wo, cm, c1, p0, pm, q[1], tol, depth - 1) +
         adaptive_cell(brdf, wo, c0, cm, pm, p1, q[2], tol, depth - 1) +
         adaptive_cell(brdf, wo, cm, c1, pm, p1, q[3], tol, depth - 1);
}

}  // namespace

double integrate_pdf_cell(const Brdf& brdf, const Vec3& wo, double c0, double c1, double p0,
                          double p1, int sub) {
  double sum = 0.0;
  const double dc = (c1 - c0) / sub, dp = (p1 - p0) / sub;
  for (int a = 0; a < sub; ++a) {
    for (int b = 0; b < sub; ++b) {
      const double ca = c0 + a * dc, pb = p0 + b * dp;
      const double whole = gauss_cell(brdf, wo, ca, ca + dc, pb, pb + dp);
      sum += adaptive_cell(brdf, wo, ca, ca + dc, pb, pb + dp, whole, 1e-9, 8);
    }
  }
  return sum;
}

double integrate_pdf_sphere(const Brdf& brdf, const Vec3& wo, int res_theta, int sub) {
  double total = 0.0;
  const int res_phi = 2 * res_theta;
  for (int i = 0; i < res_theta; ++i) {
    for (int j = 0; j < res_phi; ++j) {
      total +=
          integrate_pdf_cell(brdf, wo, -1.0 + 2.0 * i / res_theta, -1.0 + 2.0 * (i + 1) / res_theta,
                             2.0 * kPi * j / res_phi, 2.0 * kPi * (j + 1) / res_phi, sub);
    }
  }
  return total;
}

double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {  // series for P(a, x)
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000 && std::abs(term) > std::abs(sum) * 1e-16; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
  }
  // Continued fraction for Q(a, x), modified Lentz.
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(log_prefix) * h;
}

ChiSquareResult chi_square(const Brdf& brdf, const Vec3& wo, long long samples, uint64_t seed,
                           int res_theta, int sub) {
  const int res_phi = 2 * res_theta;
  const int cells = res_theta * res_phi;
  std::vector<double> observed(cells + 1, 0.0), expected(cells + 1, 0.0);
  ChiSquareResult r;
  r.samples = samples;
  const double n = static_cast<double>(samples);
  Rng rng{seed};
  for (long long k = 0; k < samples; ++k) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const BrdfSample s = brdf.sample(wo, u1, u2);
    if (!(s.pdf > 0.0)) {
      ++r.no_sample;
      observed[cells] += 1.0;
      continue;
    }
    if (s.wi.z <= 0.0) {
      ++r.below_horizon;
      continue;
    }
    double phi = std::atan2(s.wi.y, s.wi.x);
    if (phi < 0.0) phi += 2.0 * kPi;
    const int i = std::clamp(static_cast<int>(s.wi.z * res_theta), 0, res_theta - 1);
    const int j = std::clamp(static_cast<int>(phi / (2.0 * kPi) * res_phi), 0, res_phi - 1);
    observed[i * res_phi + j] += 1.0;
  }
  for (int i = 0; i < res_theta; ++i) {
    for (int j = 0; j < res_phi; ++j) {
      const double e =
          integrate_pdf_cell(brdf, wo, double(i) / res_theta, double(i + 1) / res_theta,
                             2.0 * kPi * j / res_phi, 2.0 * kPi * (j + 1) / res_phi, sub);
      r.pdf_integral += e;
      expected[i * res_phi + j] = e * n;
    }
  }
  expected[cells] = std::max(0.0, 1.0 - r.pdf_integral) * n;
  // Pool cells of low expectation, smallest first; a cell expected ~0 but hit is a failure.
  std::vector<int> order(cells + 1);
  for (int i = 0; i <= cells; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
  double pool_e = 0.0, pool_o = 0.0;
  for (int idx : order) {
    if (expected[idx] < 1e-9 * n && observed[idx] > 0 && r.failure.empty()) {
      r.failure = "a cell with expectation " + std::to_string(expected[idx]) + " received " +
                  std::to_string(observed[idx]) + " samples";
    }
    if (expected[idx] < 5.0 || pool_e > 0.0) {
      pool_e += expected[idx];
      pool_o += observed[idx];
      if (pool_e < 5.0) continue;
      const double d = pool_o - pool_e;
      r.statistic += d * d / pool_e;
      ++r.dof;
      pool_e = pool_o = 0.0;
      continue;
    }
    const double d = observed[idx] - expected[idx];
    r.statistic += d * d / expected[idx];
    ++r.dof;
  }
  if (pool_e > 0.0) {  // a last pool below 5: fold it into the statistic anyway
    const double d = pool_o - pool_e;
    r.statistic += d * d / pool_e;
    ++r.dof;
  }
  r.dof -= 1;
  if (r.below_horizon > 0 && r.failure.empty()) {
    r.failure = std::to_string(r.below_horizon) + " samples with pdf > 0 below the horizon";
  }
  r.p_value = gamma_q(0.5 * r.dof, 0.5 * r.statistic);
  return r;
}

}  // namespace brdf_test
