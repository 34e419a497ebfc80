// Materials as scene files describe them (scene/src/gltf_materials.h, the OBJ loader,
// scene/material_override.h) and tangent frames (scene/tangent_frames.h): glTF metallic-
// roughness, KHR_materials_specular/ior/anisotropy → the expected α and F0; TANGENT read,
// transformed and validated; OBJ Ks/Ns → Blinn-Phong; tangents from UVs; subdivision keeps
// BRDFs, UVs and tangents; command-line overrides and their errors; the glossy procedural scene
// written as glTF and read back. Test files are written by hand (independent of prt's writer)
// except in the round trip, whose point is the writer.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "gltf_test_files.h"
#include "numerics/constants.h"
#include "prt/brdf/blinn_phong.h"
#include "scene/glb_writer.h"
#include "scene/material_override.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "scene/tangent_frames.h"
#include "support/test_data.h"

using nlohmann::json;
using prt::brdf::Material;
using prt::brdf::MaterialModel;
using prt::scene::Scene;

namespace {

using prt::numerics::kPi;

// One triangle in the z = 0 plane (normal +Z) with NORMAL, optional TANGENT and TEXCOORD_0,
// and one material; `node` is merged into the node (e.g. a scale).
json triangle(const json& material, const std::vector<float>& tangents = {},
              const std::vector<float>& uv = {}, const json& node = json::object()) {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<unsigned char> bin;
  json views = json::array(), accessors = json::array(), attributes;
  const auto add = [&](const void* data, std::size_t bytes, const char* type, std::size_t count) {
    while (bin.size() % 4) bin.push_back(0);
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    const auto* p = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), p, p + bytes);
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", 5126},
                         {"count", count},
                         {"type", type}});
    return accessors.size() - 1;
  };
  attributes["POSITION"] = add(positions, sizeof positions, "VEC3", 3);
  accessors.back()["min"] = {0, 0, 0};
  accessors.back()["max"] = {1, 1, 0};
  attributes["NORMAL"] = add(normals, sizeof normals, "VEC3", 3);
  if (!tangents.empty()) attributes["TANGENT"] = add(tangents.data(), 48, "VEC4", 3);
  if (!uv.empty()) attributes["TEXCOORD_0"] = add(uv.data(), 24, "VEC2", 3);
  json n = {{"mesh", 0}};
  n.update(node);
  json primitive = {{"attributes", attributes}};
  if (!material.is_null()) primitive["material"] = 0;
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({n})},
      {"meshes", json::array({{{"primitives", json::array({primitive})}}})},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers",
       json::array({{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + gltf_test::base64(bin)}}})}};
  if (!material.is_null()) doc["materials"] = json::array({material});
  return doc;
}

Scene load(const std::string& name, const json& doc) {
  return prt::scene::load_scene(gltf_test::write_gltf(name, doc));
}

std::string load_error(const std::string& name, const json& doc) {
  try {
    load(name, doc);
  } catch (const prt::scene::SceneError& e) {
    return e.what();
  }
  return "";
}

void check_rgb(const prt::brdf::Rgb& c, double r, double g, double b, double tolerance = 1e-6) {
  CHECK(c.r == Approx(r).margin(tolerance));
  CHECK(c.g == Approx(g).margin(tolerance));
  CHECK(c.b == Approx(b).margin(tolerance));
}

json pbr(std::vector<double> base, double metallic, double roughness) {
  return {{"name", "m"},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {base[0], base[1], base[2], 1.0}},
            {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}}};
}

}  // namespace

