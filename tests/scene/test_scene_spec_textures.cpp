// The textures of KHR_materials_specular (specularTexture A, specularColorTexture sRGB RGB) and
// KHR_materials_anisotropy (anisotropyTexture: RG direction, B strength) read per vertex
// (scene/src/gltf_brdf_textures.h): each vertex's F0, anisotropic α and tangent direction against
// values computed here from the texels and the specs' formulas ([110], [111] of
// docs/REFERENCES.md); constant textures equal their factors; unusable textures and non-finite
// factors are reported in one line; quantise_parameters (scene/brdf_variants.h) on its own.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "scene/brdf_variants.h"
#include "scene/material_override.h"
#include "scene/scene_loader.h"
#include "scene/tangent_frames.h"
#include "scene/vertex_materials.h"
#include "support/test_data.h"
#include "support/texture_strip_glb.h"

using nlohmann::json;
using prt::brdf::Material;
using prt::scene::Scene;

namespace {

// The sRGB EOTF (IEC 61966-2-1), written here from the standard.
double srgb_decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::string glb_path(const std::string& name) {
  return prt::test::output_path(name).string();
}

Scene load_strip(const std::string& name, const json& material,
                 const std::vector<std::vector<unsigned char>>& pngs, bool texcoord1 = false) {
  const std::string path = glb_path(name);
  prt::test::write_glb_text(path, prt::test::texture_strip_gltf(material, pngs, texcoord1).dump());
  return prt::scene::load_scene(path);
}

std::string load_error(const std::string& name, const std::string& text) {
  const std::string path = glb_path(name);
  prt::test::write_glb_text(path, text);
  try {
    prt::scene::load_scene(path);
  } catch (const prt::scene::SceneError& e) {
    return e.what();
  }
  return "";
}

json base_material(double base, double metallic, double roughness) {
  return {{"name", "m"},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {base, base, base, 1.0}},
            {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}}};
}

// The material of every vertex of the strip (scene/vertex_materials.h, what a glossy bake stores).
std::vector<Material> per_vertex(const Scene& scene) {
  std::vector<Material> materials, out;
  std::vector<uint32_t> of_vertex;
  prt::scene::vertex_materials(scene, materials, of_vertex);
  for (uint32_t m : of_vertex) out.push_back(materials.at(m));
  return out;
}

// RGBA texels of columns 0..3: colour (sRGB) and A (linear).
const std::vector<std::vector<unsigned char>> kSpecularTexels = {
    {255, 255, 255, 255}, {128, 64, 0, 255}, {255, 255, 255, 128}, {255, 188, 10, 64}};

}  // namespace

TEST_CASE("the sRGB decoding used here matches the tabulated value", "[scene][materials]") {
  // 128/255 → 0.2158605 (IEC 61966-2-1); 10/255 is on the linear segment.
  CHECK(srgb_decode(128) == Approx(0.2158605).margin(1e-7));
  CHECK(srgb_decode(10) == Approx(10 / 255.0 / 12.92).margin(1e-12));
}

