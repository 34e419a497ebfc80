// Glossy surfaces lit by emitters (bake/glossy_emitter_gather.h gathers, prt/emitters/
// glossy_emitter_radiance.h shades): a GGX floor under a large square lamp (2 × 2 at height 1,
// unit emission, black elsewhere), exit radiance at several vertices and views against a direct
// numerical integration of L_e · f · cos θi over the lamp that shares no code with the SH path.
// The integration is checked first against Lambert's closed form for the irradiance from a
// polygon. Expected error: the SH band limit of the product f·cos × lamp at the file's order,
// measured here with the lamp's EXACT projection (dense quadrature, no rays), plus the gather's
// Monte Carlo noise (4096 Sobol' directions).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/glossy_emitter_gather.h"
#include "bake/glossy_transfer_baker.h"
#include "numerics/constants.h"
#include "prt/brdf/material.h"
#include "prt/emitters/glossy_emitter_radiance.h"
#include "prt/glossy/brdf_projection.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"

namespace {

using prt::numerics::kPi;

constexpr float kLampHeight = 1.f, kLampHalf = 1.f;  // the large lamp's height and half side

prt::brdf::Material floor_material() {
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kMicrofacet;
  m.distribution = prt::brdf::NormalDistribution::kGgx;
  m.fresnel = prt::brdf::FresnelMode::kNone;  // F = 1: the lobe alone
  m.alpha_x = m.alpha_y = 0.4;
  m.diffuse = prt::brdf::grey(0.1);
  return m;
}

// Floor y = 0 (normal +y, 2.4 × 2.4, 6 × 6 cells) and the lamp: the square |x|, |z| ≤ 1 at
// y = 1 facing down (its own primitive, so its vertices are its own).
prt::scene::Scene lamp_scene(float half = kLampHalf) {
  prt::scene::Scene floor = prt::scene::make_quad({-1.2f, 0.f, -1.2f}, {0.f, 0.f, 2.4f},
                                                  {2.4f, 0.f, 0.f}, 6, 6, glm::vec3(0.5f), "floor");
  floor.primitives[0].brdf = floor_material();
  const prt::scene::Scene lamp =
      prt::scene::make_quad({-half, kLampHeight, -half}, {2 * half, 0.f, 0.f}, {0.f, 0.f, 2 * half},
                            1, 1, glm::vec3(0.5f), "lamp");
  prt::scene::append_scene(floor, lamp);
  floor.primitives[1].material = "lamp";  // the emitter's name in the responses
  return floor;
}

// The responses of a lamp emitting unit radiance with nothing else lit: 1 on the lamp's
// vertices; the floor's value cannot reach a floor vertex (a plane does not see itself), so it
// is set to 0.3 to show that it is not picked up.
prt::EmitterResponses lamp_responses(const prt::scene::Scene& s, std::size_t floor_vertices) {
  prt::EmitterResponses r;
  r.emitters.push_back({"lamp", {1.f, 1.f, 1.f}});
  for (std::size_t v = 0; v < s.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) {
      r.positions.push_back(s.positions[v][c]);
      r.normals.push_back(s.normals[v][c]);
      r.responses.push_back(v < floor_vertices ? 0.3f : 1.f);
    }
  for (const glm::uvec3& t : s.triangles)
    for (int a = 0; a < 3; ++a) r.triangles.push_back(t[a]);
  return r;
}

// ∫_lamp g(ω_local) cos θ_lamp / r² dA by the midpoint rule on an m × m grid, ω_local the
// direction from p toward the lamp point in p's frame rows (t, b, n) = (x, z, y) of the floor.
// The lamp is at distance ≥ 1 and g smooth there: the rule's error is O(1/m²).
template <class G>
void integrate_lamp(const glm::dvec3& p, int m, G&& g, double half = kLampHalf) {
  const double h = 2.0 * half / m, da = h * h;
  for (int a = 0; a < m; ++a)
    for (int c = 0; c < m; ++c) {
      const glm::dvec3 q(-half + (a + 0.5) * h, kLampHeight, -half + (c + 0.5) * h);
      const glm::dvec3 d = q - p;
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      const glm::dvec3 w = d / r;  // world; cos at the lamp = w.y (its normal is −y)
      g(prt::brdf::Vec3{w.x, w.z, w.y}, w.y / r2 * da);
    }
}

// The vertex's frame in the glossy file (rows t, b, n), as the relighter builds it.
struct Frame {
  double f[9];
};
Frame frame_of(const prt::GlossyTransferData& d, std::size_t v) {
  Frame frame;
  REQUIRE(prt::glossy_vertex_frame(d, v, frame.f).ok());
  return frame;
}
prt::brdf::Vec3 to_local(const Frame& frame, const glm::dvec3& dir) {
  const double* f = frame.f;
  return {f[0] * dir.x + f[1] * dir.y + f[2] * dir.z, f[3] * dir.x + f[4] * dir.y + f[5] * dir.z,
          f[6] * dir.x + f[7] * dir.y + f[8] * dir.z};
}

// Lambert's closed form: ∫_polygon cos θ dω = ½ |Σ_k γ_k n·(a_k × a_k+1)/|a_k × a_k+1||.
double polygon_cosine_integral(const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 corners[4] = {{-kLampHalf, kLampHeight, -kLampHalf},
                                 {kLampHalf, kLampHeight, -kLampHalf},
                                 {kLampHalf, kLampHeight, kLampHalf},
                                 {-kLampHalf, kLampHeight, kLampHalf}};
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const glm::dvec3 a = glm::normalize(corners[k] - p),
                     b = glm::normalize(corners[(k + 1) % 4] - p);
    const glm::dvec3 c = glm::cross(a, b);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, c) / glm::length(c);
  }
  return 0.5 * std::abs(sum);
}