// Tolerance 1e-6: factors are float (baseColor goes through the float albedo), the mapping is
// exact arithmetic.
TEST_CASE("glTF metallic-roughness maps to the spec's BRDF: alpha = roughness^2, base, metallic",
          "[scene][materials]") {
  const Scene s = load("pbr_mix.gltf", triangle(pbr({0.5, 0.4, 0.3}, 0.25, 0.6)));
  REQUIRE(s.primitives.size() == 1);
  REQUIRE(s.primitives[0].brdf.has_value());
  const Material& m = *s.primitives[0].brdf;
  CHECK(m.model == MaterialModel::kGltf);
  CHECK(m.distribution == prt::brdf::NormalDistribution::kGgx);
  CHECK(m.fresnel == prt::brdf::FresnelMode::kSchlick);
  CHECK(m.alpha_x == Approx(0.36).margin(1e-12));
  CHECK(m.alpha_y == Approx(0.36).margin(1e-12));
  check_rgb(m.specular, 0.04, 0.04, 0.04);  // the dielectric F0; the mix is the BRDF's
  check_rgb(m.diffuse, 0.5, 0.4, 0.3);
  CHECK(m.metallic == 0.25);
  CHECK(s.primitives[0].albedo.x == Approx(0.5f));  // the diffuse path is unchanged
  CHECK(prt::brdf::make_brdf(m).ok());

  // A metal: metallic 1, base colour its F0; roughness 0 is raised to alpha 0.001.
  const Scene metal = load("pbr_metal.gltf", triangle(pbr({0.9, 0.6, 0.3}, 1.0, 0.0)));
  const Material& mm = *metal.primitives[0].brdf;
  CHECK(mm.metallic == 1.0);
  check_rgb(mm.diffuse, 0.9, 0.6, 0.3);
  CHECK(mm.alpha_x == 1e-3);
  CHECK(prt::brdf::make_brdf(mm).ok());
}

