// Scenes for radiosity: subdivision to a target edge length, emission from OBJ Ke and the
// command line's MATERIAL=r,g,b, the material checks, and patch → vertex interpolation.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "fixtures/radiosity/mesh_quality.h"
#include "fixtures/radiosity/radiosity_fixtures.h"
#include "radiosity/materials.h"
#include "radiosity/patches.h"
#include "scene/material_assignment.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "support/test_data.h"

using namespace prt::radiosity;
using prt::test::octahedron;
using prt::test::smallest_angle_degrees;
using prt::test::triangle_area;

namespace {

double total_area(const prt::scene::Scene& s) {
  double a = 0.0;
  for (const Patch& p : make_patches(s)) a += p.area;
  return a;
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = std::string(PRT_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("subdivision keeps area, orientation and the original vertices, edges ≤ L",
          "[radiosity][scene]") {
  const prt::scene::Scene box =
      prt::scene::make_box({0, 0, 0}, {1, 2, 3}, 1, false, glm::vec3(0.5f));
  const prt::scene::Scene fine = prt::scene::subdivide_to_edge_length(box, 0.4);
  CHECK(fine.triangles.size() > 10 * box.triangles.size());
  CHECK(total_area(fine) == Approx(total_area(box)).epsilon(1e-6));
  for (std::size_t v = 0; v < box.positions.size(); ++v)
    CHECK(fine.positions[v] == box.positions[v]);
  double longest = 0.0;
  for (const glm::uvec3& t : fine.triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(
          longest, double(glm::length(fine.positions[t[k]] - fine.positions[t[(k + 1) % 3]])));
  CHECK(longest <= 0.4 * (1 + 1e-6));
  // Every sub-triangle faces the way its vertex normals (the original face's) point.
  const std::vector<Patch> patches = make_patches(fine);
  for (std::size_t t = 0; t < patches.size(); ++t)
    CHECK(glm::dot(patches[t].normal, glm::dvec3(fine.normals[fine.triangles[t].x])) > 0.99);
  // Shared edges share their new vertices: in a 1×1 face at L = √2/4 the sides (length 1)
  // have 3 segments, the diagonal 4 (shared: 3 points once); each triangle adds the lattice
  // points of level n = 4 inside it, (n − 1)(n − 2)/2 = 3: 4 + 4·2 + 3 + 2·3 = 21 vertices, and
  // per triangle Σk + (n − 1)(n − 2) − 2 = 10 + 6 − 2 = 14 triangles.
  const prt::scene::Scene quad =
      prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1, glm::vec3(0.5f));
  const prt::scene::Scene quad4 = prt::scene::subdivide_to_edge_length(quad, 0.25 * std::sqrt(2.0));
  CHECK(quad4.triangles.size() == 2 * 14);
  CHECK(quad4.positions.size() == 21);
  // L = 1/4: sides 4 segments, the diagonal 6 (n = 6): 4 + 12 + 5 + 2·10 = 41 vertices.
  const prt::scene::Scene quad6 = prt::scene::subdivide_to_edge_length(quad, 0.25);
  CHECK(quad6.positions.size() >= 41);  // more only where an edge > L had to be split
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, 1e-6), std::invalid_argument);
}

TEST_CASE("subdivision is conforming: no T-junctions, a closed mesh stays closed",
          "[radiosity][scene]") {
  // Edges are split into ⌈length / L⌉ equal segments whatever triangle they belong to, the
  // points computed from the endpoints in a canonical order: neighbours of different sizes
  // share every new point of their common edge, bit for bit, also across primitives (which
  // share no vertex ids). Splitting per triangle (n² congruent pieces, n from the longest
  // edge) failed every check below but the area and the edge length.
  // Equal counts on an acute triangle give its lattice: an equilateral triangle of side 1 at
  // L = 0.25 becomes 16 equilateral triangles of side 1/4.
  prt::scene::Scene one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, float(std::sqrt(0.75)), 0}};
  one.normals.assign(3, glm::vec3(0, 0, 1));
  one.albedo.assign(3, glm::vec3(0.5f));
  one.triangles = {{0, 1, 2}};
  one.primitives.resize(1);
  one.primitives[0].vertex_count = 3;
  one.primitives[0].triangle_count = 1;
  const prt::scene::Scene tri = prt::scene::subdivide_to_edge_length(one, 0.25);
  REQUIRE(tri.triangles.size() == 16);
  for (const glm::uvec3& t : tri.triangles)
    for (int k = 0; k < 3; ++k)
      CHECK(glm::length(tri.positions[t[k]] - tri.positions[t[(k + 1) % 3]]) ==
            Approx(0.25).epsilon(1e-5));
  // Also a UV sphere stretched to 3 × 1 × 0.5 (slivers at the poles, every size between).
  prt::scene::Scene ellipsoid =
      prt::scene::make_uv_sphere({0, 0, 0}, 1.f, 7, 9, false, glm::vec3(0.5f));
  for (glm::vec3& p : ellipsoid.positions) p *= glm::vec3(3.f, 1.f, 0.5f);
  for (int mesh = 0; mesh < 3; ++mesh) {
    const bool two = mesh == 1;
    const prt::scene::Scene in = mesh == 2 ? ellipsoid : octahedron(two);
    for (const double max_edge : {0.9, 0.37, 0.2}) {
      const prt::scene::Scene out = prt::scene::subdivide_to_edge_length(in, max_edge);
      INFO((two ? "two primitives" : "one primitive")
           << ", L = " << max_edge << ": " << out.triangles.size() << " triangles");
      // Closed: every edge, as a pair of positions, is on exactly two triangles, once in each
      // direction (so also: no position lies inside another triangle's edge and nothing
      // overlaps along an edge).
      using Key = std::array<float, 6>;
      const auto key = [&](uint32_t u, uint32_t v) {
        const glm::vec3 a = out.positions[u], b = out.positions[v];
        return Key{a.x, a.y, a.z, b.x, b.y, b.z};
      };
      std::map<Key, int> directed;
      for (const glm::uvec3& t : out.triangles)
        for (int k = 0; k < 3; ++k) ++directed[key(t[k], t[(k + 1) % 3])];
      std::size_t unmatched = 0;
      for (const auto& [edge, count] : directed) {
        const Key reverse{edge[3], edge[4], edge[5], edge[0], edge[1], edge[2]};
        const auto found = directed.find(reverse);
        if (count != 1 || found == directed.end() || found->second != 1) ++unmatched;
      }
      CHECK(unmatched == 0);
      // One primitive: the same by vertex ids (vertices of a shared edge are shared).
      if (!two) {
        std::map<std::pair<uint32_t, uint32_t>, int> by_id;
        for (const glm::uvec3& t : out.triangles)
          for (int k = 0; k < 3; ++k) ++by_id[{t[k], t[(k + 1) % 3]}];
        std::size_t open = 0;
        for (const auto& [edge, count] : by_id)
          if (count != 1 || by_id.count({edge.second, edge.first}) != 1) ++open;
        CHECK(open == 0);
      }
      // The T-junction check itself, geometrically: no vertex strictly inside any edge.
      std::size_t t_junctions = 0;
      for (const glm::uvec3& t : out.triangles) {
        for (int k = 0; k < 3; ++k) {
          const glm::dvec3 a(out.positions[t[k]]), b(out.positions[t[(k + 1) % 3]]);
          const double length2 = glm::dot(b - a, b - a);
          for (const glm::vec3& p : out.positions) {
            const double s = glm::dot(glm::dvec3(p) - a, b - a) / length2;
            if (s <= 1e-6 || s >= 1.0 - 1e-6) continue;
            const glm::dvec3 off = glm::dvec3(p) - (a + s * (b - a));
            if (glm::dot(off, off) < 1e-12 * length2) ++t_junctions;
          }
        }
      }
      CHECK(t_junctions == 0);
      double area_in = 0.0, area_out = 0.0, longest = 0.0;
      for (const glm::uvec3& t : in.triangles) area_in += triangle_area(in, t);
      for (const glm::uvec3& t : out.triangles) {
        area_out += triangle_area(out, t);
        for (int k = 0; k < 3; ++k)
          longest = std::max(
              longest, double(glm::length(out.positions[t[k]] - out.positions[t[(k + 1) % 3]])));
      }
      CHECK(area_out == Approx(area_in).epsilon(1e-6));  // float positions
      CHECK(longest <= max_edge * (1 + 1e-6));
      // Well shaped: the Delaunay triangulation of the points keeps the smallest angle near
      // the input's (32.4° here; the n² lattice of the input's faces would keep it exactly).
      const double angle = smallest_angle_degrees(out);
      INFO("smallest angle " << angle << "°, input " << smallest_angle_degrees(in) << "°");
      CHECK(angle > 0.6 * smallest_angle_degrees(in));
    }
  }
}

