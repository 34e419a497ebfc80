// Tests of bake/cpca/relit_metric.h and CpcaOptions::row_metric (prt/glossy/cpca_transfer.h): the
// relit metric against closed forms and an independent Monte Carlo estimate of the relit error, the
// identity metric against the plain compressor, exactness at full rank, and refused metrics.
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/cpca/compressor.h"
#include "bake/cpca/relit_metric.h"
#include "fixtures/synthetic_glossy.h"
#include "numerics/constants.h"
#include "prt/glossy/brdf_projection.h"
#include "sh/zonal.h"

using prt::CpcaOptions;
using prt::CpcaTransfer;
using prt::GlossyTransferData;

namespace {

prt::brdf::Material glossy_material() {
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kMicrofacet;
  m.distribution = prt::brdf::NormalDistribution::kGgx;
  m.alpha_x = m.alpha_y = 0.3;
  m.specular = prt::brdf::grey(0.04);
  m.diffuse = prt::brdf::grey(0.3);
  return m;
}

template <typename T>
T require(prt::Result<T> r) {
  INFO((r.ok() ? std::string() : r.status().message()));
  REQUIRE(r.ok());
  return std::move(r).value();
}

// tr(δᵀ G δ) for one grey n²×n² error δ and metric G.
double metric_norm2(const std::vector<double>& g, const std::vector<double>& delta, int n2) {
  double s = 0.0;
  for (int i = 0; i < n2; ++i)
    for (int k = 0; k < n2; ++k)
      for (int j = 0; j < n2; ++j) s += delta[i * n2 + j] * g[i * n2 + k] * delta[k * n2 + j];
  return s;
}

// Independent estimate of E_ωo E_L[(bᵀ δ L)²] under white lighting (E[L Lᵀ] = I):
// E_ωo |δᵀ b(ω_o)|², ω_o uniform on the hemisphere by random sampling, b's channels averaged.
double relit_error2(const prt::BrdfProjection& p, const std::vector<double>& delta, int n2,
                    int samples, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> b(3 * n2);
  double sum = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double z = u(rng), phi = 2.0 * prt::numerics::kPi * u(rng), r = std::sqrt(1.0 - z * z);
    p.evaluate({r * std::cos(phi), r * std::sin(phi), z}, b.data());
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < n2; ++j) {
        double t = 0.0;
        for (int i = 0; i < n2; ++i) t += b[c * n2 + i] * delta[i * n2 + j];
        sum += t * t / 3.0;
      }
    }
  }
  return sum / samples;
}

}  // namespace

TEST_CASE("Relit metric of a Lambert surface is the clamped cosine's outer product",
          "[cpca][metric]") {
  // For Lambert, b_i(ω_o) = ρ/π · z_l for m = 0 (i = l(l+1)) and 0 otherwise, whatever the
  // view (sh/zonal.h's clamped-cosine coefficients: an independent closed form). So
  // C = (ρ/π)² z zᵀ, rank one; scaled to a largest eigenvalue of 1 it is z zᵀ/|z|², and the
  // floor adds floor²·I. The kZonal projection is exact for Lambert: tolerance 1e-12.
  GlossyTransferData d = prt::fixtures::synthetic_glossy(20, 5, 1, 64);
  d.materials[0] = prt::brdf::Material{};  // Lambert, ρ = 0.8
  prt::RelitMetricOptions o;
  o.floor = 0.1;
  const std::vector<double> g = require(prt::cpca_relit_metric(d, o));
  const int n2 = 25;
  REQUIRE(g.size() == std::size_t(n2) * n2);
  std::vector<double> z(n2, 0.0);
  double norm2 = 0.0;
  for (int l = 0; l < 5; ++l) {
    z[l * (l + 1)] = prt::sh::clamped_cosine_zonal_coefficient(l);
    norm2 += z[l * (l + 1)] * z[l * (l + 1)];
  }
  CHECK(z[12] == Approx(0.0).margin(1e-15));  // band 3 of the clamped cosine vanishes
  for (int i = 0; i < n2; ++i) {
    for (int k = 0; k < n2; ++k) {
      const double expected = z[i] * z[k] / norm2 + (i == k ? 0.01 : 0.0);
      INFO("G[" << i << "][" << k << "]");
      CHECK(g[i * n2 + k] == Approx(expected).margin(1e-12));
    }
  }
}