// Tolerance: texels are stored as float (relative rounding 6e-8), the rest is double arithmetic:
// 1e-6 relative.
TEST_CASE(
    "KHR_materials_specular textures: F0 = min(F0_ior × colour factor × sRGB⁻¹(RGB), 1) × "
    "factor × A per vertex",
    "[scene][materials]") {
  json m = base_material(0.5, 0.0, 0.5);
  const double factor = 0.5, colour[3] = {2.0, 1.0, 0.5};
  m["extensions"]["KHR_materials_specular"] = {{"specularFactor", factor},
                                               {"specularColorFactor", {2.0, 1.0, 0.5}},
                                               {"specularTexture", {{"index", 0}}},
                                               {"specularColorTexture", {{"index", 1}}}};
  // One RGBA image behind both textures: its A must be read linearly, its RGB as sRGB (an
  // sRGB-decoded A of 128 would give 0.216 instead of 0.502; a linear R of 128, 0.502 instead
  // of 0.216: both fail the F0 checks by more than a factor 2).
  const std::vector<unsigned char> png = prt::test::column_png(4, kSpecularTexels);
  const Scene scene = load_strip("spec_textures.glb", m, {png, png});
  REQUIRE(scene.primitives.size() == 1);
  const prt::scene::ScenePrimitive& p = scene.primitives[0];
  INFO(p.brdf_texture_problem);
  CHECK(p.brdf_texture_problem.empty());
  CHECK(p.brdf_variants.size() == 4);
  const std::vector<Material> materials = per_vertex(scene);
  REQUIRE(materials.size() == 8);
  glm::dvec3 mean_colour(0.0);
  double mean_a = 0.0;
  for (std::size_t v = 0; v < 8; ++v) {
    const std::vector<unsigned char>& t = kSpecularTexels[v % 4];
    const Material& got = materials[v];
    INFO("vertex " << v << ": " << prt::brdf::describe(got));
    REQUIRE(got.model == prt::brdf::MaterialModel::kGltf);
    const double expected[3] = {
        std::min(0.04 * colour[0] * srgb_decode(t[0]), 1.0) * factor * t[3] / 255.0,
        std::min(0.04 * colour[1] * srgb_decode(t[1]), 1.0) * factor * t[3] / 255.0,
        std::min(0.04 * colour[2] * srgb_decode(t[2]), 1.0) * factor * t[3] / 255.0};
    CHECK(got.specular.r == Approx(expected[0]).epsilon(1e-6));
    CHECK(got.specular.g == Approx(expected[1]).epsilon(1e-6));
    CHECK(got.specular.b == Approx(expected[2]).epsilon(1e-6).margin(1e-12));
    CHECK(got.diffuse.r == Approx(0.5).epsilon(1e-6));  // the base colour
    CHECK(got.alpha_x == Approx(0.25).epsilon(1e-6));
    CHECK(got.alpha_y == Approx(0.25).epsilon(1e-6));
    if (v < 4) {
      mean_colour += glm::dvec3(srgb_decode(t[0]), srgb_decode(t[1]), srgb_decode(t[2])) / 4.0;
      mean_a += t[3] / 255.0 / 4.0;
    }
  }
  // The primitive's own BRDF is that of the textures' means.
  REQUIRE(p.brdf.has_value());
  CHECK(p.brdf->specular.r ==
        Approx(std::min(0.04 * colour[0] * mean_colour.x, 1.0) * factor * mean_a).epsilon(1e-6));
  CHECK(p.brdf->specular.g ==
        Approx(std::min(0.04 * colour[1] * mean_colour.y, 1.0) * factor * mean_a).epsilon(1e-6));
  const std::vector<std::string> lines = prt::scene::describe_materials(scene);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].find("specular, specular colour textured: 4 variants") != std::string::npos);
}