TEST_CASE("OBJ Ke is read as emission, MATERIAL=r,g,b overrides it", "[radiosity][scene]") {
  write_text("lamp.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 3 2 1\nnewmtl wall\nKd 0.2 0.3 0.4\n");
  const std::string obj = write_text(
      "lamp.obj",
      "mtllib lamp.mtl\no lamp\nusemtl lamp\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no wall\n"
      "usemtl wall\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n");
  prt::scene::Scene scene = prt::scene::load_scene(obj);
  REQUIRE(scene.primitives.size() == 2);
  CHECK(scene.primitives[0].material == "lamp");
  CHECK(scene.primitives[0].emission == glm::vec3(3, 2, 1));
  CHECK(scene.primitives[1].emission == glm::vec3(0.f));
  using prt::scene::parse_material_colour;
  prt::scene::apply_emission(scene, {parse_material_colour("--emission", "wall=0.5,0,2")});
  CHECK(scene.primitives[1].emission == glm::vec3(0.5f, 0.f, 2.f));
  prt::scene::apply_albedo(scene, {parse_material_colour("--albedo", "wall=0.1")});
  CHECK(scene.albedo[scene.primitives[1].first_vertex] == glm::vec3(0.1f));
  check_materials(scene);
  const std::vector<Patch> patches = make_patches(scene);
  CHECK(patches[0].emission == glm::dvec3(3, 2, 1));
  CHECK_THROWS_WITH(
      prt::scene::apply_emission(scene, {parse_material_colour("--emission", "glass=1")}),
      Catch::Contains("--emission glass=1: no material or primitive named 'glass'") &&
          Catch::Contains("'lamp', 'wall'"));
}

