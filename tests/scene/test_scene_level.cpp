// The procedural level and field (scene/level_scene.h, scene/field_scene.h) and their
// tessellation (scene/shape_layout.h): exact counts, size targets, determinism, closure
// (rays from inside the rooms), winding, and the lamps read back as emitters.
#include <cmath>
#include <set>
#include <string>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "scene/field_scene.h"
#include "scene/glb_writer.h"
#include "scene/level_scene.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/shape_layout.h"
#include "support/test_data.h"

using namespace prt::scene;

TEST_CASE("layout_counts gives the tessellation's exact counts", "[scene][level]") {
  for (uint64_t seed : {1u, 7u}) {
    const ShapeLayout level = make_level_layout({seed, 5, 150}).layout;
    for (double cell : {3.0, 0.5, 0.21}) {
      const Scene s = tessellate_layout(level, cell);
      const LayoutCounts n = layout_counts(level, cell);
      CHECK(n.vertices == s.positions.size());
      CHECK(n.triangles == s.triangles.size());
      CHECK(s.normals.size() == s.positions.size());
      CHECK(s.albedo.size() == s.positions.size());
      // every vertex is used by some triangle (holes drop the vertices they enclose)
      std::vector<char> used(s.positions.size(), 0);
      for (const glm::uvec3& t : s.triangles) used[t.x] = used[t.y] = used[t.z] = 1;
      CHECK(std::count(used.begin(), used.end(), 0) == 0);
    }
  }
  const ShapeLayout field = make_field_layout(false);
  const Scene f = tessellate_layout(field, 0.4);
  CHECK(layout_counts(field, 0.4).vertices == f.positions.size());
  CHECK(layout_counts(field, 0.4).triangles == f.triangles.size());
}

TEST_CASE("size targets land within 5% (the CLI's stated tolerance)", "[scene][level]") {
  const ShapeLayout level = make_level_layout({}).layout;
  for (std::size_t target : {60'000u, 1'000'000u}) {
    const double cell = cell_size_for_count(level, target, false);
    const double got = double(layout_counts(level, cell).triangles);
    CHECK(std::fabs(got - double(target)) / double(target) < 0.05);
  }
  const ShapeLayout field = make_field_layout(true);
  for (std::size_t target : {500'000u, 5'000'000u}) {  // counted, not built
    const double cell = cell_size_for_count(field, target, true);
    const double got = double(layout_counts(field, cell).vertices);
    CHECK(std::fabs(got - double(target)) / double(target) < 0.05);
  }
}

TEST_CASE("the level is deterministic for a seed and differs between seeds", "[scene][level]") {
  const Scene a = tessellate_layout(make_level_layout({3, 4, 120}).layout, 0.7);
  const Scene b = tessellate_layout(make_level_layout({3, 4, 120}).layout, 0.7);
  const Scene c = tessellate_layout(make_level_layout({4, 4, 120}).layout, 0.7);
  REQUIRE(a.positions.size() == b.positions.size());
  CHECK(std::equal(a.positions.begin(), a.positions.end(), b.positions.begin()));
  CHECK(std::equal(a.triangles.begin(), a.triangles.end(), b.triangles.begin()));
  CHECK((a.positions.size() != c.positions.size() ||
         !std::equal(a.positions.begin(), a.positions.end(), c.positions.begin())));
}

TEST_CASE("level: names are unique, winding agrees with the normals", "[scene][level]") {
  const LevelLayout level = make_level_layout({2, 6, 400});
  std::set<std::string> names;
  for (const LayoutPart& p : level.layout.parts) CHECK(names.insert(p.name).second);
  CHECK(level.summary.objects >= 400);  // pillars come on top; placement may fail rarely
  const Scene s = tessellate_layout(level.layout, 0.5);
  std::size_t disagree = 0;
  for (const glm::uvec3& t : s.triangles) {
    const glm::dvec3 p0(s.positions[t.x]), p1(s.positions[t.y]), p2(s.positions[t.z]);
    const glm::dvec3 n =
        glm::dvec3(s.normals[t.x]) + glm::dvec3(s.normals[t.y]) + glm::dvec3(s.normals[t.z]);
    if (glm::dot(glm::cross(p1 - p0, p2 - p0), n) <= 0.0) ++disagree;
  }
  CHECK(disagree == 0);
}

// Rays from random points inside the rooms (points inside an object, where some axis ray meets
// a back face, are skipped) in uniform directions: a closed level lets none escape and shows no
// wall's back. Bound: escapes and back faces < 0.1% of 20,000 rays (a ray through a crack
// along an edge could be counted; none is expected).
TEST_CASE("level: rays from inside the rooms neither escape nor see back faces", "[scene][level]") {
  const Scene s = tessellate_layout(make_level_layout({5, 6, 400}).layout, 0.5);
  const RayCaster caster(s);
  prt::numerics::SplitMix64 rng{42};
  const glm::vec3 lo = s.bounds_min(), hi = s.bounds_max();
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::size_t rays = 0, escaped = 0, back = 0, points = 0;
  while (rays < 20000) {
    const glm::vec3 p(lo.x + float(rng.uniform()) * (hi.x - lo.x),
                      0.05f + float(rng.uniform()) * 2.2f,
                      lo.z + float(rng.uniform()) * (hi.z - lo.z));
    bool inside = true;  // every axis ray meets a front face: inside a room or corridor
    for (const glm::vec3& d : axes) {
      const RayCaster::Hit h = caster.intersect(p, d, 0.f, 1e30f);
      inside = inside && h.hit && h.front_face;
    }
    if (!inside) continue;
    ++points;
    for (int k = 0; k < 20; ++k, ++rays) {
      const prt::numerics::Vec2<double> u{rng.uniform(), rng.uniform()};
      const prt::numerics::Vec3<double> w = prt::numerics::sample_uniform_sphere(u);
      const glm::vec3 d(float(w.x), float(w.y), float(w.z));
      const RayCaster::Hit h = caster.intersect(p, d, 0.f, 1e30f);
      if (!h.hit)
        ++escaped;
      else if (!h.front_face)
        ++back;
    }
  }
  INFO(points << " points, " << escaped << " escaped, " << back << " back faces");
  CHECK(double(escaped) / double(rays) < 1e-3);
  CHECK(double(back) / double(rays) < 1e-3);
}

TEST_CASE("level: the lamps are read back as emitters by name", "[scene][level]") {
  const LevelLayout level = make_level_layout({1, 3, 30});
  const Scene s = tessellate_layout(level.layout, 1.0);
  const std::string path = prt::test::output_path("level_emitters.glb").string();
  write_glb(path, s);
  const Scene loaded = load_scene(path);
  std::size_t emitters = 0;
  std::set<std::string> materials;
  for (const ScenePrimitive& p : loaded.primitives) {
    const float e = std::max({p.emission.x, p.emission.y, p.emission.z});
    if (e <= 0.f) continue;
    ++emitters;
    materials.insert(p.material);
    const float expected = p.material == "lamp_corridor" ? kCorridorLampRadiance : kLampRadiance;
    CHECK(e == Approx(expected).epsilon(1e-6));  // the largest channel of each colour is 1
  }
  CHECK(emitters == std::size_t(level.summary.lamps + level.summary.corridors));
  CHECK(materials == std::set<std::string>{"lamp_warm", "lamp_cool", "lamp_corridor"});
  REQUIRE(loaded.cameras.size() == 1);
  CHECK(loaded.cameras[0].name == "camera");
}