TEST_CASE("glTF defaults: which materials stay Lambert", "[scene][materials]") {
  // No material at all: prt's Lambert grey, no BRDF.
  CHECK_FALSE(load("no_material.gltf", triangle(json())).primitives[0].brdf);
  // metallic 0, roughness 1, no KHR_materials_specular: prt's matte convention.
  CHECK_FALSE(load("matte.gltf", triangle(pbr({0.5, 0.5, 0.5}, 0.0, 1.0))).primitives[0].brdf);
  // specularFactor 0: the spec's pure diffuse, at any roughness.
  json diffuse = pbr({0.5, 0.5, 0.5}, 0.0, 0.3);
  diffuse["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.0}};
  CHECK_FALSE(load("spec0.gltf", triangle(diffuse)).primitives[0].brdf);
  // The same matte material WITH the specular extension is the spec's rough dielectric.
  json rough = pbr({0.5, 0.5, 0.5}, 0.0, 1.0);
  rough["extensions"]["KHR_materials_specular"] = json::object();
  const Scene r = load("rough_dielectric.gltf", triangle(rough));
  REQUIRE(r.primitives[0].brdf);
  CHECK(r.primitives[0].brdf->alpha_x == 1.0);
  check_rgb(r.primitives[0].brdf->specular, 0.04, 0.04, 0.04);
  // A material object with no pbrMetallicRoughness: the spec's defaults, metallic 1,
  // roughness 1, baseColor 1 — a rough white metal.
  const Scene defaults = load("defaults.gltf", triangle(json{{"name", "empty"}}));
  REQUIRE(defaults.primitives[0].brdf);
  const Material& d = *defaults.primitives[0].brdf;
  CHECK(d.alpha_x == 1.0);
  CHECK(d.metallic == 1.0);
  check_rgb(d.diffuse, 1, 1, 1);
}

TEST_CASE("KHR_materials_specular and KHR_materials_ior scale the dielectric F0",
          "[scene][materials]") {
  json m = pbr({0.2, 0.2, 0.2}, 0.0, 0.5);
  m["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.5},
                                               {"specularColorFactor", {2.0, 1.0, 0.5}}};
  const Material a = *load("specular.gltf", triangle(m)).primitives[0].brdf;
  check_rgb(a.specular, 0.04 * 2 * 0.5, 0.04 * 0.5, 0.04 * 0.5 * 0.5);
  CHECK(a.alpha_x == Approx(0.25));
  // F0 clamps at 1 before specularFactor: 0.02 × 100 → 1.
  m["extensions"]["KHR_materials_specular"] = {{"specularColorFactor", {100.0, 1.0, 1.0}}};
  m["extensions"]["KHR_materials_ior"] = {{"ior", 1.33}};
  const Material b = *load("specular_ior.gltf", triangle(m)).primitives[0].brdf;
  const double f0 = std::pow(0.33 / 2.33, 2.0);
  check_rgb(b.specular, 1.0, f0, f0);
  // A metal's F0 is its base colour (metallic 1 weights the dielectric F0 by 0 in the BRDF).
  json metal = pbr({0.8, 0.7, 0.6}, 1.0, 0.5);
  metal["extensions"] = m["extensions"];
  const Material mm = *load("specular_metal.gltf", triangle(metal)).primitives[0].brdf;
  CHECK(mm.metallic == 1.0);
  check_rgb(mm.diffuse, 0.8, 0.7, 0.6);
}

TEST_CASE("KHR_materials_anisotropy: alpha_t = mix(alpha, 1, s^2) along the rotated tangent",
          "[scene][materials][tangents]") {
  json m = pbr({0.9, 0.9, 0.9}, 1.0, 0.4);
  m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", 0.5},
                                                 {"anisotropyRotation", 0.3}};
  const std::vector<float> t = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const Scene s = load("aniso.gltf", triangle(m, t));
  const Material& b = *s.primitives[0].brdf;
  CHECK(b.alpha_x == Approx(0.16 + 0.84 * 0.25).margin(1e-12));
  CHECK(b.alpha_y == Approx(0.16).margin(1e-12));
  CHECK_FALSE(b.isotropic());
  CHECK(s.primitives[0].anisotropy_rotation == Approx(0.3f));
  // The α_x direction: the tangent +X turned by 0.3 rad toward the bitangent cross(+Z, +X) = +Y.
  const std::vector<glm::vec4> frames = prt::scene::tangent_frames(s);
  for (const glm::vec4& f : frames) {
    CHECK(f.x == Approx(std::cos(0.3)).margin(1e-6));
    CHECK(f.y == Approx(std::sin(0.3)).margin(1e-6));
    CHECK(f.z == Approx(0.0).margin(1e-6));
    CHECK(f.w == 1.f);
  }
  // Out-of-range factors are refused in one line naming the material.
  m["extensions"]["KHR_materials_anisotropy"]["anisotropyStrength"] = 1.5;
  const std::string error = load_error("aniso_bad.gltf", triangle(m, t));
  CHECK(error.find("material 'm': anisotropyStrength 1.5 outside [0, 1]") != std::string::npos);
  CHECK(load_error("rough_bad.gltf", triangle(pbr({0.5, 0.5, 0.5}, 0.0, -0.1)))
            .find("roughnessFactor -0.1 outside [0, 1]") != std::string::npos);
}

