// The shading paths of prt::GlossyRelighter (prt/glossy/relighter.h): the kernel path
// (prt::GlossyKernel) against the portable per-vertex loop, and compressed transfer
// (create_cpca, prt::CpcaKernel) against the uncompressed matrices. Matrices: the shadowed
// synthetic transfer of fixtures/synthetic_glossy.h; materials: a Ward lobe on some
// vertices and Lambert on the others, so b has both dense and zonal rows.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/cpca/compressor.h"
#include "fixtures/synthetic_glossy.h"
#include "glossy_fixtures.h"
#include "prt/glossy/relighter.h"

using prt::brdf::Material;
using prt::brdf::MaterialModel;

namespace {

constexpr double kUnit = 1.0 / 16777216.0;  // 2⁻²⁴, the unit roundoff of float

prt::GlossyTransferData two_material_data(std::size_t count, int order, int channels) {
  prt::GlossyTransferData d = prt::fixtures::synthetic_glossy(count, order, channels, 256);
  Material ward;
  ward.model = MaterialModel::kWard;
  ward.diffuse = {0.2, 0.1, 0.05};
  ward.specular = prt::brdf::grey(0.5);
  ward.alpha_x = ward.alpha_y = 0.2;
  Material lambert;
  lambert.diffuse = {0.5, 0.6, 0.7};
  d.materials = {ward, lambert};
  for (std::size_t v = 0; v < count; ++v) d.material_of_vertex[v] = v % 3 == 0 ? 1 : 0;
  return d;
}

// b of vertex v toward `eye` exactly as the relighter computes it (float frame and evaluate),
// 3·n² floats; zero below the tangent plane.
std::vector<float> view_vector(const prt::GlossyRelighter& r, const prt::GlossyTransferData& d,
                               const float eye[3], std::size_t v) {
  const int n2 = int(d.order * d.order);
  const std::array<double, 9> f = glossy_test::frame_rows(d, v);
  const double p[3] = {eye[0] - d.positions[3 * v], eye[1] - d.positions[3 * v + 1],
                       eye[2] - d.positions[3 * v + 2]};
  const float local[3] = {float(f[0] * p[0] + f[1] * p[1] + f[2] * p[2]),
                          float(f[3] * p[0] + f[4] * p[1] + f[5] * p[2]),
                          float(f[6] * p[0] + f[7] * p[1] + f[8] * p[2])};
  std::vector<float> b(3 * std::size_t(n2), 0.f);
  if (!(local[2] > 0.f)) return b;
  const prt::BrdfProjection& proj = r.projections()[d.material_of_vertex[v]];
  std::vector<float> scratch(proj.scratch_floats());
  proj.evaluate(local, b.data(), scratch.data());
  return b;
}

// Σ_i |b_i| Σ_j |M_ij| |L_j| of vertex v and channel c: the sum of the magnitudes of the terms a
// float evaluation of b·M·L adds up (the scale of its rounding error).
double term_magnitude(const prt::GlossyTransferData& d, const prt::ShLighting& light,
                      const std::vector<float>& b, std::size_t v, int c) {
  const int n2 = int(d.order * d.order), k = std::min(n2, light.coefficient_count());
  const int cm = d.channels == 3 ? c : 0;
  const float* m = &d.matrices[(v * d.channels + cm) * std::size_t(n2) * n2];
  double sum = 0;
  for (int i = 0; i < n2; ++i) {
    double row = 0;
    for (int j = 0; j < k; ++j)
      row += std::abs(double(m[i * n2 + j]) * light.coefficients_double(c)[j]);
    sum += std::abs(double(b[std::size_t(c * n2 + i)])) * row;
  }
  return sum;
}

std::vector<float> shade_all(const prt::GlossyRelighter& r, const prt::ShLighting& light,
                             const float eye[3]) {
  std::vector<float> out(3 * r.vertex_count(), -1.f);
  prt::GlossyFrame frame;
  REQUIRE(r.prepare(light, &frame).ok());
  REQUIRE(r.shade(frame, eye, 0, r.vertex_count(), out.data()).ok());
  return out;
}

}  // namespace

