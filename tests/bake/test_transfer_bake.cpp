// Baker plumbing: thread-count determinism, input refusal, RGB channels, metadata and a round
// trip through the coefficient-file writer and reader.
#include <cstring>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/transfer_baker.h"
#include "prt/formats/transfer_file.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "support/test_data.h"
#include "support/transfer_references.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;

namespace {

// A corner: grey floor, red and green walls, a white sphere: occlusion, colour bleeding.
prt::scene::Scene make_corner_scene() {
  prt::scene::Scene s = prt::scene::make_quad({-1.f, 0, -1.f}, {0, 0, 2}, {2, 0, 0}, 12, 12,
                                              glm::vec3(0.7f), "floor");
  prt::scene::append_scene(s, prt::scene::make_quad({-1.f, 0, -1.f}, {0, 1, 0}, {0, 0, 2}, 8, 12,
                                                    glm::vec3(0.7f, 0.1f, 0.1f), "red wall"));
  prt::scene::append_scene(s, prt::scene::make_quad({-1.f, 0, -1.f}, {2, 0, 0}, {0, 1, 0}, 12, 8,
                                                    glm::vec3(0.1f, 0.7f, 0.1f), "green wall"));
  prt::scene::append_scene(s, prt::scene::make_uv_sphere({0.2f, 0.3f, 0.1f}, 0.3f, 12, 24, false,
                                                         glm::vec3(0.8f), "sphere"));
  return s;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("bakes are bit-identical for 1 and 2 threads") {
  const prt::scene::Scene scene = make_corner_scene();
  BakeOptions o;
  // Both interreflection paths: the compact gather (bounces) and the dense one (BiCGSTAB).
  o.dense_gather = GENERATE(false, true);
  o.kind = prt::TransferKind::Interreflected;
  o.order = 3;
  o.samples = 64;
  o.ao = true;
  o.bent_normals = true;
  o.threads = 1;
  const auto one = bake_transfer(scene, o);
  o.threads = 2;
  const auto two = bake_transfer(scene, o);
  REQUIRE(one.data.channels == 3);
  REQUIRE(one.stats.compact_gather == !o.dense_gather);
  REQUIRE(one.stats.jacobi_bounces + one.stats.solver_iterations > 0);
  CHECK(same_bytes(one.data.coefficients, two.data.coefficients));
  CHECK(same_bytes(one.data.ao, two.data.ao));
  CHECK(same_bytes(one.data.bent_normals, two.data.bent_normals));
  // A different seed does change the result (the comparison above is not vacuous).
  o.seed = 2;
  const auto other = bake_transfer(scene, o);
  CHECK_FALSE(same_bytes(one.data.coefficients, other.data.coefficients));
}

TEST_CASE("colour bleeding: RGB albedo gives 3 channels and the red wall tints the floor") {
  const prt::scene::Scene scene = make_corner_scene();
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 1;
  o.samples = 128;
  const auto inter = bake_transfer(scene, o);
  o.kind = prt::TransferKind::Shadowed;
  const auto shadowed = bake_transfer(scene, o);
  REQUIRE(inter.data.channels == 3);
  // Floor vertex next to the red wall (x = −1 + 2/12, z = 0): grey albedo, so shadowed
  // transfer is equal in r, g, b; interreflection adds more red than green there.
  const std::size_t v = 1 * 13 + 6;
  REQUIRE(scene.positions[v].x == Approx(-1.f + 2.f / 12.f));
  const float* s = &shadowed.data.coefficients[v * 3];
  const float* t = &inter.data.coefficients[v * 3];
  CHECK(s[0] == s[1]);
  CHECK(s[0] == s[2]);
  CHECK(t[0] > s[0]);
  CHECK(t[0] - s[0] > 1.5f * (t[1] - s[1]));
  // Metadata: the bake parameters and the basis convention.
  const auto meta = nlohmann::json::parse(inter.data.metadata_json);
  CHECK(meta["transfer"] == "interreflected");
  CHECK(meta["samples_per_vertex"] == 128);
  CHECK(meta["sh_basis"].get<std::string>().find("no Condon-Shortley") != std::string::npos);
}

TEST_CASE(
    "albedo not below 1 (or negative, NaN) and absurd options are refused with the primitive "
    "named") {
  prt::scene::Scene scene = make_corner_scene();
  BakeOptions o;
  for (const float bad : {1.0f, 1.5f, -0.1f, std::nanf("")}) {
    prt::scene::Scene s = scene;
    const prt::scene::ScenePrimitive& wall = s.primitives[1];
    for (uint32_t v = wall.first_vertex; v < wall.first_vertex + wall.vertex_count; ++v)
      s.albedo[v].y = bad;
    CHECK_THROWS_WITH(bake_transfer(s, o),
                      Catch::Contains("red wall") && Catch::Contains("outside [0, 1)"));
  }
  o.order = 0;
  CHECK_THROWS_AS(bake_transfer(scene, o), prt::bake::BakeError);
  o.order = 3;
  o.samples = 0;
  CHECK_THROWS_AS(bake_transfer(scene, o), prt::bake::BakeError);
  o.samples = 16;
  o.kind = prt::TransferKind::Haar;
  CHECK_THROWS_AS(bake_transfer(scene, o), prt::bake::BakeError);
  CHECK_THROWS_AS(bake_transfer(prt::scene::Scene{}, BakeOptions{}), prt::bake::BakeError);
}

TEST_CASE("a baked scene survives write_transfer_file / read_transfer_file") {
  const prt::scene::Scene scene = make_corner_scene();
  BakeOptions o;
  o.order = 4;
  o.samples = 32;
  o.ao = true;
  o.bent_normals = true;
  const auto baked = bake_transfer(scene, o);
  const std::string path = prt::test::output_path("baked_corner.prt").string();
  REQUIRE(prt::write_transfer_file(path, baked.data).ok());
  auto read = prt::read_transfer_file(path);
  REQUIRE(read.ok());
  const prt::TransferData& d = read.value();
  CHECK(d.kind == prt::TransferKind::Shadowed);
  CHECK(d.order == 4);
  CHECK(d.channels == 3);
  CHECK(d.vertex_count == scene.positions.size());
  CHECK(d.fingerprint == baked.data.fingerprint);
  CHECK(same_bytes(d.coefficients, baked.data.coefficients));
  CHECK(same_bytes(d.positions, baked.data.positions));
  CHECK(same_bytes(d.ao, baked.data.ao));
  CHECK(same_bytes(d.bent_normals, baked.data.bent_normals));
  CHECK(d.metadata_json == baked.data.metadata_json);
  REQUIRE(d.primitives.size() == 4);
  CHECK(d.primitives[1].name == "red wall");
  // f16 storage keeps 11 significant bits.
  o.precision = prt::Precision::F16;
  const auto half = bake_transfer(scene, o);
  const std::string half_path = prt::test::output_path("baked_corner_f16.prt").string();
  REQUIRE(prt::write_transfer_file(half_path, half.data).ok());
  auto half_read = prt::read_transfer_file(half_path);
  REQUIRE(half_read.ok());
  for (std::size_t i = 0; i < half.data.coefficients.size(); ++i)
    REQUIRE(half_read.value().coefficients[i] ==
            Approx(half.data.coefficients[i]).epsilon(1e-3).margin(1e-7));
  std::filesystem::remove(path);
  std::filesystem::remove(half_path);
}

TEST_CASE("ray caster: hits, barycentrics, faces, packets and an empty scene") {
  prt::scene::Scene tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // CCW seen from +Z
  tri.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  tri.albedo = {glm::vec3(0.5f), glm::vec3(0.5f), glm::vec3(0.5f)};
  tri.triangles = {{0, 1, 2}};
  const prt::scene::RayCaster caster(tri);
  const auto h = caster.intersect({0.2f, 0.3f, 2.f}, {0, 0, -1}, 0.f, 10.f);
  REQUIRE(h.hit);
  CHECK(h.t == Approx(2.0));
  CHECK(h.u == Approx(0.2));  // weight of vertex 1 = (1, 0, 0)
  CHECK(h.v == Approx(0.3));  // weight of vertex 2 = (0, 1, 0)
  CHECK(h.front_face);
  const auto back = caster.intersect({0.2f, 0.3f, -2.f}, {0, 0, 1}, 0.f, 10.f);
  CHECK(back.hit);
  CHECK_FALSE(back.front_face);
  CHECK_FALSE(caster.intersect({0.8f, 0.8f, 2.f}, {0, 0, -1}, 0.f, 10.f).hit);
  CHECK(caster.occluded({0.2f, 0.3f, 2.f}, {0, 0, -1}, 0.f, 10.f));
  CHECK_FALSE(caster.occluded({0.2f, 0.3f, 2.f}, {0, 0, -1}, 0.f, 1.5f));  // tfar before it
  glm::vec3 dirs[16];
  bool occ[16];
  prt::scene::RayCaster::Hit hits[16];
  // Aim at (0.01 + 0.06 i, 0.25, 0) from (0, 0.25, 1): away from the edges x = 0, x + y = 1.
  auto x_of = [](int i) { return 0.01f + 0.06f * static_cast<float>(i); };
  for (int i = 0; i < 16; ++i) dirs[i] = glm::normalize(glm::vec3(x_of(i), 0.f, -1.f));
  caster.occluded_packet({0.f, 0.25f, 1.f}, dirs, 16, 100.f, occ);
  caster.intersect_packet({0.f, 0.25f, 1.f}, dirs, 16, 100.f, hits);
  for (int i = 0; i < 16; ++i) {
    const bool inside = x_of(i) < 0.75f;  // x + y < 1 at y = 0.25
    INFO("ray " << i);
    CHECK(occ[i] == inside);
    CHECK(hits[i].hit == inside);
    CHECK(hits[i].front_face == inside);  // from +Z: the front
  }
  // Without the side (face_side = false): the same hits, front_face left false.
  prt::scene::RayCaster::Hit bare[16];
  caster.intersect_packet({0.f, 0.25f, 1.f}, dirs, 16, 100.f, bare, false);
  for (int i = 0; i < 16; ++i) {
    INFO("ray " << i);
    CHECK(bare[i].hit == hits[i].hit);
    CHECK(bare[i].t == hits[i].t);
    CHECK(bare[i].triangle == hits[i].triangle);
    CHECK(bare[i].u == hits[i].u);
    CHECK(bare[i].v == hits[i].v);
    CHECK_FALSE(bare[i].front_face);
  }
  // ε_v = 4·2^-23·max|p| + 2^-18·(longest edge) (scene/ray_offset.h): vertex 0 sits at the origin
  // (no ulp term), the others at 1; every vertex touches the √2 edge.
  const std::vector<float>& eps = caster.vertex_ray_starts().offset;
  CHECK(eps[0] == Approx(std::ldexp(std::sqrt(2.0), -18)).epsilon(1e-6));
  CHECK(eps[1] == Approx(std::ldexp(4.0, -23) + std::ldexp(std::sqrt(2.0), -18)).epsilon(1e-6));
  const prt::scene::Scene empty;
  const prt::scene::RayCaster none(empty);
  CHECK_FALSE(none.occluded({0, 0, 0}, {0, 0, 1}, 0.f, 1e30f));
}