struct Case {
  std::size_t vertex;
  glm::dvec3 eye;
};

}  // namespace

TEST_CASE("the lamp quadrature reproduces Lambert's closed form for a polygon",
          "[glossy][emitters]") {
  for (const glm::dvec3 p :
       {glm::dvec3(0, 0, 0), glm::dvec3(0.8, 0, -0.4), glm::dvec3(1.2, 0, 1.2)}) {
    double numeric = 0;
    integrate_lamp(p, 400, [&](const prt::brdf::Vec3& w, double dw) { numeric += w.z * dw; });
    const double exact = polygon_cosine_integral(p, {0, 1, 0});
    INFO("p = " << p.x << "," << p.z << ": " << numeric << " vs " << exact);
    CHECK(std::abs(numeric - exact) < 1e-5 * exact);  // midpoint rule, h = 0.005: O(h²)
  }
}

TEST_CASE("glossy floor under a lamp: gathered emitter radiance against direct integration",
          "[glossy][emitters]") {
  const prt::scene::Scene scene = lamp_scene();
  const std::size_t floor_vertices = 49;
  const prt::EmitterResponses responses = lamp_responses(scene, floor_vertices);
  const prt::brdf::Material material = floor_material();
  const auto brdf = prt::brdf::make_brdf(material);
  REQUIRE(brdf.ok());
  // Interior vertices (grid index j·7 + i at x = −1.2 + 0.4 j, z = −1.2 + 0.4 i): the centre,
  // one under the lamp's edge, one outside it; views from above, oblique and grazing.
  const std::vector<Case> cases = {{24, {0.3, 2.0, 1.5}},   {24, {-2.5, 0.9, 0.4}},
                                   {32, {-1.5, 1.5, -2.0}}, {32, {2.0, 0.6, 1.0}},
                                   {38, {-2.0, 1.0, 0.0}},  {10, {2.5, 1.2, -0.3}}};
  // Stated band-limit bounds (relative to the true value, worst over the cases), measured with
  // the exact projection: see docs/GLOSSY.md, "Emitters on glossy surfaces".
  struct OrderBound {
    int order;
    double truncation_bound;
  };
  double previous_worst = 1e9;
  for (const OrderBound ob : {OrderBound{4, 0.08}, OrderBound{6, 0.03}, OrderBound{8, 0.02}}) {
    const int n = ob.order, K = n * n;
    prt::bake::GlossyBakeOptions bake;
    bake.order = n;
    bake.samples = 16;  // the frames and materials are what the gather needs
    const prt::GlossyTransferData glossy = prt::bake::bake_glossy_transfer(scene, bake).data;
    prt::bake::GlossyEmitterGatherOptions gather;
    gather.samples = 4096;
    prt::bake::GlossyEmitterGatherStatistics stats;
    const prt::GlossyEmitterRadiance g =
        prt::bake::gather_glossy_emitters(scene, glossy, responses, gather, &stats);
    REQUIRE(prt::validate_glossy_emitter_radiance(g).ok());
    std::vector<prt::BrdfProjection> projections;
    for (const prt::brdf::Material& m : glossy.materials) {
      auto p = prt::BrdfProjection::create(m, n);
      REQUIRE(p.ok());
      projections.push_back(std::move(p).value());
    }
    const std::vector<float> white = {1.f, 1.f, 1.f};
    double worst_truncation = 0, worst_total = 0;
    for (const Case& c : cases) {
      const glm::dvec3 p(scene.positions[c.vertex]);
      const Frame frame = frame_of(glossy, c.vertex);
      const prt::brdf::Vec3 wo = normalize(to_local(frame, glm::normalize(c.eye - p)));
      // The truth: ∫ f(ωi, ωo) cos θi L_e dω over the lamp, L_e = 1.
      double truth = 0;
      std::vector<double> exact_l(K, 0.0), y(K);
      integrate_lamp(p, 400, [&](const prt::brdf::Vec3& w_world, double dw) {
        const prt::brdf::Vec3 wi = to_local(frame, glm::dvec3(w_world.x, w_world.z, w_world.y));
        truth += (*brdf)->eval(wi, wo).g * wi.z * dw;
        prt::sh::evaluate(n, wi.x, wi.y, wi.z, y.data());
        for (int i = 0; i < K; ++i) exact_l[i] += y[i] * dw;
      });
      // The band-limited value: b(ωo) · (the lamp's exact projection at order n).
      std::vector<double> b(3 * K);
      projections[glossy.material_of_vertex[c.vertex]].evaluate(wo, b.data());
      double band_limited = 0;
      for (int i = 0; i < K; ++i) band_limited += b[K + i] * exact_l[i];
      // The pipeline: gathered G, shaded toward the eye.
      float out[3] = {0, 0, 0};
      const double eye[3] = {c.eye.x, c.eye.y, c.eye.z};
      REQUIRE(
          prt::shade_glossy_emitters(g, white, glossy, projections, eye, c.vertex, 1, out).ok());
      const double truncation = std::abs(band_limited - truth) / truth;
      const double total = std::abs(out[1] - truth) / truth;
      const double noise = std::abs(out[1] - band_limited) / truth;
      std::printf(
          "order %d vertex %zu view θo %.0f°: truth %.5f, band-limited %.5f (%.2f%%), "
          "gathered %.5f (%.2f%%; %.2f%% from the band-limited value)\n",
          n, c.vertex, std::acos(wo.z) * 180 / kPi, truth, band_limited, 100 * truncation, out[1],
          100 * total, 100 * noise);
      CHECK(truncation < ob.truncation_bound);
      // The gather's Monte Carlo error against the exact projection: 4096 stratified directions
      // over the hemisphere with the lamp's 2.1 sr edge in it; measured ≤ 0.5%, bound 1.5%.
      CHECK(noise < 0.015);
      CHECK(total < ob.truncation_bound + 0.015);  // end to end: band limit + noise
      CHECK(out[0] == out[1]);                     // grey BRDF and white responses
      worst_truncation = std::max(worst_truncation, truncation);
      worst_total = std::max(worst_total, total);
    }
    std::printf(
        "order %d: worst band-limit error %.2f%%, worst total %.2f%%; gather %.3f s, "
        "%llu rays\n",
        n, 100 * worst_truncation, 100 * worst_total, stats.seconds,
        static_cast<unsigned long long>(stats.rays));
    CHECK(worst_truncation < previous_worst);  // the error falls with the order
    previous_worst = worst_truncation;
  }
}