TEST_CASE("glTF TANGENT is read, transformed, and bad values are regenerated",
          "[scene][tangents]") {
  const json matte = pbr({0.5, 0.5, 0.5}, 0.0, 1.0);
  const std::vector<float> t = {0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1};
  const Scene s = load("tangent.gltf", triangle(matte, t));
  REQUIRE(s.tangents.size() == 3);
  CHECK(s.tangents[0] == glm::vec4(0, 1, 0, -1));
  // A node mirrored in X: the tangent (a surface direction) is unchanged by the X flip here,
  // but the handedness flips so that w · cross(n, t) is still the transformed bitangent.
  const Scene mirrored = load(
      "tangent_mirrored.gltf",
      triangle(matte, {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, {}, json{{"scale", {-1.0, 1.0, 1.0}}}));
  REQUIRE(mirrored.tangents.size() == 3);
  CHECK(mirrored.tangents[1] == glm::vec4(-1, 0, 0, -1));
  // The file's bitangent was +Y (w · cross(+Z, +X)); mirrored in X it is still +Y.
  const glm::vec3 n = mirrored.normals[1];
  const glm::vec3 b = mirrored.tangents[1].w * glm::cross(n, glm::vec3(mirrored.tangents[1]));
  CHECK(b.y == Approx(1.f));
  // w = 0.5, a NaN or a zero vector: replaced by zero, and tangent_frames generates a frame.
  const std::vector<float> bad = {1, 0, 0, 0.5f, std::nanf(""), 0, 0, 1, 0, 0, 0, 1};
  const Scene r = load("tangent_bad.gltf", triangle(matte, bad));
  REQUIRE(r.tangents.size() == 3);
  for (const glm::vec4& v : r.tangents) CHECK(v == glm::vec4(0.f));
  for (const glm::vec4& f : prt::scene::tangent_frames(r))
    CHECK(f == prt::scene::normal_only_tangent(glm::vec3(0, 0, 1)));
}

TEST_CASE("anisotropic glTF without TANGENT takes its tangents from TEXCOORD_0",
          "[scene][tangents]") {
  json m = pbr({0.9, 0.9, 0.9}, 1.0, 0.4);
  m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", 0.5}};
  // u runs along +Y on this triangle (u = y, v = x): the tangent must be +Y, the bitangent
  // (increasing v) +X, so w = −1 (cross(+Z, +Y) = −X).
  const Scene s = load("aniso_uv.gltf", triangle(m, {}, {0, 0, 0, 1, 1, 0}));
  REQUIRE(s.texcoords.size() == 3);
  for (const glm::vec4& f : prt::scene::tangent_frames(s)) {
    CHECK(f.y == Approx(1.f).margin(1e-6));
    CHECK(f.w == -1.f);
  }
  // An isotropic material does not keep its UVs (no texture either).
  CHECK(load("iso_uv.gltf", triangle(pbr({0.9, 0.9, 0.9}, 1.0, 0.4), {}, {0, 0, 0, 1, 1, 0}))
            .texcoords.empty());
}

namespace {

// An OBJ quad with an MTL of one material `m` whose lines are `mtl_body`.
std::string write_obj(const std::string& name, const std::string& mtl_body) {
  const auto obj = prt::test::output_path(name + ".obj");
  std::ofstream(prt::test::output_path(name + ".mtl")) << "newmtl m\n" << mtl_body;
  std::ofstream(obj) << "mtllib " << name << ".mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     << "usemtl m\nf 1 2 3 4\n";
  return obj.string();
}

}  // namespace

TEST_CASE("OBJ Ks/Ns become normalised Blinn-Phong (k_L = Kd, k_G = Ks, s = Ns)",
          "[scene][materials]") {
  const Scene s = prt::scene::load_scene(
      write_obj("phong", "Kd 0.5 0.4 0.3\nKs 0.3 0.2 0.1\nNs 40\nillum 2\n"));
  REQUIRE(s.primitives[0].brdf);
  const Material& m = *s.primitives[0].brdf;
  CHECK(m.model == MaterialModel::kBlinnPhong);
  check_rgb(m.diffuse, 0.5, 0.4, 0.3);
  check_rgb(m.specular, 0.3, 0.2, 0.1);
  CHECK(m.exponent == 40.0);
  // No Ks, Ks 0, or illum 1 ("no specular"): Lambert.
  CHECK_FALSE(
      prt::scene::load_scene(write_obj("no_ks", "Kd 0.5 0.5 0.5\nNs 40\n")).primitives[0].brdf);
  CHECK_FALSE(prt::scene::load_scene(write_obj("ks0", "Kd 0.5 0.5 0.5\nKs 0 0 0\nNs 40\n"))
                  .primitives[0]
                  .brdf);
  CHECK_FALSE(
      prt::scene::load_scene(write_obj("illum1", "Kd 0.5 0.5 0.5\nKs 0.3 0.3 0.3\nillum 1\n"))
          .primitives[0]
          .brdf);
  // Kd + Ks > 1: k_G lowered in that channel only, to (1 − Kd) over the lobe's largest albedo —
  // at normal incidence for Blinn-Phong, the closed form (8 + s)/(8π) normalisation's 1.0748 at
  // s = 10 (the quadrature's bound, 3e-3, as the tolerance).
  const Scene over =
      prt::scene::load_scene(write_obj("over", "Kd 0.8 0.2 0.2\nKs 0.5 0.5 0.5\nNs 10\n"));
  check_rgb(over.primitives[0].brdf->specular, 0.2 / prt::brdf::blinn_phong_normal_albedo(10.0),
            0.5, 0.5, 3e-3);
  // Kd + Ks ≤ 1 whose normalised lobe still reflects more than arrives: refused, one line.
  try {
    prt::scene::load_scene(write_obj("hot", "Kd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 10\n"));
    FAIL("accepted a Blinn-Phong material of albedo 1.04");
  } catch (const prt::scene::SceneError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("hot.obj: material 'm' blinn-phong(") != std::string::npos);
    CHECK(message.find("directional albedo must not exceed 1") != std::string::npos);
  }
  // A negative exponent is refused in one line naming the material.
  try {
    prt::scene::load_scene(write_obj("neg_ns", "Kd 0.5 0.5 0.5\nKs 0.3 0.3 0.3\nNs -3\n"));
    FAIL("accepted Ns -3");
  } catch (const prt::scene::SceneError& e) {
    const std::string message = e.what();
    CHECK(message.find("neg_ns.obj: material 'm': ") != std::string::npos);
    CHECK(message.find("-3") != std::string::npos);
  }
}