TEST_CASE("Glossy shading: the kernel path equals the portable path within float rounding",
          "[glossy][kernel]") {
  // Both paths read the same float M, L and b and differ only in the order of the float sums
  // (and the portable path skipping rows whose b is 0). Each result is within
  // γ·Σ|terms| of the exact value, γ = (n² + n²)·2⁻²⁴ for the two nested sums, so the two are
  // within twice that; + 4 for the final products. A wrong row, column, channel or vertex
  // gives errors of the size of the terms themselves.
  for (const auto& [order, channels] : {std::pair{5, 1}, std::pair{3, 3}, std::pair{6, 1}}) {
    const prt::GlossyTransferData d = two_material_data(250, order, channels);
    auto kernel = prt::GlossyRelighter::create(prt::GlossyTransferData(d), {},
                                               prt::GlossyShadingPath::kKernel);
    auto portable = prt::GlossyRelighter::create(prt::GlossyTransferData(d), {},
                                                 prt::GlossyShadingPath::kPortable);
    REQUIRE(kernel.ok());
    REQUIRE(portable.ok());
    CHECK(kernel->path() == prt::GlossyShadingPath::kKernel);
    CHECK_FALSE(kernel->compressed());
    // Lighting of a higher order than the file: both truncate it the same way.
    const prt::ShLighting light = glossy_test::band_limited_lighting(order + 1, {0.3, 0.9, 0.2});
    const float eye[3] = {0.5f, 3.f, 7.f};
    const std::vector<float> a = shade_all(*kernel, light, eye);
    const std::vector<float> b = shade_all(*portable, light, eye);
    const double gamma = (2.0 * order * order + 4.0) * kUnit;
    std::size_t lit = 0;
    double worst = 0;
    for (std::size_t v = 0; v < d.vertex_count; ++v) {
      const std::vector<float> bv = view_vector(*kernel, d, eye, v);
      for (int c = 0; c < 3; ++c) {
        const double bound = 2.0 * gamma * term_magnitude(d, light, bv, v, c) + 1e-30;
        const double diff = std::abs(double(a[3 * v + c]) - double(b[3 * v + c]));
        worst = std::max(worst, diff / bound);
        lit += b[3 * v + c] != 0.f ? 1 : 0;
      }
    }
    INFO("order " << order << ", channels " << channels << ": worst |kernel - portable| / bound "
                  << worst);
    CHECK(worst <= 1.0);
    CHECK(lit > d.vertex_count);  // most vertices face the eye: the comparison is not vacuous
    // A range that starts inside a block of 16 gives the same bits as the whole run.
    std::vector<float> part(3 * 37);
    REQUIRE(kernel->shade(light, eye, 5, 37, part.data()).ok());
    CHECK(std::equal(part.begin(), part.end(), a.begin() + 15));
  }
}

TEST_CASE("Glossy shading of CPCA transfer: within the Cauchy-Schwarz bound of the matrix error",
          "[glossy][cpca]") {
  // For each vertex and channel, e − ẽ = b·(M − M̃)·L, so |e − ẽ| ≤ |b|₂ ‖M − M̃‖_F |L|₂
  // (Cauchy–Schwarz twice). The test checks that bound (+ the float rounding of both
  // evaluations, as above with K more terms) at every vertex, so a wrong cluster, weight or
  // basis vector in the CPCA path fails it; with lossy settings the errors are not zero.
  const int order = 5;
  const prt::GlossyTransferData d = two_material_data(400, order, 1);
  prt::CpcaOptions o;
  o.clusters = 6;
  o.vectors = 4;
  auto cpca = prt::cpca_compress(d, o);
  REQUIRE(cpca.ok());
  auto full = prt::GlossyRelighter::create(prt::GlossyTransferData(d));
  prt::GlossyTransferData geometry = d;
  geometry.matrices.clear();  // create_cpca must not need them
  auto compressed = prt::GlossyRelighter::create_cpca(std::move(geometry), *cpca);
  REQUIRE(full.ok());
  REQUIRE(compressed.ok());
  CHECK(compressed->compressed());
  const prt::ShLighting light = glossy_test::band_limited_lighting(order, {-0.4, 0.8, 0.4});
  const float eye[3] = {-1.f, 2.5f, 6.f};
  const std::vector<float> e = shade_all(*full, light, eye);
  const std::vector<float> e_cpca = shade_all(*compressed, light, eye);
  const std::size_t n2 = order * order, dim = n2 * n2;
  std::vector<double> rec(dim);
  double worst = 0, diff2 = 0, ref2 = 0;
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    prt::cpca_reconstruct(*cpca, v, rec.data());
    double frob = 0, magnitude = 0;
    for (std::size_t k = 0; k < dim; ++k) {
      frob += (rec[k] - d.matrices[v * dim + k]) * (rec[k] - d.matrices[v * dim + k]);
      magnitude += std::abs(rec[k]) + std::abs(double(d.matrices[v * dim + k]));
    }
    const std::vector<float> bv = view_vector(*full, d, eye, v);
    for (int c = 0; c < 3; ++c) {
      double b2 = 0, l2 = 0, bmax = 0;
      for (std::size_t i = 0; i < n2; ++i) {
        b2 += double(bv[c * n2 + i]) * bv[c * n2 + i];
        bmax = std::max(bmax, std::abs(double(bv[c * n2 + i])));
        l2 += light.coefficients_double(c)[i] * light.coefficients_double(c)[i];
      }
      const double lmax = std::sqrt(l2);
      const double rounding = (2.0 * n2 + o.vectors + 4.0) * kUnit * 2.0 *
                              (term_magnitude(d, light, bv, v, c) + bmax * lmax * magnitude);
      const double bound = std::sqrt(b2 * frob * l2) + rounding + 1e-30;
      const double diff = std::abs(double(e[3 * v + c]) - double(e_cpca[3 * v + c]));
      worst = std::max(worst, diff / bound);
      diff2 += diff * diff;
      ref2 += double(e[3 * v + c]) * e[3 * v + c];
    }
  }
  const double relative_rms = std::sqrt(diff2 / ref2);
  const double matrix_error = prt::cpca_relative_rms_error(*cpca, d.matrices.data());
  INFO("worst ratio to the bound " << worst << "; relit relative RMS " << relative_rms
                                   << "; matrix relative RMS " << matrix_error);
  CHECK(worst <= 1.0);
  CHECK(relative_rms > 1e-4);  // lossy: the comparison means something
  CHECK(matrix_error > 1e-3);
}