TEST_CASE("glossy emitter radiance is linear in the emitter colours", "[glossy][emitters]") {
  const prt::scene::Scene scene = lamp_scene();
  const prt::EmitterResponses responses = lamp_responses(scene, 49);
  prt::bake::GlossyBakeOptions bake;
  bake.order = 5;
  bake.samples = 16;
  const prt::GlossyTransferData glossy = prt::bake::bake_glossy_transfer(scene, bake).data;
  prt::bake::GlossyEmitterGatherOptions gather;
  gather.samples = 256;
  const prt::GlossyEmitterRadiance g =
      prt::bake::gather_glossy_emitters(scene, glossy, responses, gather);
  std::vector<prt::BrdfProjection> projections;
  for (const prt::brdf::Material& m : glossy.materials)
    projections.push_back(std::move(prt::BrdfProjection::create(m, 5)).value());
  const double eye[3] = {0.4, 1.8, 2.2};
  const std::size_t V = scene.vertex_count();
  std::vector<float> once(3 * V, 0.f), twice(3 * V, 0.f);
  REQUIRE(
      prt::shade_glossy_emitters(g, {1.f, 0.5f, 0.25f}, glossy, projections, eye, 0, V, once.data())
          .ok());
  REQUIRE(
      prt::shade_glossy_emitters(g, {2.f, 1.f, 0.5f}, glossy, projections, eye, 0, V, twice.data())
          .ok());
  double brightest = 0;
  for (float x : once) brightest = std::max(brightest, double(x));
  REQUIRE(brightest > 0.05);
  for (std::size_t k = 0; k < once.size(); ++k)
    CHECK(std::abs(twice[k] - 2.f * once[k]) <= 1e-6 * brightest);
  // The lamp's own vertices (the last four) show its emission from below, plus what its
  // Lambert 0.5 reflects of the floor's 0.3 (at most 0.5 · 0.3); nothing from above.
  const std::size_t lamp_vertex = V - 1;
  REQUIRE(g.emitter_of_vertex[lamp_vertex] == 0);
  REQUIRE(g.emitter_of_vertex[0] == prt::kNotAnEmitter);
  float lamp_out[3] = {0, 0, 0};
  const double below[3] = {0.2, 0.1, 0.3}, above[3] = {0.2, 3.0, 0.3};
  REQUIRE(prt::shade_glossy_emitters(g, {1.f, 1.f, 1.f}, glossy, projections, below, lamp_vertex, 1,
                                     lamp_out)
              .ok());
  CHECK(lamp_out[0] >= 1.f);
  CHECK(lamp_out[0] <= 1.f + 0.5f * 0.3f);
  lamp_out[0] = 0.f;
  REQUIRE(prt::shade_glossy_emitters(g, {1.f, 1.f, 1.f}, glossy, projections, above, lamp_vertex, 1,
                                     lamp_out)
              .ok());
  CHECK(lamp_out[0] == 0.f);
  // The channels follow the colour: (1, 0.5, 0.25) on a grey BRDF.
  CHECK(std::abs(once[3 * 24 + 1] - 0.5f * once[3 * 24]) <= 1e-6 * brightest);
  // Bad colours and mismatched data are refused, not shaded.
  CHECK_FALSE(
      prt::shade_glossy_emitters(g, {1.f, -1.f, 0.f}, glossy, projections, eye, 0, V, once.data())
          .ok());
  CHECK_FALSE(
      prt::shade_glossy_emitters(g, {1.f, 1.f}, glossy, projections, eye, 0, V, once.data()).ok());
  prt::scene::Scene other = scene;
  other.triangles.pop_back();
  CHECK_THROWS_AS(prt::bake::gather_glossy_emitters(other, glossy, responses, gather),
                  prt::bake::BakeError);
}