// A skewed UV parameterisation: P = corner + s·edge_u + t·edge_v with (u, v) = (s, t), so
// dP/du = edge_u and dP/dv = edge_v exactly; mirrored u (u = 1 − s) flips the tangent and w.
TEST_CASE("tangents from UVs follow dP/du with the handedness of dP/dv", "[scene][tangents]") {
  const glm::vec3 edge_u(2.f, 0.f, 0.5f), edge_v(0.7f, 0.f, -1.5f);
  Scene plane = prt::scene::make_quad({0, 0, 0}, edge_u, edge_v, 4, 3, glm::vec3(0.5f));
  const glm::vec3 du = glm::normalize(edge_u);
  for (const glm::vec4& t : prt::scene::uv_tangents(plane)) {
    CHECK(glm::dot(glm::vec3(t), du) == Approx(1.f).margin(1e-5));
    CHECK(t.w == 1.f);
  }
  for (glm::vec2& uv : plane.texcoords) uv.x = 1.f - uv.x;
  for (const glm::vec4& t : prt::scene::tangent_frames(plane)) {
    CHECK(glm::dot(glm::vec3(t), du) == Approx(-1.f).margin(1e-5));
    CHECK(t.w == -1.f);
  }
  // Degenerate UVs (all zero): the frame from the normal.
  for (glm::vec2& uv : plane.texcoords) uv = glm::vec2(0.f);
  for (std::size_t v = 0; v < plane.vertex_count(); ++v)
    CHECK(prt::scene::tangent_frames(plane)[v] ==
          prt::scene::normal_only_tangent(plane.normals[v]));
}

// A UV sphere with (u, v) = (φ/2π, θ/π): away from the poles and the u seam the tangent is the
// direction of increasing φ, (−sin φ, 0, cos φ); everywhere it is a unit vector ⊥ the normal.
// Tolerances: float positions on a 32×64 sphere, tangents averaged over ~6 triangles whose
// chords differ from the analytic derivative by O(h²) ≈ 1e-3.
TEST_CASE("UV tangents on a sphere are orthonormal to the normals and follow phi",
          "[scene][tangents]") {
  const int rings = 32, segments = 64;
  Scene s = prt::scene::make_uv_sphere({0, 0, 0}, 1.f, rings, segments, false, glm::vec3(0.5f));
  s.texcoords.resize(s.vertex_count());
  for (std::size_t v = 0; v < s.vertex_count(); ++v) {
    const glm::vec3 p = s.positions[v];
    const double phi = std::atan2(double(p.z), double(p.x));
    s.texcoords[v] = glm::vec2(float((phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi)),
                               float(std::acos(std::clamp(double(p.y), -1.0, 1.0)) / kPi));
  }
  const std::vector<glm::vec4> frames = prt::scene::tangent_frames(s);
  int checked = 0;
  for (std::size_t v = 0; v < s.vertex_count(); ++v) {
    const glm::vec3 t(frames[v]);
    CHECK(glm::length(t) == Approx(1.f).margin(1e-5));
    CHECK(std::fabs(glm::dot(t, s.normals[v])) < 1e-5f);
    const glm::vec3 p = s.positions[v];
    const int ring = int(std::lround(std::acos(std::clamp(double(p.y), -1.0, 1.0)) / kPi * rings));
    const int seg = int(std::lround(s.texcoords[v].x * segments)) % segments;
    if (ring < 2 || ring > rings - 2 || seg < 1 || seg > segments - 2) continue;
    const double phi = 2 * kPi * seg / segments;
    CHECK(glm::dot(t, glm::vec3(float(-std::sin(phi)), 0.f, float(std::cos(phi)))) > 0.999f);
    CHECK(frames[v].w == frames[s.vertex_count() / 2].w);  // one handedness everywhere
    ++checked;
  }
  CHECK(checked > 1500);
}

