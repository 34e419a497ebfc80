// The subsurface bake (bake/subsurface/): a flat slab under uniform light against R_total·E/π,
// the hierarchical sum against the direct one, energy with no absorption, light through a thin
// part, and the refusals.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/subsurface/dipole_gather.h"
#include "bake/subsurface/subsurface_baker.h"
#include "bake/subsurface/subsurface_part.h"
#include "numerics/constants.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"

using namespace prt;
using namespace prt::bake;

namespace {

const double kSqrtFourPi = std::sqrt(4.0 * numerics::kPi);

subsurface::DipoleCoefficients marble() {
  return subsurface::find_subsurface_preset("marble")->coefficients;
}

// Exit radiance of vertex v, channel c, under uniform sky radiance 1 (L_0 = √(4π)).
double furnace_exit(const TransferData& d, std::size_t v, int c) {
  const std::size_t K = d.coefficients_per_channel();
  return d.coefficients[(v * d.channels + c) * K] * kSqrtFourPi;
}

// Exit radiance under a distant point light of unit irradiance-per-π from direction `to_light`
// (radiance SH L_k = Y_k(ω)).
double directional_exit(const TransferData& d, std::size_t v, int c, glm::dvec3 to_light) {
  const int order = static_cast<int>(d.order);
  std::vector<double> y(static_cast<std::size_t>(order * order));
  sh::evaluate(order, to_light.x, to_light.y, to_light.z, y.data());
  const std::size_t K = y.size();
  double sum = 0;
  for (std::size_t k = 0; k < K; ++k) sum += d.coefficients[(v * d.channels + c) * K + k] * y[k];
  return sum;
}

}  // namespace

TEST_CASE("subsurface slab under uniform light exits R_total times E over pi away from edges") {
  // A 200 × 200 mm plane (one scene unit = 200 mm, mm_per_unit = 200) in 100 × 100 cells of 2 mm,
  // marble: 1/σ_tr = 8.5, 6.2, 4.0 mm; z_r = 0.46 .. 0.33 mm. Vertices further than the radius
  // holding all but 0.1% of the profile from every edge see an infinite plane.
  const scene::Scene plane = scene::make_quad({-0.5f, 0.f, 0.5f}, {1.f, 0.f, 0.f}, {0.f, 0.f, -1.f},
                                              100, 100, glm::vec3(0.5f));
  BakeOptions o;
  o.kind = TransferKind::Shadowed;
  o.order = 3;
  o.samples = 16;
  SubsurfaceBakeOptions ss;
  ss.materials = {marble()};
  ss.mm_per_unit = 200.0;
  ss.gather.energy_clamp = false;  // the clamp would pin an overshoot to R_total exactly
  // The direct sum gives the same to 3e-4 here (measured); the test of the hierarchy is below.
  for (bool reference : {false}) {
    ss.gather.reference = reference;
    const SubsurfaceBakeResult r = bake_subsurface_transfer(plane, o, ss);
    const subsurface::DipoleMaterial m = *subsurface::make_dipole(marble());
    REQUIRE(r.bake.data.channels == 3);
    double worst = 0;
    int interior = 0;
    for (std::size_t v = 0; v < plane.positions.size(); ++v) {
      const glm::vec3 p = plane.positions[v];
      const double edge_mm = (0.5 - std::max(std::abs(p.x), std::abs(p.z))) * 200.0;
      if (edge_mm < m.channels[0].radius_for_tail(1e-3)) continue;
      ++interior;
      for (int c = 0; c < 3; ++c) {
        // E = π under radiance 1, so R_total·E/π = R_total.
        const double expected = m.channels[c].total();
        worst = std::max(worst, std::abs(furnace_exit(r.bake.data, v, c) / expected - 1.0));
      }
    }
    CAPTURE(reference, interior, worst);
    REQUIRE(interior > 1000);  // 4,489 of 10,201
    // 0.1% of the profile lies beyond the edge margin; the sum over 2 mm cells (the receiver's
    // own cell and the near ones integrated as discs, docs/SUBSURFACE.md) adds its quadrature
    // error, measured −1.6% (red) to −1.9% (blue) at 1–4 mm cells by the direct sum, and the
    // hierarchy at the default ε = 0.2 adds up to 1% (2.7% in all, measured): 3%. With point
    // samples for the near cells the sum was 4–5.5% low, so the bound can fail.
    REQUIRE(worst < 0.03);
  }
}

