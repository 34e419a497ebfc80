// Scenes for radiosity: subdivision to a target edge length, emission from OBJ Ke and the
// command line's MATERIAL=r,g,b, the material checks, and patch → vertex interpolation.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "radiosity/materials.h"
#include "radiosity/patches.h"
#include "relight/radiosity_pipeline.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

using namespace prt::radiosity;

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
  // Shared edges share their new vertices: a 1×1 face split in n² has (n+1)(n+2)/2… per
  // triangle, and the two triangles of a face share the diagonal's points.
  const prt::scene::Scene quad =
      prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1, glm::vec3(0.5f));
  const prt::scene::Scene quad4 = prt::scene::subdivide_to_edge_length(quad, 0.25 * std::sqrt(2.0));
  CHECK(quad4.triangles.size() == 2 * 16);
  CHECK(quad4.positions.size() == 25);  // the 5 × 5 grid
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(prt::scene::subdivide_to_edge_length(box, 1e-6), std::invalid_argument);
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
  apply_emission(scene, {parse_material_value("--emission", "wall=0.5,0,2")});
  CHECK(scene.primitives[1].emission == glm::vec3(0.5f, 0.f, 2.f));
  apply_albedo(scene, {parse_material_value("--albedo", "wall=0.1")});
  CHECK(scene.albedo[scene.primitives[1].first_vertex] == glm::vec3(0.1f));
  check_materials(scene);
  const std::vector<Patch> patches = make_patches(scene);
  CHECK(patches[0].emission == glm::dvec3(3, 2, 1));
  CHECK_THROWS_WITH(apply_emission(scene, {parse_material_value("--emission", "glass=1")}),
                    Catch::Contains("no primitive") && Catch::Contains("lamp, wall"));
}

TEST_CASE("glTF emission is emissiveFactor times KHR_materials_emissive_strength",
          "[radiosity][scene]") {
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  {
    std::ofstream bin(std::string(PRT_TEST_OUTPUT_DIR) + "/emissive.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  const std::string gltf = write_text(
      "emissive.gltf",
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
  for (const char* text : {"light=-1,0,0", "light=nan", "light=inf,1,1", "light=1,2", "=1",
                           "light=", "light", "light=1,x,2"})
    CHECK_THROWS_AS(parse_material_value("--emission", text), std::invalid_argument);
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

TEST_CASE("automatic exposure maps the log-average luminance of lit pixels to 0.18",
          "[radiosity][scene]") {
  prt::relight::Image image;
  image.width = 4;
  image.height = 1;
  // Two grey pixels of luminance 0.09 and 1.44 (log-average 0.36), two black ones (ignored).
  image.rgb = {0.09f, 0.09f, 0.09f, 1.44f, 1.44f, 1.44f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
  CHECK(prt::relight::automatic_exposure_ev(image) == Approx(-1.0).margin(1e-5));
  image.rgb.assign(12, 0.f);
  CHECK(prt::relight::automatic_exposure_ev(image) == 0.f);
}
