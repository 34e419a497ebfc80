// Glossy shading (prt/glossy/relighter.h) on an unshadowed sphere built in memory: Lambert
// through the glossy path against diffuse SH shading, glossy materials against a Monte Carlo
// rendering integral, and the handling of views from below the tangent plane.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "glossy_fixtures.h"
#include "numerics/constants.h"
#include "prt/glossy/relighter.h"
#include "sh/basis.h"
#include "sh/zonal.h"

using prt::GlossyRelighter;
using prt::brdf::Material;
using prt::brdf::MaterialModel;

namespace {

using prt::numerics::kPi;

Material ward_material(double alpha) {
  Material m;
  m.model = MaterialModel::kWard;
  m.diffuse = {0.15, 0.1, 0.05};
  m.specular = prt::brdf::grey(0.6);
  m.alpha_x = m.alpha_y = alpha;
  return m;
}

// L' = M·L (channel c) of vertex v in double, order² values of the file's order.
std::vector<double> transferred(const prt::GlossyTransferData& d, const prt::ShLighting& light,
                                std::size_t v, int c) {
  const int n2 = int(d.order * d.order), k = std::min(n2, light.coefficient_count());
  std::vector<double> out(static_cast<std::size_t>(n2), 0.0);
  const float* m = &d.matrices[v * std::size_t(n2) * n2];
  for (int i = 0; i < n2; ++i)
    for (int j = 0; j < k; ++j)
      out[std::size_t(i)] += double(m[std::size_t(i * n2 + j)]) * light.coefficients_double(c)[j];
  return out;
}

}  // namespace

TEST_CASE("A Lambert material through the glossy path equals diffuse SH shading",
          "[glossy][relighter]") {
  // Diffuse SH shading, independently: exit = ρ/π · Σ_lm A_l L_lm Y_lm(n) (Funk–Hecke with the
  // clamped-cosine factors of sh/zonal.h, evaluated at the global normal). The glossy path
  // rotates L into the tangent frame and dots with b = ρ/π z_l δ_m0, so the two agree up to float
  // rounding of ~36² products: relative 2e-5, plus 1e-6 absolute for near-zero values.
  Material lambert;
  lambert.diffuse = {0.8, 0.6, 0.3};
  const int order = 6;
  prt::GlossyTransferData d = glossy_test::unshadowed_sphere(order, 60, lambert);
  const prt::ShLighting light = glossy_test::band_limited_lighting(order, {0.3, 0.9, 0.2});
  auto relighter = GlossyRelighter::create(d);
  REQUIRE(relighter.ok());
  std::vector<float> out(3 * 60);
  const float eye[3] = {0.f, 0.f, 4.f};
  REQUIRE(relighter->shade(light, eye, 0, 60, out.data()).ok());
  std::vector<double> y(36);
  const double rho[3] = {0.8, 0.6, 0.3};
  int lit = 0;
  for (std::size_t v = 0; v < 60; ++v) {
    const double n[3] = {d.normals[3 * v], d.normals[3 * v + 1], d.normals[3 * v + 2]};
    prt::sh::evaluate(order, n[0], n[1], n[2], y.data());
    const bool faces_eye = 4.0 * n[2] - 1.0 > 0.0;     // n·(eye − p) with p = n
    if (std::fabs(4.0 * n[2] - 1.0) < 1e-3) continue;  // on the tangent plane: float decides
    for (int c = 0; c < 3; ++c) {
      double e = 0.0;
      for (int l = 0; l < order; ++l)
        for (int m = -l; m <= l; ++m)
          e += prt::sh::clamped_cosine_band_factor(l) *
               light.coefficients_double(c)[prt::sh::index(l, m)] * y[prt::sh::index(l, m)];
      const double expected = faces_eye ? rho[c] / kPi * e : 0.0;
      REQUIRE(out[3 * v + c] == Approx(expected).epsilon(2e-5).margin(1e-6));
    }
    lit += faces_eye;
  }
  REQUIRE(lit > 20);
}