TEST_CASE("subdivision carries BRDFs, rotations, UVs and tangents", "[scene][tangents]") {
  Scene disc = prt::scene::make_disc({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, 1.f, 2, 12, glm::vec3(0.5f));
  Material m;
  m.model = MaterialModel::kWard;
  m.specular = prt::brdf::grey(0.5);
  m.alpha_x = 0.3;
  m.alpha_y = 0.1;
  disc.primitives[0].brdf = m;
  disc.primitives[0].anisotropy_rotation = 0.5f;
  disc.texcoords.assign(disc.vertex_count(), glm::vec2(0.25f, 0.75f));
  const Scene fine = prt::scene::subdivide_to_edge_length(disc, 0.1);
  REQUIRE(fine.vertex_count() > 4 * disc.vertex_count());
  REQUIRE(fine.primitives[0].brdf);
  CHECK(fine.primitives[0].brdf->alpha_x == 0.3);
  CHECK(fine.primitives[0].anisotropy_rotation == 0.5f);
  REQUIRE(fine.texcoords.size() == fine.vertex_count());
  REQUIRE(fine.tangents.size() == fine.vertex_count());
  CHECK(fine.texcoords.back() == glm::vec2(0.25f, 0.75f));
  // New vertices off the centre: the interpolated circle tangent stays ⊥ the radius.
  int checked = 0;
  for (std::size_t v = disc.vertex_count(); v < fine.vertex_count(); ++v) {
    const glm::vec3 p = fine.positions[v];
    const glm::vec4 t = fine.tangents[v];
    CHECK(std::fabs(glm::length(glm::vec3(t)) - 1.f) < 1e-5f);
    if (glm::length(p) > 0.55f) {  // outside the fan around the centre
      CHECK(std::fabs(glm::dot(glm::vec3(t), glm::normalize(p))) < 0.27f);  // chord: ≤ sin(15°)
      ++checked;
    }
  }
  CHECK(checked > 50);
}

TEST_CASE("material overrides: every model parses to the expected Material", "[scene][override]") {
  using prt::scene::parse_material_override;
  const auto w = parse_material_override("metal=ward:rho_d=0.1,rho_s=0.4/0.3/0.2,ax=0.3,ay=0.1");
  CHECK(w.name == "metal");
  CHECK(w.material.model == MaterialModel::kWard);
  check_rgb(w.material.specular, 0.4, 0.3, 0.2);
  CHECK(w.material.alpha_x == 0.3);
  CHECK(w.material.alpha_y == 0.1);
  const auto g = parse_material_override("*=ggx:roughness=0.5,f0=0.9/0.6/0.3,kd=0.1");
  CHECK(g.material.model == MaterialModel::kMicrofacet);
  CHECK(g.material.distribution == prt::brdf::NormalDistribution::kGgx);
  CHECK(g.material.alpha_x == 0.25);
  CHECK(g.material.alpha_y == 0.25);
  check_rgb(g.material.diffuse, 0.1, 0.1, 0.1);
  const auto spec = parse_material_override("s=gltf:base=0.2/0.4/0.8,roughness=0.4,metallic=0.5");
  CHECK(spec.material.model == MaterialModel::kGltf);
  check_rgb(spec.material.diffuse, 0.2, 0.4, 0.8);
  check_rgb(spec.material.specular, 0.04, 0.04, 0.04);
  CHECK(spec.material.metallic == 0.5);
  CHECK(spec.material.alpha_x == Approx(0.16));
  // gltf-additive: F0 = mix(0.04, base, m) over an added Lambert layer base · (1 − m).
  const auto add =
      parse_material_override("a=gltf-additive:base=0.2/0.4/0.8,roughness=0.4,metallic=0.5");
  CHECK(add.material.model == MaterialModel::kMicrofacet);
  check_rgb(add.material.diffuse, 0.1, 0.2, 0.4);
  check_rgb(add.material.specular, 0.12, 0.22, 0.42);
  CHECK(add.material.alpha_y == Approx(0.16));
  const auto b = parse_material_override("x=beckmann:alpha=0.2,fresnel=dielectric,eta=1.33");
  CHECK(b.material.distribution == prt::brdf::NormalDistribution::kBeckmann);
  CHECK(b.material.fresnel == prt::brdf::FresnelMode::kDielectric);
  CHECK(b.material.eta == 1.33);
  const auto p = parse_material_override("x=blinn-phong:kd=0.5,ks=0.3,s=50");
  CHECK(p.material.model == MaterialModel::kBlinnPhong);
  CHECK(p.material.exponent == 50);
  const auto l = parse_material_override("x=lambert:kd=0.2/0.3/0.4");
  CHECK(l.material.lambertian());
  CHECK(l.set_albedo);
}

TEST_CASE("material override errors are one line naming the option and the problem",
          "[scene][override]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"m=ggx:roughness=0", "alpha_x is 0, must be in [0.001, 1]"},
      {"m=ggx:alpha=nan", "NaN"},
      {"m=ward:rho_s=0.5,ax=0", "must be in [0.001, 1]"},
      {"m=blinn-phong:ks=0.3,s=-1", "is -1, must be in [0"},
      {"m=plastic:alpha=0.1", "unknown model 'plastic'"},
      {"m=ggx:alpha=0.1,shiny=1", "unknown key 'shiny'"},
      {"m=ggx", "ggx needs alpha"},
      {"m=ggx:alpha=0.1,roughness=0.3", "only one of"},
      {"m=ggx:alpha=abc", "'abc' is not a number"},
      {"m=lambert:kd=0.1/0.2", "expected one value or r/g/b"},
      {"=ggx:alpha=0.1", "expected NAME=MODEL"},
      {"m=merl", "merl needs a file"},
      {"m=merl:" + prt::test::output_path("no_such_merl.binary").string(), "cannot open"},
  };
  for (const auto& [text, expect] : cases) {
    try {
      prt::scene::parse_material_override(text);
      FAIL("accepted " << text);
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      INFO(message);
      const std::string prefix = "--material " + text + ": ";
      CHECK(message.rfind(prefix, 0) == 0);
      CHECK(message.find(expect, prefix.size()) != std::string::npos);  // in the problem part
      CHECK(message.find('\n') == std::string::npos);
    }
  }
  // A truncated MERL file: make_brdf's message.
  const std::string truncated = prt::test::output_path("override_truncated.binary").string();
  {
    const int32_t dims[3] = {90, 90, 180};
    std::ofstream(truncated, std::ios::binary).write(reinterpret_cast<const char*>(dims), 12);
  }
  CHECK_THROWS_WITH(prt::scene::parse_material_override("m=merl:" + truncated),
                    Catch::Contains("truncated MERL file"));
}