namespace {

// A sphere (translucent, material 0) on a floor (opaque) and its shadowed transfer S.
struct SphereOnFloor {
  scene::Scene scene;
  SubsurfaceSamples samples;
};

SphereOnFloor sphere_on_floor(int rings, int segments, int order) {
  SphereOnFloor f;
  f.scene = scene::make_uv_sphere({0.f, 0.5f, 0.f}, 0.5f, rings, segments, false, glm::vec3(0.5f));
  const std::size_t sphere_vertices = f.scene.positions.size();
  scene::append_scene(f.scene, scene::make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f},
                                                8, 8, glm::vec3(0.5f)));
  BakeOptions o;
  o.kind = TransferKind::Shadowed;
  o.order = order;
  o.samples = 64;
  o.keep_albedo_apart = true;
  const BakeResult s = bake_transfer(f.scene, o);
  f.samples.K = order * order;
  f.samples.transfer.assign(s.data.coefficients.begin(), s.data.coefficients.end());
  f.samples.areas = vertex_areas(f.scene);
  for (std::size_t v = 0; v < f.scene.positions.size(); ++v) {
    f.samples.positions.push_back(glm::dvec3(f.scene.positions[v]) * 100.0);  // mm
    f.samples.areas[v] *= 1e4;
    f.samples.material.push_back(v < sphere_vertices ? 0 : -1);
  }
  return f;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TEST_CASE("subsurface hierarchical sum matches the direct sum within 1 percent at 10k vertices") {
  // 9,902 sphere vertices (100 mm across) over a floor, order 3, skin1 (the shortest profile of
  // the presets here, so the near field matters) and marble (the longest, so the far field does).
  const SphereOnFloor f = sphere_on_floor(100, 100, 3);
  for (const char* name : {"marble", "skin1"}) {
    const std::vector<subsurface::DipoleMaterial> mats = {
        *subsurface::make_dipole(subsurface::find_subsurface_preset(name)->coefficients)};
    SubsurfaceGatherOptions direct;
    direct.reference = true;
    SubsurfaceGatherOptions tree;  // ε = 0.2, the default
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> d = gather_subsurface(f.samples, mats, direct);
    const double t_direct = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    SubsurfaceGatherStats st;
    const std::vector<double> h = gather_subsurface(f.samples, mats, tree, &st);
    const double t_tree = seconds_since(t1);
    double num = 0, den = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      num += (h[i] - d[i]) * (h[i] - d[i]);
      den += d[i] * d[i];
    }
    const double rel_rms = std::sqrt(num / den);
    std::printf(
        "subsurface %s: 10k vertices, direct %.2f s, hierarchical %.2f s (eps 0.2), "
        "relative RMS %.2e, nodes used %llu, samples %llu\n",
        name, t_direct, t_tree, rel_rms, static_cast<unsigned long long>(st.node_evaluations),
        static_cast<unsigned long long>(st.sample_evaluations));
    CAPTURE(name, rel_rms);
    REQUIRE(den > 0);
    REQUIRE(rel_rms < 0.01);
    REQUIRE(st.node_evaluations > 0);  // the hierarchy is used, not a direct sum in disguise
  }
}