TEST_CASE("Glossy sphere: error against the rendering integral within the truncation error",
          "[glossy][relighter]") {
  // Lighting band-limited to order 8. For a glossy Ward (α 0.25) sphere relit at order n, the
  // exact order-n projection differs from the rendering integral by the TAIL Σ_{i ≥ n²} b_i L'_i
  // (bands n..7; computed here from the reference b of order 8 and L' = M·L of order 8, not by
  // the code under test). The rendering integral is estimated independently by importance-
  // sampling the BRDF (48² jittered draws, standard error σ). Required per vertex:
  //   reference path: |ref − MC| ≤ |tail| + 4σ + 1e-9,
  //   fast path:      |fast − MC| ≤ |tail| + 4σ + 2e-3·Σ_i |b_i L'_i| (the isotropic table's
  //                   interpolation, measured below 4e-4 of |b|, and float rounding).
  // At n = 8 the tail is 0, so both must match the Monte Carlo value to its noise.
  const Material material = ward_material(0.25);
  const prt::ShLighting light = glossy_test::band_limited_lighting(8, {0.2, 0.5, 0.85});
  const prt::GlossyTransferData d8 = glossy_test::unshadowed_sphere(8, 40, material);
  const double eye[3] = {0.5, 1.0, 3.0};
  const float eye_f[3] = {0.5f, 1.f, 3.f};
  auto f = prt::brdf::make_brdf(material);
  REQUIRE(f.ok());
  for (int order : {4, 6, 8}) {
    const prt::GlossyTransferData d = glossy_test::unshadowed_sphere(order, 40, material);
    auto relighter = GlossyRelighter::create(d);
    REQUIRE(relighter.ok());
    std::vector<float> fast(3 * 40);
    REQUIRE(relighter->shade(light, eye_f, 0, 40, fast.data()).ok());
    double worst_ratio = 0.0;
    int checked = 0;
    for (std::size_t v = 0; v < 40; ++v) {
      const auto frame = glossy_test::frame_rows(d8, v);
      const double dv[3] = {eye[0] - d8.positions[3 * v], eye[1] - d8.positions[3 * v + 1],
                            eye[2] - d8.positions[3 * v + 2]};
      const prt::brdf::Vec3 wo{frame[0] * dv[0] + frame[1] * dv[1] + frame[2] * dv[2],
                               frame[3] * dv[0] + frame[4] * dv[1] + frame[5] * dv[2],
                               frame[6] * dv[0] + frame[7] * dv[1] + frame[8] * dv[2]};
      if (wo.z <= 0.05 * prt::brdf::length(wo)) continue;  // skip the silhouette's edge
      std::vector<double> b8(3 * 64);
      REQUIRE(prt::project_brdf_slice(*f.value(), 8, wo, {12}, b8.data()).ok());
      double sigma = 0.0;
      const auto mc = glossy_test::monte_carlo_exit(d8, light, eye, v, 48, &sigma);
      double ref[3];
      REQUIRE(prt::shade_glossy_reference(d, light, eye, v, {12}, ref).ok());
      for (int c = 0; c < 3; ++c) {
        const std::vector<double> lp = transferred(d8, light, v, c);
        double tail = 0.0, magnitude = 0.0;
        for (int i = 0; i < 64; ++i) {
          const double term = b8[std::size_t(c * 64 + i)] * lp[std::size_t(i)];
          if (i >= order * order) tail += term;
          magnitude += std::fabs(term);
        }
        const double noise = 4.0 * sigma;
        CHECK(std::fabs(ref[c] - mc[c]) <= std::fabs(tail) + noise + 1e-9);
        const double fast_error = std::fabs(double(fast[3 * v + c]) - mc[c]);
        CHECK(fast_error <= std::fabs(tail) + noise + 2e-3 * magnitude);
        worst_ratio = std::max(worst_ratio, fast_error / (std::fabs(tail) + noise + 1e-12));
      }
      ++checked;
    }
    INFO("order " << order << ": " << checked
                  << " vertices, worst |fast - MC| / (|tail| + 4 sigma) = " << worst_ratio);
    REQUIRE(checked >= 12);
  }
}