TEST_CASE("Relit metric measures the expected relit error of a glossy surface", "[cpca][metric]") {
  // Two errors of equal Frobenius norm, one in the low bands' rows and one in band 4's rows:
  // the glossy lobe (GGX α 0.3) filters band 4, so the relit error of the second is smaller.
  // The metric's ratio tr(δ₁ᵀGδ₁)/tr(δ₂ᵀGδ₂) must match an independent Monte Carlo estimate of
  // the ratio of expected relit errors (random views, 40,000 samples: ~1% noise on each; the
  // metric's 16×32 view grid is accurate to well under 1% for this smooth b). Tolerance 4%.
  // The plain (identity) metric would give a ratio of 1; the measured ratio is far from it.
  GlossyTransferData d = prt::fixtures::synthetic_glossy(20, 5, 1, 64);
  d.materials[0] = glossy_material();
  prt::RelitMetricOptions o;
  o.floor = 1e-6;  // (the floor adds 1e-12·I: negligible here)
  const std::vector<double> g = require(prt::cpca_relit_metric(d, o));
  const int n2 = 25;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  std::vector<double> low(n2 * n2, 0.0), high(n2 * n2, 0.0);
  for (int i = 0; i < n2; ++i)
    for (int j = 0; j < n2; ++j) (i < 9 ? low : high)[i * n2 + j] = gauss(rng);
  double nl = 0, nh = 0;
  for (int e = 0; e < n2 * n2; ++e) {
    nl += low[e] * low[e];
    nh += high[e] * high[e];
  }
  for (double& x : high) x *= std::sqrt(nl / nh);
  const double metric_ratio = metric_norm2(g, low, n2) / metric_norm2(g, high, n2);
  const prt::BrdfProjection p = require(prt::BrdfProjection::create(glossy_material(), 5));
  const double mc_ratio =
      relit_error2(p, low, n2, 40000, 11) / relit_error2(p, high, n2, 40000, 12);
  INFO("metric ratio " << metric_ratio << ", Monte Carlo ratio " << mc_ratio);
  CHECK(metric_ratio == Approx(mc_ratio).epsilon(0.04));
  CHECK(mc_ratio > 5.0);  // measured 14.7
}

TEST_CASE("CPCA under the identity metric is the plain compression, bit for bit",
          "[cpca][metric]") {
  // W = I exactly (Jacobi leaves a diagonal matrix alone), so every step is the plain one.
  const GlossyTransferData d = prt::fixtures::synthetic_glossy(200, 3, 3, 128);
  CpcaOptions o;
  o.clusters = 4;
  o.vectors = 5;
  const CpcaTransfer plain = require(prt::cpca_compress(d, o));
  const std::size_t n2 = 9;
  o.row_metric.assign(3 * n2 * n2, 0.0);
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n2; ++i) o.row_metric[(c * n2 + i) * n2 + i] = 1.0;
  const CpcaTransfer same = require(prt::cpca_compress(d, o));
  CHECK(same.cluster_of_vertex == plain.cluster_of_vertex);
  CHECK(same.means == plain.means);
  CHECK(same.basis == plain.basis);
  CHECK(same.weights == plain.weights);
}