TEST_CASE(
    "KHR_materials_anisotropy texture: strength = factor × B, direction = R(rotation) · "
    "normalize(2·RG − 1) turns each vertex's tangent",
    "[scene][materials][tangents]") {
  json m = base_material(0.9, 1.0, 0.4);
  const double strength = 0.8, rotation = 0.5;
  m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", strength},
                                                 {"anisotropyRotation", rotation},
                                                 {"anisotropyTexture", {{"index", 0}}}};
  const std::vector<std::vector<unsigned char>> texels = {
      {255, 128, 255}, {128, 255, 128}, {0, 0, 64}, {200, 40, 0}};
  const Scene scene = load_strip("aniso_texture.glb", m, {prt::test::column_png(3, texels)});
  const prt::scene::ScenePrimitive& p = scene.primitives[0];
  INFO(p.brdf_texture_problem);
  CHECK(p.brdf_texture_problem.empty());
  CHECK(p.brdf_variants.size() == 4);
  REQUIRE(p.anisotropy_rotation_of_vertex.size() == 8);
  const std::vector<Material> materials = per_vertex(scene);
  const std::vector<glm::vec4> frames = prt::scene::tangent_frames(scene);
  REQUIRE(frames.size() == 8);
  const double c = std::cos(rotation), s = std::sin(rotation);
  for (std::size_t v = 0; v < 8; ++v) {
    const std::vector<unsigned char>& t = texels[v % 4];
    INFO("vertex " << v << ": " << prt::brdf::describe(materials[v]));
    // The spec's GLSL: direction = mat2(c, s, −s, c) · normalize(rg · 2 − 1), in (T, B) = (+X, +Y).
    const double x = 2.0 * t[0] / 255.0 - 1.0, y = 2.0 * t[1] / 255.0 - 1.0;
    const double len = std::hypot(x, y);
    const double dx = (c * x - s * y) / len, dy = (s * x + c * y) / len;
    CHECK(frames[v].x == Approx(dx).margin(1e-6));  // float frames
    CHECK(frames[v].y == Approx(dy).margin(1e-6));
    CHECK(frames[v].z == Approx(0.0).margin(1e-6));
    CHECK(frames[v].w == 1.f);
    // at = mix(α, 1, s²) with s = strength × B, ab = α = 0.4².
    const double sv = strength * t[2] / 255.0;
    CHECK(materials[v].alpha_x == Approx(0.16 + 0.84 * sv * sv).epsilon(1e-6));
    CHECK(materials[v].alpha_y == Approx(0.16).epsilon(1e-6));
    CHECK(materials[v].metallic == 1.0);  // metal: F0 = base colour, inside the BRDF
    CHECK(materials[v].diffuse.r == Approx(0.9).epsilon(1e-6));
  }
  CHECK(materials[3].isotropic());  // B = 0: no anisotropy
  const std::vector<std::string> lines = prt::scene::describe_materials(scene);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].find("anisotropy textured: 4 variants") != std::string::npos);
  CHECK(lines[0].find("anisotropy direction textured") != std::string::npos);
  // An override replaces the textured direction too: back to the file's tangent +X.
  Scene overridden = scene;
  prt::scene::apply_material_overrides(
      overridden, {prt::scene::parse_material_override("m=ggx:roughness=0.5")});
  CHECK(overridden.primitives[0].anisotropy_rotation_of_vertex.empty());
  for (const glm::vec4& f : prt::scene::tangent_frames(overridden))
    CHECK(f == glm::vec4(1, 0, 0, 1));
}

TEST_CASE("constant specular and anisotropy textures give the factors' material",
          "[scene][materials][tangents]") {
  json factors = base_material(0.5, 0.0, 0.5);
  factors["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.5},
                                                     {"specularColorFactor", {2.0, 1.0, 0.5}}};
  factors["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", 0.8},
                                                       {"anisotropyRotation", 0.5}};
  json textured = factors;
  textured["extensions"]["KHR_materials_specular"]["specularTexture"] = {{"index", 0}};
  textured["extensions"]["KHR_materials_specular"]["specularColorTexture"] = {{"index", 0}};
  textured["extensions"]["KHR_materials_anisotropy"]["anisotropyTexture"] = {{"index", 1}};
  const std::vector<unsigned char> white =
      prt::test::column_png(4, std::vector<std::vector<unsigned char>>(4, {255, 255, 255, 255}));
  // (R, G) = (255, 128): the spec's "no extra direction" (1, ½); G = 128 is y = 1/255, the
  // closest 8 bits come to 0.
  const std::vector<unsigned char> along =
      prt::test::column_png(3, std::vector<std::vector<unsigned char>>(4, {255, 128, 255}));
  const Scene a = load_strip("constant_textures.glb", textured, {white, along});
  const Scene b = load_strip("constant_factors.glb", factors, {});
  REQUIRE(a.primitives[0].brdf.has_value());
  REQUIRE(b.primitives[0].brdf.has_value());
  CHECK(a.primitives[0].brdf_texture_problem.empty());
  CHECK(a.primitives[0].brdf_variants.empty());  // one value everywhere: no variants
  INFO(prt::brdf::describe(*a.primitives[0].brdf)
       << " vs " << prt::brdf::describe(*b.primitives[0].brdf));
  CHECK(prt::scene::same_material(*a.primitives[0].brdf, *b.primitives[0].brdf));
  CHECK_FALSE(a.primitives[0].brdf->isotropic());
  REQUIRE(a.primitives[0].anisotropy_rotation_of_vertex.size() == 8);
  for (float r : a.primitives[0].anisotropy_rotation_of_vertex)
    CHECK(r == Approx(0.5 + std::atan(1.0 / 255.0)).margin(1e-6));
  CHECK(b.primitives[0].anisotropy_rotation == Approx(0.5f));
  CHECK(b.primitives[0].anisotropy_rotation_of_vertex.empty());
}