TEST_CASE("Glossy shading of full-rank CPCA equals the uncompressed shading to float rounding",
          "[glossy][cpca]") {
  // Order 2, K = D = 16: every matrix lies in its cluster's span, so the CPCA form reproduces
  // M to float rounding (tests of prt/glossy/cpca_transfer.h) and so does the shading: relative
  // 1e-5 of the magnitude of the terms (|Δe| ≈ (2n² + K)·2⁻²⁴·Σ|terms| ≈ 3e-6 of it, plus the
  // basis's own rounding); a wrong cluster or vector order gives errors of the size of e itself.
  const prt::GlossyTransferData d = two_material_data(300, 2, 1);
  prt::CpcaOptions o;
  o.clusters = 5;
  o.vectors = 16;
  auto cpca = prt::cpca_compress(d, o);
  REQUIRE(cpca.ok());
  auto full = prt::GlossyRelighter::create(prt::GlossyTransferData(d));
  auto compressed = prt::GlossyRelighter::create_cpca(prt::GlossyTransferData(d), *cpca);
  REQUIRE(full.ok());
  REQUIRE(compressed.ok());
  const prt::ShLighting light = glossy_test::band_limited_lighting(2, {0.3, 0.9, 0.2});
  const float eye[3] = {0.5f, 3.f, 7.f};
  const std::vector<float> e = shade_all(*full, light, eye);
  const std::vector<float> e_cpca = shade_all(*compressed, light, eye);
  double worst = 0;
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    const std::vector<float> bv = view_vector(*full, d, eye, v);
    for (int c = 0; c < 3; ++c) {
      const double scale = term_magnitude(d, light, bv, v, c) + 1e-30;
      worst = std::max(worst, std::abs(double(e[3 * v + c]) - e_cpca[3 * v + c]) / scale);
    }
  }
  INFO("worst |Δe| / Σ|terms| " << worst);
  CHECK(worst < 1e-5);
}

TEST_CASE("Glossy shading refuses a CPCA of other data and a frame of another relighter",
          "[glossy][cpca]") {
  const prt::GlossyTransferData d = two_material_data(120, 3, 1);
  prt::CpcaOptions o;
  o.clusters = 3;
  o.vectors = 2;
  auto cpca = prt::cpca_compress(d, o);
  REQUIRE(cpca.ok());
  const prt::GlossyTransferData other = two_material_data(100, 3, 1);
  auto refused = prt::GlossyRelighter::create_cpca(prt::GlossyTransferData(other), *cpca);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.status().message().find("120 vertices") != std::string::npos);
  auto a = prt::GlossyRelighter::create(prt::GlossyTransferData(d));
  auto b = prt::GlossyRelighter::create_cpca(prt::GlossyTransferData(d), *cpca);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  prt::GlossyFrame frame;
  const prt::ShLighting light = glossy_test::band_limited_lighting(3, {0, 1, 0});
  REQUIRE(a->prepare(light, &frame).ok());
  std::vector<float> out(3 * 4);
  const float eye[3] = {0, 3, 5};
  CHECK_FALSE(b->shade(frame, eye, 0, 4, out.data()).ok());
  CHECK(a->shade(frame, eye, 0, 4, out.data()).ok());
}
