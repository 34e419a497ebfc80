// Wavefront OBJ loading (scene/scene_loader.h) on small files written here and on real meshes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "scene/scene_loader.h"
#include "support/png_writer.h"
#include "support/test_data.h"

using prt::scene::Scene;
using prt::scene::SceneError;

namespace {

std::string write_text(const std::string& name, const std::string& text) {
  const auto path = prt::test::output_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

std::string error_of(const std::string& path) {
  try {
    prt::scene::load_scene(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// The albedo at texture coordinate `uv` (glTF convention) of a textured scene, found by solving
// for the triangle holding it.
glm::vec3 albedo_at_texcoord(const Scene& s, glm::vec2 uv) {
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const glm::uvec3 tri = s.triangles[t];
    const glm::vec2 a = s.texcoords[tri.x], e1 = s.texcoords[tri.y] - a,
                    e2 = s.texcoords[tri.z] - a;
    const glm::vec2 r = uv - a;
    const float det = e1.x * e2.y - e1.y * e2.x;
    if (det == 0.f) continue;
    const float u = (r.x * e2.y - r.y * e2.x) / det, v = (e1.x * r.y - e1.y * r.x) / det;
    if (u >= -1e-6f && v >= -1e-6f && u + v <= 1.f + 1e-6f) return s.albedo_at(t, u, v);
  }
  FAIL("texture coordinate outside the mesh");
  return {};
}

double linear_of_byte(int byte) {  // IEC 61966-2-1, written out here
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

void check_unit_normals(const Scene& s) {
  REQUIRE(s.normals.size() == s.positions.size());
  for (const glm::vec3& n : s.normals) REQUIRE(glm::length(n) == Approx(1.0).margin(1e-5));
}

}  // namespace

TEST_CASE("OBJ without normals: file vertex order, polygons triangulated, negative indices, CRLF") {
  // A unit square (quad) in z = 0 and a pentagon in z = 1 given with negative indices.
  const std::string text =
      "# test\r\n"
      "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\n"
      "f 1 2 3 4\r\n"
      "v 0 0 1\r\nv 2 0 1\r\nv 3 1 1\r\nv 1 2 1\r\nv -1 1 1\r\n"
      "f -5 -4 -3 -2 -1\r\n";
  const Scene s = prt::scene::load_scene(write_text("polygons_crlf.obj", text));
  REQUIRE(s.positions.size() == 9);
  CHECK(s.positions[0] == glm::vec3(0, 0, 0));
  CHECK(s.positions[4] == glm::vec3(0, 0, 1));
  CHECK(s.positions[8] == glm::vec3(-1, 1, 1));
  // A quad gives 2 triangles, a pentagon 3.
  REQUIRE(s.triangles.size() == 5);
  std::set<uint32_t> used;
  double area = 0.0;
  for (const auto& t : s.triangles) {
    used.insert({t.x, t.y, t.z});
    const glm::dvec3 a(s.positions[t.x]), b(s.positions[t.y]), c(s.positions[t.z]);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  CHECK(used.size() == 9);
  // Square 1 + pentagon (shoelace: 10/2 = 5) = 6; small integers, exact in float and double.
  CHECK(area == Approx(6.0).epsilon(1e-12));
  CHECK(s.computed_normal_vertices == 9);
  check_unit_normals(s);
  for (const glm::vec3& n : s.normals) CHECK(glm::distance(n, glm::vec3(0, 0, 1)) < 1e-6f);
  CHECK(s.primitives.size() == 1);
  CHECK(s.albedo[0] == glm::vec3(0.8f));  // no material: 0.8 grey
}

TEST_CASE("OBJ with vn: one vertex per unique (position, normal) pair, first-seen order") {
  // A cube corner's two faces sharing an edge but with different normals on it.
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 -1\nv 0 1 -1\n"
      "vn 0 0 1\nvn -1 0 0\n"
      "o front\nf 1//1 2//1 3//1 4//1\n"
      "o side\nf 5//2 1//2 4//2 6//2\n";
  const Scene s = prt::scene::load_scene(write_text("with_normals.obj", text));
  REQUIRE(s.primitives.size() == 2);
  CHECK(s.primitives[0].name == "front");
  CHECK(s.primitives[1].name == "side");
  REQUIRE(s.positions.size() == 8);  // positions 1 and 4 appear with two normals each
  CHECK(s.computed_normal_vertices == 0);
  CHECK(s.positions[4] == glm::vec3(0, 0, -1));
  CHECK(s.positions[5] == glm::vec3(0, 0, 0));
  CHECK(s.normals[0] == glm::vec3(0, 0, 1));
  CHECK(s.normals[5] == glm::vec3(-1, 0, 0));
  CHECK(s.triangles[2] == glm::uvec3(4, 5, 6));
}

TEST_CASE("OBJ albedo from the MTL's Kd, and one-line errors naming the file") {
  write_text("coloured.mtl", "newmtl red\nKd 0.7 0.1 0.05\nnewmtl blue\nKd 0.1 0.2 0.6\n");
  const std::string text =
      "mtllib coloured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
      "o a\nusemtl red\nf 1 2 3\no b\nusemtl blue\nf 1 3 4\n";
  const Scene s = prt::scene::load_scene(write_text("coloured.obj", text));
  REQUIRE(s.primitives.size() == 2);
  CHECK(s.primitives[0].albedo == glm::vec3(0.7f, 0.1f, 0.05f));
  CHECK(s.primitives[1].albedo == glm::vec3(0.1f, 0.2f, 0.6f));
  // Shape b uses positions 1, 3, 4 only: 3 vertices in file order.
  CHECK(s.primitives[1].vertex_count == 3);
  CHECK(s.positions[s.primitives[1].first_vertex + 2] == glm::vec3(0, 0, 1));

  const std::string bad_index = write_text("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  const std::string message = error_of(bad_index);
  INFO(message);
  CHECK(message.rfind(bad_index + ": ", 0) == 0);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find("out of range") != std::string::npos);

  const std::string empty = write_text("no_faces.obj", "v 0 0 0\nv 1 0 0\n");
  CHECK(error_of(empty).find("no (non-degenerate) triangles") != std::string::npos);
}

TEST_CASE("Real OBJ: stanford-bunny.obj keeps all 35,947 vertices in file order") {
  const auto path = prt::test::shared_data("meshes/stanford-bunny.obj");
  PRT_REQUIRE_SHARED_DATA(path);
  const Scene s = prt::scene::load_scene(path.string());
  CHECK(s.positions.size() == 35947);
  CHECK(s.triangles.size() + s.skipped_degenerate_triangles == 69451);
  CHECK(s.computed_normal_vertices == 35947);
  // 1,113 `v` lines are used by no face (checked independently below): they are kept, so
  // vertex i is the file's i-th `v`, with the +Y fallback normal.
  check_unit_normals(s);
  // The file read independently: `v` lines in order and the set of indices faces use.
  std::ifstream in(path);
  std::string line;
  std::vector<glm::vec3> file_positions;
  std::set<long> used;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) {
      glm::vec3 p;
      REQUIRE(std::sscanf(line.c_str(), "v %f %f %f", &p.x, &p.y, &p.z) == 3);
      file_positions.push_back(p);
    } else if (line.rfind("f ", 0) == 0) {
      long a, b, c;
      REQUIRE(std::sscanf(line.c_str(), "f %ld %ld %ld", &a, &b, &c) == 3);
      used.insert({a - 1, b - 1, c - 1});
    }
  }
  REQUIRE(file_positions.size() == s.positions.size());
  CHECK(file_positions == s.positions);
  CHECK(used.size() == 34834);
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    if (used.count(static_cast<long>(v)) == 0) REQUIRE(s.normals[v] == glm::vec3(0, 1, 0));
  }
}

TEST_CASE("Real OBJ: cornell_box albedo from MTL, dragon (CRLF), suzanne (vn)") {
  const auto cornell = prt::test::shared_data("meshes/cornell_box.obj");
  PRT_REQUIRE_SHARED_DATA(cornell);
  const Scene box = prt::scene::load_scene(cornell.string());
  bool red = false, green = false;
  for (const auto& p : box.primitives) {
    red = red || (p.albedo.r > 0.5f && p.albedo.g < 0.2f);
    green = green || (p.albedo.g > 0.3f && p.albedo.r < 0.2f);
  }
  CHECK(red);
  CHECK(green);
  CHECK(box.primitives.size() == 8);
  CHECK(box.triangles.size() == 36);

  const auto dragon_path = prt::test::shared_data("meshes/dragon.obj");
  PRT_REQUIRE_SHARED_DATA(dragon_path);
  const Scene dragon = prt::scene::load_scene(dragon_path.string());
  CHECK(dragon.positions.size() == 50000);
  CHECK(dragon.triangles.size() + dragon.skipped_degenerate_triangles == 100000);
  check_unit_normals(dragon);

  const auto suzanne_path = prt::test::shared_data("meshes/suzanne.obj");
  PRT_REQUIRE_SHARED_DATA(suzanne_path);
  const Scene suzanne = prt::scene::load_scene(suzanne_path.string());
  CHECK(suzanne.computed_normal_vertices == 0);
  CHECK(suzanne.positions.size() >= 507);
  check_unit_normals(suzanne);
}

TEST_CASE("OBJ map_Kd: sRGB PNG, vt with v up, Kd replaced, -clamp, -s and -o honoured") {
  // 1×2 texture: top row (200, 40, 20), bottom row (30, 180, 60).
  prt::test::write_png(prt::test::output_path("obj_tex.png").string(), 1, 2, 3,
                       {200, 40, 20, 30, 180, 60});
  write_text("obj_tex.mtl",
             "newmtl plain\nKd 0.5 0.5 0.5\nmap_Kd obj_tex.png\n"
             "newmtl clamped\nKd 0.5 0.5 0.5\nmap_Kd -clamp on -s 2 2 1 -o 0.5 0 0 obj_tex.png\n");
  const std::string quad =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "f 1/1 2/2 3/3 4/4\n";
  const Scene s = prt::scene::load_scene(
      write_text("obj_tex.obj", "mtllib obj_tex.mtl\nusemtl plain\n" + quad));
  REQUIRE(s.primitives.size() == 1);
  REQUIRE(s.primitives[0].base_color_texture.has_value());
  // OBJ's vt (0, 0) is the image's bottom-left: glTF (0, 1).
  const auto vertex_at = [](const Scene& scene, glm::vec3 p) {
    for (std::size_t i = 0; i < scene.positions.size(); ++i)
      if (scene.positions[i] == p) return i;
    FAIL("no vertex at that position");
    return std::size_t{0};
  };
  CHECK(s.texcoords[vertex_at(s, {0, 0, 0})] == glm::vec2(0, 1));
  CHECK(s.texcoords[vertex_at(s, {1, 1, 0})] == glm::vec2(1, 0));
  // OBJ v = 0.25 lies in the bottom row, v = 0.75 in the top row; the texture replaces Kd.
  const glm::vec3 bottom = albedo_at_texcoord(s, {0.5f, 0.75f});
  const glm::vec3 top = albedo_at_texcoord(s, {0.5f, 0.25f});
  CHECK(bottom.x == Approx(linear_of_byte(30)).margin(1e-6));
  CHECK(bottom.y == Approx(linear_of_byte(180)).margin(1e-6));
  CHECK(top.x == Approx(linear_of_byte(200)).margin(1e-6));
  CHECK(top.z == Approx(linear_of_byte(20)).margin(1e-6));

  const Scene c = prt::scene::load_scene(
      write_text("obj_tex_clamp.obj", "mtllib obj_tex.mtl\nusemtl clamped\n" + quad));
  REQUIRE(c.primitives[0].base_color_texture.has_value());
  CHECK(c.primitives[0].base_color_texture->sampler.wrap_s == prt::scene::TextureWrap::ClampToEdge);
  CHECK(c.primitives[0].base_color_texture->sampler.wrap_t == prt::scene::TextureWrap::ClampToEdge);
  // vt (1, 1) → (1·2 + 0.5, 1·2 + 0) = (2.5, 2) → glTF (2.5, 1 − 2).
  const std::size_t corner = vertex_at(c, {1, 1, 0});
  CHECK(c.texcoords[corner] == glm::vec2(2.5f, -1.f));
  // Clamped far outside in v = −1 (above the image): the top row.
  CHECK(c.albedo[corner].x == Approx(linear_of_byte(200)).margin(1e-6));
}

TEST_CASE("OBJ map_Kd without vn: texture seams split vertices but not the shading") {
  prt::test::write_png(prt::test::output_path("seam.png").string(), 1, 1, 1, {128});
  write_text("seam.mtl", "newmtl m\nmap_Kd seam.png\n");
  // Two quads folded along the edge x = 1 (positions 2 and 5), the second rising at 45°; the
  // edge has texture coordinate u = 1 on the first quad and u = 0 on the second.
  const std::string text =
      "mtllib seam.mtl\nusemtl m\n"
      "v 0 0 0\nv 1 0 0\nv 2 0 1\nv 0 1 0\nv 1 1 0\nv 2 1 1\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
      "f 1/1 2/2 5/4 4/3\nf 2/1 3/2 6/4 5/3\n";
  const Scene s = prt::scene::load_scene(write_text("seam.obj", text));
  REQUIRE(s.primitives[0].base_color_texture.has_value());
  // 6 positions, the two on the fold used with two coordinates each: 8 vertices.
  REQUIRE(s.positions.size() == 8);
  check_unit_normals(s);
  // Vertices at the same position share one normal: the fold's normal is the mean of the two
  // faces' (area- and angle-weighted equally here), not either face's.
  for (std::size_t a = 0; a < s.positions.size(); ++a)
    for (std::size_t b = a + 1; b < s.positions.size(); ++b)
      if (s.positions[a] == s.positions[b]) {
        CHECK(glm::distance(s.normals[a], s.normals[b]) < 1e-6f);
        CHECK(s.texcoords[a] != s.texcoords[b]);
        CHECK(std::fabs(s.normals[a].z) > 0.1f);  // neither face's own normal
        CHECK(std::fabs(s.normals[a].x) > 0.1f);
      }
  // Grey 128 everywhere: the linearised value at every vertex.
  for (const glm::vec3& a : s.albedo) {
    CHECK(a.x == Approx(linear_of_byte(128)).margin(1e-6));
    CHECK(a.z == a.x);
  }
}

TEST_CASE("OBJ map_Kd that cannot be read, or faces without vt: a warning, and Kd instead") {
  write_text("missing_tex.mtl", "newmtl m\nKd 0.2 0.3 0.4\nmap_Kd not_there.png\n");
  const Scene s = prt::scene::load_scene(write_text(
      "missing_tex.obj", "mtllib missing_tex.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
  CHECK(s.albedo[0] == glm::vec3(0.2f, 0.3f, 0.4f));
  prt::test::write_png(prt::test::output_path("novt.png").string(), 1, 1, 1, {255});
  write_text("novt.mtl", "newmtl m\nKd 0.2 0.3 0.4\nmap_Kd novt.png\n");
  const Scene n = prt::scene::load_scene(
      write_text("novt.obj", "mtllib novt.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  CHECK_FALSE(n.primitives[0].base_color_texture.has_value());
  CHECK(n.albedo[0] == glm::vec3(0.2f, 0.3f, 0.4f));
}