TEST_CASE("material overrides apply by material or primitive name, unknown names are refused",
          "[scene][override]") {
  Scene s = prt::scene::make_glossy_scene();
  using prt::scene::parse_material_override;
  prt::scene::apply_material_overrides(
      s, {parse_material_override("rough_gold=ward:rho_s=0.5,alpha=0.2"),
          parse_material_override("floor=lambert:kd=0.3"),
          parse_material_override("glossy_sphere=lambert")});
  for (const auto& p : s.primitives) {
    if (p.material == "rough_gold") CHECK(p.brdf->model == MaterialModel::kWard);
    if (p.material == "floor") {
      CHECK_FALSE(p.brdf);
      CHECK(p.albedo == glm::vec3(0.3f));
      CHECK(s.albedo[p.first_vertex] == glm::vec3(0.3f));
    }
    if (p.name == "glossy_sphere") {
      CHECK_FALSE(p.brdf);                               // the BRDF removed
      CHECK(p.albedo == glm::vec3(0.7f, 0.08f, 0.06f));  // the albedo kept
    }
  }
  CHECK_THROWS_WITH(
      prt::scene::apply_material_overrides(s, {parse_material_override("chrome=ggx:alpha=0.1")}),
      Catch::StartsWith("--material chrome=ggx:alpha=0.1: no material or primitive "
                        "named 'chrome' in procedural:glossy (materials: 'floor', "));
}