TEST_CASE("a specularTexture without alpha reads A = 1: the factor alone", "[scene][materials]") {
  json factors = base_material(0.5, 0.0, 0.5);
  factors["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.5}};
  json textured = factors;
  textured["extensions"]["KHR_materials_specular"]["specularTexture"] = {{"index", 0}};
  // RGB texels that differ per column: reading R, G or B as A would give four variants.
  const std::vector<unsigned char> rgb =
      prt::test::column_png(3, {{10, 20, 30}, {90, 60, 30}, {200, 100, 50}, {255, 0, 128}});
  const Scene a = load_strip("spec_rgb_only.glb", textured, {rgb});
  const Scene b = load_strip("spec_rgb_factor.glb", factors, {});
  CHECK(a.primitives[0].brdf_texture_problem.empty());
  CHECK(a.primitives[0].brdf_variants.empty());
  REQUIRE(a.primitives[0].brdf.has_value());
  REQUIRE(b.primitives[0].brdf.has_value());
  CHECK(a.primitives[0].brdf->specular.r == Approx(0.04 * 0.5).epsilon(1e-12));
  CHECK(prt::scene::same_material(*a.primitives[0].brdf, *b.primitives[0].brdf));
}

TEST_CASE("unusable specular and anisotropy textures are recorded in one line, factors used",
          "[scene][materials]") {
  const std::vector<unsigned char> png = prt::test::column_png(4, kSpecularTexels);
  json m = base_material(0.5, 0.0, 0.5);
  m["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.5}};
  const Scene plain = load_strip("spec_factor_only.glb", m, {});
  REQUIRE(plain.primitives[0].brdf.has_value());
  const auto check_recorded = [&](const Scene& s, const std::string& problem) {
    const prt::scene::ScenePrimitive& p = s.primitives[0];
    CHECK(p.brdf_texture_problem == "material 'm': " + problem);
    CHECK(p.brdf_variants.empty());
    CHECK(p.anisotropy_rotation_of_vertex.empty());
    REQUIRE(p.brdf.has_value());
    CHECK(prt::scene::same_material(*p.brdf, *plain.primitives[0].brdf));  // the factors
    const std::vector<std::string> lines = prt::scene::describe_materials(s);
    CHECK(lines.at(0).find("not used: material 'm': " + problem) != std::string::npos);
  };
  SECTION("texture index out of range") {
    m["extensions"]["KHR_materials_specular"]["specularTexture"] = {{"index", 7}};
    check_recorded(load_strip("spec_bad_index.glb", m, {png}),
                   "specularTexture texture 7 does not exist");
  }
  SECTION("textureInfo without an index") {
    m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyTexture", {{"texCoord", 0}}}};
    check_recorded(load_strip("aniso_no_index.glb", m, {png}),
                   "anisotropyTexture has no valid texture index");
  }
  SECTION("texCoord set the mesh does not have") {
    m["extensions"]["KHR_materials_specular"]["specularColorTexture"] = {{"index", 0},
                                                                         {"texCoord", 1}};
    check_recorded(load_strip("spec_no_uv1.glb", m, {png}),
                   "specularColorTexture mesh 'strip/0' has no TEXCOORD_1");
    // With TEXCOORD_1 present the same file reads the texture.
    const Scene ok = load_strip("spec_uv1.glb", m, {png}, /*texcoord1=*/true);
    CHECK(ok.primitives[0].brdf_texture_problem.empty());
    CHECK(ok.primitives[0].brdf_variants.size() == 3);  // three distinct colours in RGB
  }
}

TEST_CASE("non-finite and out-of-range specular and anisotropy factors: one line naming the file",
          "[scene][materials]") {
  json m = base_material(0.5, 0.0, 0.5);
  m["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.123456},
                                               {"specularColorFactor", {1.0, 0.234567, 1.0}}};
  m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", 0.654321},
                                                 {"anisotropyRotation", 0.111111}};
  const std::string text = prt::test::texture_strip_gltf(m, {}).dump();
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const std::size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };
  // JSON has no NaN or infinity: a number that overflows to one (1e999) is refused by the JSON
  // parser, in one line naming the file and the number.
  for (const char* from : {"0.123456", "0.654321", "0.111111", "0.234567"}) {
    const std::string error = load_error("factor_inf.glb", with(from, "-1e999"));
    INFO(error);
    CHECK(error.rfind(glb_path("factor_inf.glb") + ": cannot load glTF: ", 0) == 0);
    CHECK(error.find("-1e999") != std::string::npos);
    CHECK(error.find('\n') == std::string::npos);
  }
  const struct {
    const char *from, *to, *message;
  } cases[] = {
      {"0.123456", "1.5", "material 'm': specularFactor 1.5 outside [0, 1]"},
      {"0.234567", "-0.25", "material 'm': specularColorFactor -0.25 outside [0, 1e+06]"},
      {"0.654321", "-0.5", "material 'm': anisotropyStrength -0.5 outside [0, 1]"},
  };
  for (const auto& c : cases) {
    const std::string error = load_error("factor_bad.glb", with(c.from, c.to));
    INFO(error);
    CHECK(error == glb_path("factor_bad.glb") + ": " + c.message);
  }
  // The untouched file loads.
  CHECK(load_error("factor_ok.glb", text).empty());
}