TEST_CASE("Glossy shading: views from below the tangent plane and at the vertex give 0",
          "[glossy][relighter]") {
  const prt::GlossyTransferData d = glossy_test::unshadowed_sphere(4, 30, ward_material(0.3));
  const prt::ShLighting light = glossy_test::band_limited_lighting(4, {0, 1, 0});
  auto relighter = GlossyRelighter::create(d);
  REQUIRE(relighter.ok());
  std::vector<float> out(3);
  for (std::size_t v = 0; v < 30; ++v) {
    const float p[3] = {d.positions[3 * v], d.positions[3 * v + 1], d.positions[3 * v + 2]};
    const float behind[3] = {-3.f * p[0], -3.f * p[1], -3.f * p[2]};
    const float in_front[3] = {3.f * p[0], 3.f * p[1], 3.f * p[2]};
    REQUIRE(relighter->shade(light, behind, v, 1, out.data()).ok());
    REQUIRE((out[0] == 0.f && out[1] == 0.f && out[2] == 0.f));
    REQUIRE(relighter->shade(light, p, v, 1, out.data()).ok());  // the eye at the vertex
    REQUIRE((out[0] == 0.f && out[1] == 0.f && out[2] == 0.f));
    REQUIRE(relighter->shade(light, in_front, v, 1, out.data()).ok());
    REQUIRE(std::isfinite(out[0]));
  }
  // Out of range and null pointers are errors.
  const float eye[3] = {0, 0, 3};
  REQUIRE_FALSE(relighter->shade(light, eye, 29, 2, out.data()).ok());
  REQUIRE_FALSE(relighter->shade(light, nullptr, 0, 1, out.data()).ok());
}

TEST_CASE(
    "Glossy shading: RGB transfer holding grey copies equals grey transfer and bad data is refused",
    "[glossy][relighter]") {
  const prt::GlossyTransferData grey = glossy_test::unshadowed_sphere(5, 20, ward_material(0.3));
  prt::GlossyTransferData rgb = grey;
  rgb.channels = 3;
  rgb.matrices.clear();
  const std::size_t block = 25 * 25;
  for (std::size_t v = 0; v < 20; ++v)
    for (int c = 0; c < 3; ++c)
      rgb.matrices.insert(rgb.matrices.end(), grey.matrices.begin() + long(v * block),
                          grey.matrices.begin() + long((v + 1) * block));
  const prt::ShLighting light = glossy_test::band_limited_lighting(5, {1, 1, 0});
  std::vector<float> a(60), b(60);
  const float eye[3] = {1.f, 2.f, 3.f};
  REQUIRE(GlossyRelighter::create(grey)->shade(light, eye, 0, 20, a.data()).ok());
  REQUIRE(GlossyRelighter::create(rgb)->shade(light, eye, 0, 20, b.data()).ok());
  REQUIRE(a == b);

  prt::GlossyTransferData bad = grey;
  bad.material_of_vertex[3] = 5;
  auto refused = GlossyRelighter::create(bad);
  REQUIRE_FALSE(refused.ok());
  REQUIRE(refused.status().message().find("vertex 3") != std::string::npos);
  bad = grey;
  bad.matrices.pop_back();
  REQUIRE_FALSE(GlossyRelighter::create(bad).ok());
  bad = grey;
  bad.tangents[0] = bad.normals[0], bad.tangents[1] = bad.normals[1];
  bad.tangents[2] = bad.normals[2];
  REQUIRE_FALSE(GlossyRelighter::create(bad).ok());
}