TEST_CASE("CPCA under the relit metric: exact at full rank, lower relit error at a fixed size",
          "[cpca][metric]") {
  GlossyTransferData d = prt::fixtures::synthetic_glossy(400, 5, 1, 256);
  d.materials[0] = glossy_material();
  CpcaOptions o;
  o.row_metric = require(prt::cpca_relit_metric(d));
  {
    // 40 vertices in 4 clusters with K = 40: every member in mean + span, to rounding. The map
    // back by W⁻¹ (condition number ≤ 1/floor = 20) scales the float rounding: 1e-4.
    GlossyTransferData small = prt::fixtures::synthetic_glossy(40, 5, 1, 256);
    small.materials[0] = glossy_material();
    o.clusters = 4;
    o.vectors = 40;
    const CpcaTransfer t = require(prt::cpca_compress(small, o));
    CHECK(prt::cpca_relative_rms_error(t, small.matrices.data()) < 1e-4);
  }
  // At Q = 8, K = 4 the metric spends the vectors where the lobe sees them: the expected relit
  // error (white lighting, uniform views: the metric itself with a negligible floor, which the
  // previous test checks against Monte Carlo) must drop clearly below the plain compression's
  // (a 15% margin), while the plain matrix error rises.
  prt::RelitMetricOptions exact;
  exact.floor = 1e-6;
  const std::vector<double> relit = require(prt::cpca_relit_metric(d, exact));
  o.clusters = 8;
  o.vectors = 4;
  const CpcaTransfer weighted = require(prt::cpca_compress(d, o));
  CpcaOptions plain_options = o;
  plain_options.row_metric.clear();
  const CpcaTransfer plain = require(prt::cpca_compress(d, plain_options));
  const double relit_weighted =
      prt::cpca_metric_relative_rms_error(weighted, d.matrices.data(), relit);
  const double relit_plain = prt::cpca_metric_relative_rms_error(plain, d.matrices.data(), relit);
  const double matrix_weighted = prt::cpca_relative_rms_error(weighted, d.matrices.data());
  const double matrix_plain = prt::cpca_relative_rms_error(plain, d.matrices.data());
  INFO("relit: metric " << relit_weighted << ", plain " << relit_plain << "; matrix: metric "
                        << matrix_weighted << ", plain " << matrix_plain);
  CHECK(relit_weighted < 0.85 * relit_plain);  // measured 0.143 against 0.186
  CHECK(matrix_weighted > matrix_plain);
  // A target is met in the metric it is given in.
  o.vectors = 0;
  o.target_relative_rms = 0.05;
  o.max_vectors = 16;
  const CpcaTransfer t = require(prt::cpca_compress(d, o));
  CHECK(prt::cpca_metric_relative_rms_error(t, d.matrices.data(), o.row_metric) <= 0.05);
}

TEST_CASE("CPCA refuses a malformed metric with a one-line message", "[cpca][metric]") {
  const GlossyTransferData d = prt::fixtures::synthetic_glossy(30, 2, 1, 64);
  CpcaOptions o;
  o.clusters = 2;
  o.vectors = 2;
  auto refused = [&](const std::vector<double>& metric, const char* what) {
    o.row_metric = metric;
    auto r = prt::cpca_compress(d, o);
    REQUIRE_FALSE(r.ok());
    INFO(r.status().message());
    CHECK(r.status().message().find(what) != std::string::npos);
    CHECK(r.status().message().find('\n') == std::string::npos);
  };
  std::vector<double> eye(16, 0.0);
  for (int i = 0; i < 4; ++i) eye[i * 4 + i] = 1.0;
  refused(std::vector<double>(15, 1.0), "metric values");
  std::vector<double> bad = eye;
  bad[1] = 0.5;  // not symmetric
  refused(bad, "not symmetric");
  bad = eye;
  bad[5] = -1.0;  // an eigenvalue of −1
  refused(bad, "not positive definite");
  bad = eye;
  bad[0] = NAN;
  refused(bad, "not finite");
  prt::RelitMetricOptions mo;
  mo.floor = 0.0;
  CHECK_FALSE(prt::cpca_relit_metric(d, mo).ok());
}