TEST_CASE("a small lamp: area sampling cuts the gather's noise, both estimators agree",
          "[glossy][emitters]") {
  // A 0.3 × 0.3 lamp at height 1 (0.09 sr from below): 256 hemisphere directions meet it about
  // 4 times per vertex. The gathered lamp projection G against its exact projection (the
  // midpoint rule of the first test case), relative L2 over the SH coefficients, at the floor's
  // interior vertices; order 4 (16 coefficients).
  const float half = 0.15f;
  const prt::scene::Scene scene = lamp_scene(half);
  const prt::EmitterResponses responses = lamp_responses(scene, 49);
  prt::bake::GlossyBakeOptions bake;
  bake.order = 4;
  bake.samples = 16;
  const prt::GlossyTransferData glossy = prt::bake::bake_glossy_transfer(scene, bake).data;
  const int K = 16;
  const auto error_of = [&](int emitter_samples, uint64_t seed) {
    prt::bake::GlossyEmitterGatherOptions o;
    o.samples = 256;
    o.emitter_samples = emitter_samples;
    o.seed = seed;
    const prt::GlossyEmitterRadiance g =
        prt::bake::gather_glossy_emitters(scene, glossy, responses, o);
    double num = 0, den = 0;
    for (std::size_t v : {8u, 16u, 24u, 30u, 40u}) {
      const Frame frame = frame_of(glossy, v);
      std::vector<double> exact(K, 0.0), y(K);
      integrate_lamp(
          glm::dvec3(scene.positions[v]), 200,
          [&](const prt::brdf::Vec3& w, double dw) {
            const prt::brdf::Vec3 l = to_local(frame, glm::dvec3(w.x, w.z, w.y));
            prt::sh::evaluate(4, l.x, l.y, l.z, y.data());
            for (int i = 0; i < K; ++i) exact[i] += y[i] * dw;
          },
          half);
      for (int i = 0; i < K; ++i) {
        const double d = g.coefficients[(v * 3 + 1) * K + i] - exact[i];
        num += d * d;
        den += exact[i] * exact[i];
      }
    }
    return std::sqrt(num / den);
  };
  double hemisphere = 0, mixed = 0;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    hemisphere = std::max(hemisphere, error_of(0, seed));
    mixed = std::max(mixed, error_of(64, seed));
  }
  std::printf(
      "small lamp, order 4, 256 directions: worst relative L2 error of G over 4 seeds: "
      "hemisphere only %.2f%%, + 64 area samples %.2f%%\n",
      100 * hemisphere, 100 * mixed);
  CHECK(mixed < 0.05);               // measured 1.5%: the area samples carry the lamp
  CHECK(mixed < 0.25 * hemisphere);  // measured 40%: a few hemisphere hits
}