TEST_CASE("subsurface energy: with no absorption no vertex returns more than arrives") {
  // σ_a = 0: R_total = 1, so a vertex may at most return what arrives, E/π = 1 under a uniform
  // sky of radiance 1. On a sphere the area within straight-line distance r of a point is πr²
  // (Archimedes), so the sum is the plane's integral cut off at the diameter: ≤ 1 up to the
  // quadrature error, and the energy clamp removes that error.
  const scene::Scene sphere =
      scene::make_uv_sphere({0.f, 0.f, 0.f}, 0.5f, 60, 60, false, glm::vec3(0.5f));
  subsurface::DipoleCoefficients c;
  c.sigma_a = {0.0, 0.0, 0.0};
  c.sigma_s_prime = {0.5, 1.0, 2.0};
  c.eta = 1.3;
  BakeOptions o;
  o.kind = TransferKind::Shadowed;
  o.order = 3;
  o.samples = 16;
  SubsurfaceBakeOptions ss;
  ss.materials = {c};
  ss.mm_per_unit = 20.0;  // a 20 mm ball: the profile (z_v up to 8 mm) reaches around it
  for (bool clamp : {true, false}) {
    ss.gather.energy_clamp = clamp;
    const SubsurfaceBakeResult r = bake_subsurface_transfer(sphere, o, ss);
    double most = 0;
    for (std::size_t v = 0; v < sphere.positions.size(); ++v)
      for (int ch = 0; ch < 3; ++ch) most = std::max(most, furnace_exit(r.bake.data, v, ch));
    CAPTURE(clamp, most);
    if (clamp)
      REQUIRE(most <= 1.0 + 1e-6);  // float storage
    else
      REQUIRE(most <= 1.01);  // the disc quadrature's overshoot, as on the slab
    REQUIRE(most > 0.5);      // and light does come back
  }
}

TEST_CASE("subsurface light from behind crosses a thin part (straight-line distances)") {
  // A 100 × 100 mm sheet of thickness t lit from behind (−Z) only: the front face (+Z) receives
  // no light itself, so all it returns crossed the sheet. Straight-line distance through a 2 mm
  // sheet is 2 mm; along the surface it would be ≥ 100 mm (round the edge) and the glow would
  // vanish. Skin1 (1/σ_tr = 3.7, 1.4, 0.7 mm): red crosses 2 mm well, blue hardly.
  const auto front_back = [](double t_mm) {
    const float half = static_cast<float>(0.5 * t_mm / 100.0);
    const scene::Scene sheet =
        scene::make_box({-0.5f, -0.5f, -half}, {0.5f, 0.5f, half}, 50, false, glm::vec3(0.5f));
    BakeOptions o;
    o.kind = TransferKind::Shadowed;
    o.order = 4;
    o.samples = 64;
    SubsurfaceBakeOptions ss;
    ss.materials = {subsurface::find_subsurface_preset("skin1")->coefficients};
    ss.mm_per_unit = 100.0;
    const SubsurfaceBakeResult r = bake_subsurface_transfer(sheet, o, ss);
    std::size_t front = 0, back = 0;
    for (std::size_t v = 0; v < sheet.positions.size(); ++v) {
      const glm::vec3 p = sheet.positions[v];
      const auto dist = [&](glm::vec3 q) { return glm::length(p - q); };
      if (dist({0, 0, half}) < dist(sheet.positions[front])) front = v;
      if (dist({0, 0, -half}) < dist(sheet.positions[back])) back = v;
    }
    const glm::dvec3 from_behind(0, 0, -1);
    std::array<double, 2> red = {directional_exit(r.bake.data, front, 0, from_behind),
                                 directional_exit(r.bake.data, back, 0, from_behind)};
    return red;
  };
  const std::array<double, 2> thin = front_back(2.0);
  const std::array<double, 2> thick = front_back(30.0);
  std::printf("subsurface thin sheet, red exit front/back: 2 mm %.4f, 30 mm %.2e\n",
              thin[0] / thin[1], thick[0] / thick[1]);
  CAPTURE(thin[0], thin[1], thick[0], thick[1]);
  REQUIRE(thin[1] > 0);
  // Through 2 mm of skin the front glows at a good fraction of the lit back...
  REQUIRE(thin[0] > 0.2 * thin[1]);
  // ...through 30 mm (8 red diffusion lengths) it does not: what the thick front returns is the
  // SH ringing of the order-4 delta light on its own (unlit) face, 6% of the back (measured;
  // the thin front returns 58%): the thin front must beat it severalfold.
  REQUIRE(thin[0] > 4.0 * thick[0]);
  REQUIRE(thick[0] < 0.1 * thick[1]);
}