TEST_CASE("glTF emission is emissiveFactor times KHR_materials_emissive_strength",
          "[radiosity][scene]") {
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  {
    std::ofstream bin(std::string(PRT_TEST_OUTPUT_DIR) + "/emissive.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  const std::string gltf =
      write_text("emissive.gltf",
                 R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
 "nodes":[{"mesh":0},{"mesh":1}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]},
           {"primitives":[{"attributes":{"POSITION":0},"material":1}]}],
 "materials":[{"name":"lamp","emissiveFactor":[1,0.5,0.25],
               "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":8}}},
              {"name":"plain","emissiveFactor":[0.5,0.5,0.5]}],
 "extensionsUsed":["KHR_materials_emissive_strength"],
 "buffers":[{"uri":"emissive.bin","byteLength":36}],
 "bufferViews":[{"buffer":0,"byteLength":36}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
               "min":[0,0,0],"max":[1,1,0]}]})");
  const prt::scene::Scene scene = prt::scene::load_scene(gltf);
  REQUIRE(scene.primitives.size() == 2);
  CHECK(scene.primitives[0].material == "lamp");
  CHECK(scene.primitives[0].emission == glm::vec3(8.f, 4.f, 2.f));
  CHECK(scene.primitives[1].emission == glm::vec3(0.5f));
}

TEST_CASE("bad emission and albedo values are refused with one line", "[radiosity][scene]") {
  prt::scene::Scene scene =
      prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1, glm::vec3(0.5f));
  scene.source_path = "quad.obj";
  scene.primitives[0].emission = glm::vec3(1.f, -0.5f, 0.f);
  CHECK_THROWS_WITH(check_materials(scene),
                    Catch::Contains("quad.obj") && Catch::Contains("emission"));
  scene.primitives[0].emission = glm::vec3(1.f, std::nanf(""), 0.f);
  CHECK_THROWS_AS(check_materials(scene), std::invalid_argument);
  scene.primitives[0].emission = glm::vec3(1.f);
  scene.albedo[0] = glm::vec3(1.5f);
  CHECK_THROWS_WITH(check_materials(scene), Catch::Contains("albedo"));
  scene.albedo[0] = glm::vec3(1.f);
  check_materials(scene);  // albedo 1 is allowed where light can escape (checked by the solver)
  CHECK(has_unit_albedo(scene));
}

TEST_CASE("vertex radiance is the area-weighted mean of the patches around a vertex",
          "[radiosity][scene]") {
  // Two triangles of areas 0.5 and 1.5 sharing vertices 1 and 2.
  prt::scene::Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 0}};
  s.normals.assign(4, {0, 0, 1});
  s.albedo.assign(4, glm::vec3(0.5f));
  s.triangles = {{0, 1, 2}, {1, 3, 2}};
  const std::vector<Patch> patches = make_patches(s);
  REQUIRE(patches[1].area == Approx(1.5));
  const std::vector<float> v = vertex_radiance(s, patches, {glm::dvec3(1.0), glm::dvec3(4.0)});
  CHECK(v[0] == Approx(1.0));
  CHECK(v[3 * 3] == Approx(4.0));
  CHECK(v[3 * 1] == Approx((0.5 * 1 + 1.5 * 4) / 2.0));
}
