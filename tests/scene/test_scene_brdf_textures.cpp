// Textured material parameters: glTF metallicRoughnessTexture sampled at each vertex
// (scene/src/gltf_loader.cpp) and quantised to at most 64 variants per material
// (scene/brdf_variants.h); the per-vertex materials a glossy bake stores
// (scene/vertex_materials.h); overrides drop the variants; unusable textures are recorded.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "scene/brdf_variants.h"
#include "scene/material_override.h"
#include "scene/scene_loader.h"
#include "scene/vertex_materials.h"
#include "support/metal_rough_glb.h"
#include "support/test_data.h"

using prt::brdf::Material;
using prt::brdf::MaterialModel;

namespace {

// The glTF mapping (scene/src/gltf_materials.h) for base colour 0.5 grey, ior 1.5.
void check_gltf_material(const Material& m, double roughness, double metalness) {
  INFO("roughness " << roughness << ", metalness " << metalness << ": " << prt::brdf::describe(m));
  REQUIRE(m.model == MaterialModel::kGltf);
  const double alpha = std::max(roughness * roughness, 1e-3);
  // The texels are stored as float (relative rounding 6e-8, squared in α): 1e-6 relative.
  CHECK(m.alpha_x == Approx(alpha).epsilon(1e-6));
  CHECK(m.alpha_y == Approx(alpha).epsilon(1e-6));
  // The spec's BRDF takes base colour, metallic and the dielectric F0 as they are.
  CHECK(m.metallic == Approx(metalness).epsilon(1e-6).margin(1e-12));
  CHECK(m.specular.r == Approx(0.04).epsilon(1e-6));
  CHECK(m.diffuse.r == Approx(0.5).epsilon(1e-6));
}

}  // namespace

TEST_CASE(
    "glTF metallicRoughnessTexture: each half of the strip gets its texels' roughness and "
    "metalness") {
  // Left texels G 64, B 0 (roughness 64/255, dielectric); right G 200, B 255 (roughness
  // 200/255, metal). The texture is linear data: an sRGB decode would turn 64 into 0.05 and
  // fail the α check by a factor of ~25.
  const std::string path = prt::test::output_path("metal_rough_halves.glb").string();
  prt::test::write_metal_rough_glb(path, 64, 0, 200, 255);
  const prt::scene::Scene scene = prt::scene::load_scene(path);
  REQUIRE(scene.primitives.size() == 1);
  const prt::scene::ScenePrimitive& p = scene.primitives[0];
  CHECK(p.brdf_texture_problem.empty());
  REQUIRE(p.brdf_variants.size() == 2);
  REQUIRE(p.brdf_variant_of_vertex.size() == 16);
  std::vector<Material> materials;
  std::vector<uint32_t> material_of_vertex;
  prt::scene::vertex_materials(scene, materials, material_of_vertex);
  REQUIRE(materials.size() == 2);
  for (std::size_t v = 0; v < 16; ++v) {
    const bool right = v % 8 >= 4;
    INFO("vertex " << v);
    check_gltf_material(materials[material_of_vertex[v]], right ? 200 / 255.0 : 64 / 255.0,
                        right ? 1.0 : 0.0);
  }
  // The primitive's own BRDF is the texture's mean: roughness (64 + 200)/2/255, metalness ½.
  REQUIRE(p.brdf.has_value());
  check_gltf_material(*p.brdf, 132 / 255.0, 0.5);
  // An override replaces the textured parameters too: one material for every vertex.
  prt::scene::Scene overridden = scene;
  prt::scene::apply_material_overrides(
      overridden, {prt::scene::parse_material_override("patchy=ggx:roughness=0.5")});
  CHECK(overridden.primitives[0].brdf_variants.empty());
  prt::scene::vertex_materials(overridden, materials, material_of_vertex);
  CHECK(materials.size() == 1);
  const std::vector<std::string> lines = prt::scene::describe_materials(scene);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].find("roughness/metalness textured: 2 variants") != std::string::npos);
}