// A farm bake (bake/subsurface/subsurface_part.h): three shards' rows merged give the single
// bake's transfer, bit for bit (every coefficient, AO and the metadata), shadowed (the inner bake
// keeps the albedo apart and reads S back from floats) and interreflected (R_total as the solve's
// albedo); half the vertices translucent, so a merge that ran the gather on other inputs differs.
TEST_CASE("subsurface bake: merged shards give the single bake's transfer exactly") {
  const scene::Scene scene = scene::make_demo_scene();
  SubsurfaceBakeOptions ss;
  ss.materials = {marble(), subsurface::find_subsurface_preset("skin1")->coefficients};
  ss.vertex_material.assign(scene.positions.size(), -1);
  for (std::size_t v = 0; v < scene.positions.size(); ++v)
    if (v % 3 != 2) ss.vertex_material[v] = static_cast<int32_t>(v % 3);
  for (const TransferKind kind : {TransferKind::Shadowed, TransferKind::Interreflected}) {
    INFO("kind " << static_cast<int>(kind));
    BakeOptions o;
    o.kind = kind;
    o.order = 2;
    o.samples = 16;
    o.ao = true;
    const SubsurfaceBakeResult single = bake_subsurface_transfer(scene, o, ss);
    std::vector<TransferPart> parts;
    for (uint32_t i = 0; i < 3; ++i) parts.push_back(bake_subsurface_part(scene, o, ss, {i, 3}));
    std::vector<const TransferPart*> pointers;
    for (const TransferPart& p : parts) pointers.push_back(&p);
    const SubsurfaceBakeResult merged = merge_subsurface_parts(scene, o, ss, pointers);
    CHECK(merged.bake.data.channels == 3);
    CHECK(merged.bake.data.coefficients == single.bake.data.coefficients);
    CHECK(merged.bake.data.ao == single.bake.data.ao);
    CHECK(merged.bake.data.metadata_json == single.bake.data.metadata_json);
    CHECK(merged.subsurface.translucent_vertices == single.subsurface.translucent_vertices);
    // The parts are needed: a merge of other materials differs.
    SubsurfaceBakeOptions other = ss;
    other.materials[1] = marble();
    CHECK(merge_subsurface_parts(scene, o, other, pointers).bake.data.coefficients !=
          single.bake.data.coefficients);
  }
}

TEST_CASE("subsurface bake refuses what it cannot do with one line") {
  const scene::Scene plane = scene::make_quad({-0.5f, 0.f, 0.5f}, {1.f, 0.f, 0.f}, {0.f, 0.f, -1.f},
                                              4, 4, glm::vec3(0.5f));
  BakeOptions o;
  o.kind = TransferKind::Shadowed;
  SubsurfaceBakeOptions ss;
  ss.materials = {marble()};
  ss.materials[0].sigma_s_prime[1] = -1;
  REQUIRE_THROWS_WITH(bake_subsurface_transfer(plane, o, ss),
                      Catch::Contains("sigma_s' (green) must be finite and > 0"));
  ss.materials = {marble()};
  ss.materials[0].eta = 0.5;
  REQUIRE_THROWS_WITH(bake_subsurface_transfer(plane, o, ss), Catch::Contains("eta must be"));
  ss.materials = {marble()};
  ss.vertex_material.assign(plane.positions.size(), 3);
  REQUIRE_THROWS_WITH(bake_subsurface_transfer(plane, o, ss), Catch::Contains("out of range"));
  ss.vertex_material.clear();
  o.kind = TransferKind::Unshadowed;
  REQUIRE_THROWS_WITH(bake_subsurface_transfer(plane, o, ss),
                      Catch::Contains("shadowed or interreflected"));
  o.kind = TransferKind::Shadowed;
  o.adaptive.enabled = true;
  REQUIRE_THROWS_WITH(bake_subsurface_transfer(plane, o, ss), Catch::Contains("adaptive"));
}
