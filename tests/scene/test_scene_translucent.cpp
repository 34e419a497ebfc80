// The translucent scenes (scene/translucent_scene.h): counts, bounds, closed outward surfaces
// (welded edges used twice, once each way; volume by the divergence theorem) and the fin's
// thickness measured by rays against its closed form.
#include <cmath>
#include <map>
#include <tuple>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "scene/ray_caster.h"
#include "scene/translucent_scene.h"
#include "sh/constants.h"

using namespace prt::scene;

namespace {

const ScenePrimitive& primitive(const Scene& s, const std::string& name) {
  for (const ScenePrimitive& p : s.primitives)
    if (p.name == name) return p;
  FAIL("no primitive " << name);
  return s.primitives.front();
}

// Welded positions (1e-4 mm grid), then every directed edge of the primitive's triangles:
// closed and consistently oriented when each directed edge occurs once and its reverse once.
bool closed_and_oriented(const Scene& s, const ScenePrimitive& p) {
  std::map<std::tuple<long, long, long>, uint32_t> weld;
  const auto id = [&](uint32_t v) {
    const glm::vec3 q = s.positions[v];
    const auto key =
        std::make_tuple(std::lround(q.x * 1e4), std::lround(q.y * 1e4), std::lround(q.z * 1e4));
    return weld.emplace(key, static_cast<uint32_t>(weld.size())).first->second;
  };
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (uint32_t t = p.first_triangle; t < p.first_triangle + p.triangle_count; ++t) {
    const glm::uvec3 tri = s.triangles[t];
    const uint32_t a = id(tri.x), b = id(tri.y), c = id(tri.z);
    ++directed[{a, b}];
    ++directed[{b, c}];
    ++directed[{c, a}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto reverse = directed.find({edge.second, edge.first});
    if (reverse == directed.end() || reverse->second != 1) return false;
  }
  return !directed.empty();
}

// Σ p0·(p1 × p2) / 6 over the primitive's triangles: its volume when closed and outward.
double signed_volume(const Scene& s, const ScenePrimitive& p) {
  double v = 0;
  for (uint32_t t = p.first_triangle; t < p.first_triangle + p.triangle_count; ++t) {
    const glm::uvec3 tri = s.triangles[t];
    v += glm::dot(glm::dvec3(s.positions[tri.x]),
                  glm::cross(glm::dvec3(s.positions[tri.y]), glm::dvec3(s.positions[tri.z])));
  }
  return v / 6.0;
}

}  // namespace

TEST_CASE("the translucent scene: parts, counts, bounds, closed outward surfaces",
          "[scene][translucent]") {
  const Scene s = make_translucent_scene();
  REQUIRE(s.primitives.size() == 4);
  CHECK(s.cameras.size() == 1);
  CHECK(s.normals.size() == s.positions.size());
  const ScenePrimitive& sphere = primitive(s, "sphere");
  const ScenePrimitive& fin = primitive(s, "fin");
  const ScenePrimitive& slab = primitive(s, "slab");
  CHECK(sphere.vertex_count == 2 + 47 * 96);  // UV sphere: 2 poles + (rings − 1) circles
  CHECK(fin.vertex_count == 2 + 63 * 128);
  // slab 50 × 10 × 40 at 1.5 mm cells: 33 × 7 × 27 segments, six grids
  CHECK(slab.vertex_count == 2 * (8 * 28 + 28 * 34 + 34 * 8));
  CHECK(primitive(s, "ground").vertex_count == 26 * 41);
  const glm::vec3 lo = s.bounds_min(), hi = s.bounds_max();
  CHECK(lo.x == Approx(-80).margin(1e-4));
  CHECK(hi.x == Approx(80).margin(1e-4));
  CHECK(lo.y == Approx(-2).margin(1e-3));  // the fin's lower tip, 2 mm into the ground
  CHECK(hi.y == Approx(38).margin(1e-3));  // its upper tip
  for (const std::string name : {"slab", "sphere", "fin"})
    CHECK(closed_and_oriented(s, primitive(s, name)));
  // Volumes: the box exactly; sphere and fin (the bend is a shear: volume kept) to the
  // inscribed tessellation's deficit, under 0.5% at these ring counts.
  CHECK(signed_volume(s, slab) == Approx(50.0 * 10 * 40).epsilon(1e-5));
  CHECK(signed_volume(s, sphere) == Approx(4.0 / 3 * prt::sh::kPi * 12 * 12 * 12).epsilon(5e-3));
  CHECK(signed_volume(s, fin) == Approx(4.0 / 3 * prt::sh::kPi * 14 * 20 * 1.25).epsilon(5e-3));
}

TEST_CASE("the fin's thickness along Z is 2.5·sqrt(1 − (x/14)² − (y/20)²)",
          "[scene][translucent]") {
  const Scene s = make_translucent_scene();
  const RayCaster caster(s);
  const FinShape f;
  for (const glm::vec2 q :
       {glm::vec2(0, 0), glm::vec2(5, 0), glm::vec2(0, 8), glm::vec2(-7, -6), glm::vec2(10, 10)}) {
    const glm::vec3 from = f.centre + glm::vec3(q.x, q.y, 100.f);
    const RayCaster::Hit first = caster.intersect(from, {0, 0, -1}, 0.f, 1e3f);
    REQUIRE(first.hit);
    CHECK(first.front_face);
    const RayCaster::Hit second = caster.intersect(from, {0, 0, -1}, first.t + 1e-4f, 1e3f);
    REQUIRE(second.hit);
    CHECK_FALSE(second.front_face);  // leaving the fin through its back
    const double expected =
        2.5 * std::sqrt(1.0 - std::pow(q.x / 14.0, 2) - std::pow(q.y / 20.0, 2));
    // the tessellation's chords: under 1% of the thickness at these points
    CHECK(double(second.t - first.t) == Approx(expected).epsilon(0.01));
  }
}

TEST_CASE("the lone slab and sphere", "[scene][translucent]") {
  const Scene slab = make_translucent_slab();
  REQUIRE(slab.primitives.size() == 1);
  CHECK(closed_and_oriented(slab, slab.primitives[0]));
  CHECK(signed_volume(slab, slab.primitives[0]) == Approx(100.0 * 100 * 20).epsilon(1e-5));
  CHECK(slab.bounds_max().y == Approx(0).margin(1e-5));
  const Scene sphere = make_translucent_sphere();
  REQUIRE(sphere.primitives.size() == 1);
  CHECK(closed_and_oriented(sphere, sphere.primitives[0]));
  CHECK(sphere.extent() == Approx(20 * std::sqrt(3.0)).epsilon(1e-4));
}