TEST_CASE("quantise_parameters: exact up to 64 vectors, else a grid with bounded error",
          "[scene][materials]") {
  SECTION("few vectors are kept exactly") {
    std::vector<std::vector<double>> samples;
    for (int i = 0; i < 300; ++i) samples.push_back({(i % 4) / 3.0, 0.5, (i % 5) / 4.0, 1.0});
    const prt::scene::QuantisedVectors q = prt::scene::quantise_parameters(samples);
    CHECK(q.levels.size() == 20);
    for (std::size_t i = 0; i < samples.size(); ++i) CHECK(q.levels[q.level_of[i]] == samples[i]);
    for (double e : q.max_error) CHECK(e == 0.0);
  }
  SECTION("three continuous components: 4 levels each, error at most range/8") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::vector<double>> samples;
    for (int i = 0; i < 4000; ++i) samples.push_back({u(rng), 0.3, u(rng), u(rng)});
    const prt::scene::QuantisedVectors q = prt::scene::quantise_parameters(samples);
    CHECK(q.levels.size() <= 64);
    CHECK(q.levels.size() > 48);  // 4 × 4 × 4 cells, nearly all used by 4000 samples
    std::vector<double> lo(4, 1e9), hi(4, -1e9), worst(4, 0.0);
    for (const auto& s : samples)
      for (std::size_t k = 0; k < 4; ++k) {
        lo[k] = std::min(lo[k], s[k]);
        hi[k] = std::max(hi[k], s[k]);
      }
    for (std::size_t i = 0; i < samples.size(); ++i)
      for (std::size_t k = 0; k < 4; ++k)
        worst[k] = std::max(worst[k], std::fabs(q.levels[q.level_of[i]][k] - samples[i][k]));
    for (std::size_t k = 0; k < 4; ++k) {
      INFO("component " << k);
      CHECK(worst[k] == q.max_error[k]);
      CHECK(q.max_error[k] <= (hi[k] - lo[k]) / 8 + 1e-12);
    }
    CHECK(q.max_error[1] == 0.0);                  // constant: exact
    CHECK(q.max_error[0] > (hi[0] - lo[0]) / 16);  // really binned (not exact)
  }
  SECTION("only the first two varying: the metal-roughness grid") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    std::vector<std::vector<double>> samples;
    std::vector<glm::dvec2> pairs;
    for (int i = 0; i < 3000; ++i) {
      samples.push_back({u(rng), u(rng), 0.7, 0.7});
      pairs.emplace_back(samples.back()[0], samples.back()[1]);
    }
    const prt::scene::QuantisedVectors q = prt::scene::quantise_parameters(samples);
    const prt::scene::QuantisedParameters r = prt::scene::quantise_metal_roughness(pairs);
    REQUIRE(q.levels.size() == r.levels.size());
    CHECK(q.level_of == r.level_of);
    for (std::size_t l = 0; l < q.levels.size(); ++l)
      CHECK(q.levels[l] == std::vector<double>{r.levels[l].x, r.levels[l].y, 0.7, 0.7});
  }
  SECTION("bad arguments") {
    CHECK_THROWS_AS(prt::scene::quantise_parameters({{0.1, 0.2}, {0.3}}), std::invalid_argument);
    CHECK_THROWS_AS(prt::scene::quantise_parameters({{0.1}}, 65), std::invalid_argument);
  }
}