TEST_CASE("glossy emitter radiance: validation and the per-vertex combination by hand",
          "[glossy][emitters]") {
  prt::GlossyEmitterRadiance g;
  g.order = 2;
  g.vertex_count = 2;
  g.emitters = {{"a", {1, 1, 1}}, {"b", {1, 1, 1}}};
  g.coefficients.resize(2 * 2 * 3 * 4);
  for (std::size_t k = 0; k < g.coefficients.size(); ++k) g.coefficients[k] = float(k % 7) - 2.f;
  g.emitter_of_vertex = {prt::kNotAnEmitter, 1};
  REQUIRE(prt::validate_glossy_emitter_radiance(g).ok());
  // Vertex 1, channel c, coefficient i: Σ_e colour_e,c · G[((1·2 + e)·3 + c)·4 + i].
  const std::vector<float> colors = {0.5f, 1.f, 2.f, 3.f, 0.f, 0.25f};
  float out[12];
  REQUIRE(prt::combine_glossy_emitters(g, colors, 1, out).ok());
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 4; ++i) {
      double expected = 0;
      for (int e = 0; e < 2; ++e)
        expected += colors[3 * e + c] * g.coefficients[((2 + e) * 3 + c) * 4 + i];
      CHECK(out[c * 4 + i] == Approx(expected).margin(1e-6));
    }
  CHECK_FALSE(prt::combine_glossy_emitters(g, colors, 2, out).ok());  // vertex out of range
  prt::GlossyEmitterRadiance bad = g;
  bad.coefficients.pop_back();
  CHECK_FALSE(prt::validate_glossy_emitter_radiance(bad).ok());
  bad = g;
  bad.coefficients[5] = std::nanf("");
  CHECK_FALSE(prt::validate_glossy_emitter_radiance(bad).ok());
  bad = g;
  bad.emitter_of_vertex[0] = 2;
  CHECK_FALSE(prt::validate_glossy_emitter_radiance(bad).ok());
  bad = g;
  bad.order = 0;
  CHECK_FALSE(prt::validate_glossy_emitter_radiance(bad).ok());
  bad = g;
  bad.emitters.clear();
  CHECK_FALSE(prt::validate_glossy_emitter_radiance(bad).ok());
}