TEST_CASE(
    "glTF metallicRoughnessTexture that cannot be used: recorded with the file's name, "
    "factors used") {
  SECTION("missing file") {
    const std::string path = prt::test::output_path("metal_rough_missing.glb").string();
    std::filesystem::remove(prt::test::output_path("no_such_mr.png"));
    prt::test::write_metal_rough_glb(path, 64, 0, 200, 255, prt::test::MetalRoughImage::kUri,
                                     "no_such_mr.png");
    const prt::scene::Scene scene = prt::scene::load_scene(path);
    const prt::scene::ScenePrimitive& p = scene.primitives[0];
    INFO(p.brdf_texture_problem);
    CHECK(p.brdf_texture_problem.find("material 'patchy': metallicRoughnessTexture") == 0);
    CHECK(p.brdf_texture_problem.find("no_such_mr.png: no such file") != std::string::npos);
    CHECK(p.brdf_variants.empty());
    REQUIRE(p.brdf.has_value());
    check_gltf_material(*p.brdf, 1.0, 1.0);  // the factors
  }
  SECTION("not an image") {
    const std::string path = prt::test::output_path("metal_rough_garbage.glb").string();
    const std::string file = prt::test::output_path("garbage_mr.png").string();
    std::ofstream(file, std::ios::binary) << "not an image at all";
    prt::test::write_metal_rough_glb(path, 64, 0, 200, 255, prt::test::MetalRoughImage::kUri,
                                     "garbage_mr.png");
    const prt::scene::Scene scene = prt::scene::load_scene(path);
    INFO(scene.primitives[0].brdf_texture_problem);
    CHECK(scene.primitives[0].brdf_texture_problem.find("garbage_mr.png") != std::string::npos);
    CHECK(scene.primitives[0].brdf_variants.empty());
  }
}

TEST_CASE("quantise_metal_roughness: exact up to 64 pairs, else bounded error and <= 64 levels") {
  SECTION("few pairs are kept exactly") {
    std::vector<glm::dvec2> samples;
    for (int i = 0; i < 200; ++i) samples.emplace_back((i % 8) / 7.0, (i % 3) / 2.0);
    const prt::scene::QuantisedParameters q = prt::scene::quantise_metal_roughness(samples);
    CHECK(q.levels.size() == 24);
    CHECK(q.max_roughness_error == 0.0);
    CHECK(q.max_metalness_error == 0.0);
    for (std::size_t i = 0; i < samples.size(); ++i) CHECK(q.levels[q.level_of[i]] == samples[i]);
  }
  SECTION("continuous roughness, binary metalness: metalness exact, 32 roughness bins") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.2, 0.9);
    std::vector<glm::dvec2> samples;
    for (int i = 0; i < 5000; ++i) samples.emplace_back(u(rng), i % 2);
    const prt::scene::QuantisedParameters q = prt::scene::quantise_metal_roughness(samples);
    CHECK(q.levels.size() <= 64);
    CHECK(q.levels.size() > 32);  // both metalness values × most of the 32 bins are used
    CHECK(q.max_metalness_error == 0.0);
    double worst = 0;
    for (std::size_t i = 0; i < samples.size(); ++i)
      worst = std::max(worst, std::fabs(q.levels[q.level_of[i]].x - samples[i].x));
    CHECK(worst == q.max_roughness_error);
    CHECK(worst <= 0.7 / 64 + 1e-12);  // half of a bin of (0.9 − 0.2)/32
  }
  SECTION("both continuous: 16 × 4 bins") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<glm::dvec2> samples;
    for (int i = 0; i < 5000; ++i) samples.emplace_back(u(rng), u(rng));
    const prt::scene::QuantisedParameters q = prt::scene::quantise_metal_roughness(samples);
    CHECK(q.levels.size() == 64);
    CHECK(q.max_roughness_error <= 1.0 / 32 + 1e-12);
    CHECK(q.max_metalness_error <= 1.0 / 8 + 1e-12);
    CHECK(q.max_roughness_error > 0.8 / 32);  // the bound is nearly reached with 5000 samples
  }
  CHECK_THROWS(prt::scene::quantise_metal_roughness({}, 65));
}