// The glossy scene through prt's writer and loader: the same BRDFs (α to 1e-9: roughness is
// written as √α in double; colours exact through float), rotations and tangents (float).
TEST_CASE("the glossy scene round-trips through glTF with its materials and tangents",
          "[scene][materials][tangents]") {
  const Scene made = prt::scene::make_glossy_scene();
  const std::string path = prt::test::output_path("glossy_round_trip.glb").string();
  prt::scene::write_glb(path, made);
  const Scene loaded = prt::scene::load_scene(path);
  REQUIRE(loaded.primitives.size() == made.primitives.size());
  REQUIRE(loaded.tangents.size() == made.tangents.size());
  int glossy = 0, anisotropic = 0;
  for (std::size_t i = 0; i < made.primitives.size(); ++i) {
    const auto& a = made.primitives[i];
    const auto& b = loaded.primitives[i];
    INFO(a.name);
    CHECK(a.albedo == b.albedo);
    CHECK(a.material == b.material);
    REQUIRE(a.brdf.has_value() == b.brdf.has_value());
    if (!a.brdf) continue;
    ++glossy;
    anisotropic += a.brdf->isotropic() ? 0 : 1;
    CHECK(b.brdf->model == MaterialModel::kGltf);
    CHECK(b.brdf->metallic == a.brdf->metallic);
    CHECK(b.brdf->alpha_x == Approx(a.brdf->alpha_x).margin(1e-9));
    CHECK(b.brdf->alpha_y == Approx(a.brdf->alpha_y).margin(1e-9));
    check_rgb(b.brdf->specular, a.brdf->specular.r, a.brdf->specular.g, a.brdf->specular.b, 1e-7);
    check_rgb(b.brdf->diffuse, a.brdf->diffuse.r, a.brdf->diffuse.g, a.brdf->diffuse.b, 1e-7);
    CHECK(b.anisotropy_rotation == a.anisotropy_rotation);
    CHECK(prt::brdf::make_brdf(*b.brdf).ok());
  }
  CHECK(glossy == 3);
  CHECK(anisotropic == 1);
  for (std::size_t v = 0; v < made.tangents.size(); ++v) {
    REQUIRE(glm::length(glm::vec3(loaded.tangents[v] - made.tangents[v])) < 1e-6f);
    REQUIRE(loaded.tangents[v].w == made.tangents[v].w);
  }
  // The disc's tangents run along its circles: ⊥ to the radius from its centre.
  for (const auto& p : made.primitives) {
    if (p.name != "brushed_disc") continue;
    const glm::vec3 centre = made.positions[p.first_vertex];
    for (uint32_t v = p.first_vertex + 1; v < p.first_vertex + p.vertex_count; ++v)
      CHECK(std::fabs(glm::dot(glm::vec3(made.tangents[v]),
                               glm::normalize(made.positions[v] - centre))) < 1e-5f);
  }
}
