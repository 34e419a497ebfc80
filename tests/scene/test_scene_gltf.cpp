// glTF loading (scene/scene_loader.h) on small files written by the tests, and on real assets.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <OpenImageIO/imageio.h>

#include "scene/scene_loader.h"
#include "support/base64.h"
#include "support/png_writer.h"
#include "support/test_data.h"

using nlohmann::json;
using prt::scene::Scene;
using prt::scene::SceneError;

namespace {

constexpr int kFloat = 5126, kU8 = 5121, kU16 = 5123, kU32 = 5125;

// A minimal glTF document with one external binary buffer, built by hand (independent of the
// project's writer).
struct MiniGltf {
  json doc;
  std::vector<unsigned char> bin;

  MiniGltf() {
    doc = {{"asset", {{"version", "2.0"}}},
           {"scene", 0},
           {"scenes", json::array({{{"nodes", json::array({0})}}})},
           {"nodes", json::array()},
           {"meshes", json::array()},
           {"accessors", json::array()},
           {"bufferViews", json::array()},
           {"buffers", json::array()}};
  }

  int add_accessor(const void* bytes, std::size_t size, int component_type, std::size_t count,
                   const char* type) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    const auto* p = static_cast<const unsigned char*>(bytes);
    bin.insert(bin.end(), p, p + size);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                {"componentType", component_type},
                                {"count", count},
                                {"type", type}});
    return static_cast<int>(doc["accessors"].size() - 1);
  }

  int add_vec3(const std::vector<glm::vec3>& v) {
    const int a = add_accessor(v.data(), v.size() * 12, kFloat, v.size(), "VEC3");
    if (!v.empty()) {
      glm::vec3 lo = v[0], hi = v[0];
      for (const auto& x : v) lo = glm::min(lo, x), hi = glm::max(hi, x);
      doc["accessors"][static_cast<std::size_t>(a)]["min"] = {lo.x, lo.y, lo.z};
      doc["accessors"][static_cast<std::size_t>(a)]["max"] = {hi.x, hi.y, hi.z};
    }
    return a;
  }

  int add_vec2(const std::vector<glm::vec2>& v) {
    return add_accessor(v.data(), v.size() * 8, kFloat, v.size(), "VEC2");
  }

  // An image stored in a buffer view (as in a GLB); returns the image index.
  int add_image_in_buffer(const std::vector<unsigned char>& bytes, const std::string& mime) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.insert(bin.end(), bytes.begin(), bytes.end());
    doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
    doc["images"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"mimeType", mime}});
    return static_cast<int>(doc["images"].size() - 1);
  }

  int add_indices(const std::vector<uint32_t>& indices, int component_type) {
    std::vector<unsigned char> bytes;
    for (uint32_t i : indices) {
      const std::size_t size = component_type == kU8 ? 1 : component_type == kU16 ? 2 : 4;
      unsigned char raw[4];
      std::memcpy(raw, &i, 4);  // little-endian host (x86-64), as glTF requires
      bytes.insert(bytes.end(), raw, raw + size);
    }
    return add_accessor(bytes.data(), bytes.size(), component_type, indices.size(), "SCALAR");
  }

  // Adds a mesh with one TRIANGLES primitive and a node showing it; returns the node index.
  int add_mesh_node(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                    int index_type = kU32, const std::vector<glm::vec3>& normals = {}) {
    json primitive = {{"attributes", {{"POSITION", add_vec3(positions)}}}, {"mode", 4}};
    if (!normals.empty()) primitive["attributes"]["NORMAL"] = add_vec3(normals);
    if (index_type != 0) primitive["indices"] = add_indices(indices, index_type);
    std::string name = "m";
    name += std::to_string(doc["meshes"].size());
    doc["meshes"].push_back({{"name", name}, {"primitives", json::array({primitive})}});
    doc["nodes"].push_back({{"mesh", doc["meshes"].size() - 1}});
    return static_cast<int>(doc["nodes"].size() - 1);
  }

  // Writes NAME.gltf and NAME.bin into the scratch directory; returns the .gltf path.
  std::string write(const std::string& name) {
    const std::string bin_name = name + ".bin";
    doc["buffers"] = json::array({{{"uri", bin_name}, {"byteLength", bin.size()}}});
    std::ofstream(prt::test::output_path(bin_name), std::ios::binary)
        .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
    const auto path = prt::test::output_path(name + ".gltf");
    std::ofstream(path) << doc.dump(1);
    return path.string();
  }

  // Writes NAME.glb (JSON chunk, then the buffer as the BIN chunk); returns its path.
  std::string write_glb(const std::string& name) {
    doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> body = bin;
    while (body.size() % 4) body.push_back(0);
    std::vector<unsigned char> out;
    const auto put32 = [&](uint32_t x) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<unsigned char>(x >> (8 * k)));
    };
    put32(0x46546C67);  // "glTF"
    put32(2);
    put32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + body.size()));
    put32(static_cast<uint32_t>(text.size()));
    put32(0x4E4F534A);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    put32(static_cast<uint32_t>(body.size()));
    put32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), body.begin(), body.end());
    const auto path = prt::test::output_path(name + ".glb");
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
    return path.string();
  }
};

const std::vector<glm::vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

std::string error_of(const std::string& path, const prt::scene::LoadOptions& options = {}) {
  try {
    prt::scene::load_scene(path, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// A loader message is one line, starts with the path, and mentions `needle`.
void check_error(const std::string& message, const std::string& path, const std::string& needle) {
  INFO(message);
  REQUIRE_FALSE(message.empty());
  CHECK(message.rfind(path + ": ", 0) == 0);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find(needle) != std::string::npos);
}

}  // namespace

TEST_CASE("glTF node TRS is applied to positions and normals use the inverse transpose") {
  // A tilted triangle whose NORMAL is its true face normal; a non-uniform scale bends normals,
  // so only the inverse transpose keeps them perpendicular to the transformed triangle.
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}};
  const glm::vec3 face =
      glm::normalize(glm::cross(positions[1] - positions[0], positions[2] - positions[0]));
  MiniGltf g;
  g.add_mesh_node(positions, {0, 1, 2}, kU16, {face, face, face});
  const glm::dvec3 axis = glm::normalize(glm::dvec3(1, 2, 2));
  const double angle = 0.7;
  const glm::dvec3 t(1, 2, 3), sc(2, 0.5, 1.5);
  g.doc["nodes"][0]["translation"] = {t.x, t.y, t.z};
  g.doc["nodes"][0]["rotation"] = {axis.x * std::sin(angle / 2), axis.y * std::sin(angle / 2),
                                   axis.z * std::sin(angle / 2), std::cos(angle / 2)};
  g.doc["nodes"][0]["scale"] = {sc.x, sc.y, sc.z};
  const Scene s = prt::scene::load_scene(g.write("trs"));

  // Independent reference: T * R(axis-angle) * S built with glm's matrix helpers.
  const glm::dmat4 m = glm::scale(glm::rotate(glm::translate(glm::dmat4(1.0), t), angle, axis), sc);
  REQUIRE(s.positions.size() == 3);
  for (std::size_t v = 0; v < 3; ++v) {
    const glm::dvec3 expected(m * glm::dvec4(glm::dvec3(positions[v]), 1.0));
    // Float storage of O(5)-sized coordinates: 1e-5 absolute.
    CHECK(glm::distance(glm::dvec3(s.positions[v]), expected) < 1e-5);
  }
  const glm::dvec3 e1 = glm::dvec3(s.positions[1] - s.positions[0]);
  const glm::dvec3 e2 = glm::dvec3(s.positions[2] - s.positions[0]);
  for (const glm::vec3& n : s.normals) {
    CHECK(glm::length(n) == Approx(1.0).margin(1e-6));
    CHECK(glm::dot(glm::dvec3(n), glm::normalize(e1)) == Approx(0.0).margin(1e-5));
    CHECK(glm::dot(glm::dvec3(n), glm::normalize(e2)) == Approx(0.0).margin(1e-5));
    CHECK(glm::dot(glm::dvec3(n), glm::cross(e1, e2)) > 0.0);  // same side as the winding
  }
  CHECK(s.computed_normal_vertices == 0);
}

TEST_CASE("glTF hierarchy composes parent TRS with a child matrix, depth-first") {
  MiniGltf g;
  const int child = g.add_mesh_node(kTriangle, {0, 1, 2});
  // Column-major matrix: scale 2 and translation (1, 0, 0).
  g.doc["nodes"][static_cast<std::size_t>(child)]["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0,
                                                               0, 0, 2, 0, 1, 0, 0, 1};
  const int sibling = g.add_mesh_node(kTriangle, {0, 1, 2});
  g.doc["nodes"].push_back({{"translation", {0, 10, 0}}, {"children", {child}}});
  g.doc["scenes"][0]["nodes"] = {g.doc["nodes"].size() - 1, sibling};
  const Scene s = prt::scene::load_scene(g.write("hierarchy"));
  REQUIRE(s.primitives.size() == 2);
  REQUIRE(s.positions.size() == 6);
  for (std::size_t v = 0; v < 3; ++v) {
    CHECK(glm::distance(s.positions[v],
                        glm::vec3(0, 10, 0) + 2.f * kTriangle[v] + glm::vec3(1, 0, 0)) < 1e-6f);
    CHECK(glm::distance(s.positions[3 + v], kTriangle[v]) < 1e-6f);
  }
  // No NORMAL in the file: computed, +Z for this winding.
  CHECK(s.computed_normal_vertices == 6);
  for (const glm::vec3& n : s.normals) CHECK(glm::distance(n, glm::vec3(0, 0, 1)) < 1e-6f);
}

TEST_CASE("glTF u8, u16, u32 and absent indices give the same triangles") {
  std::vector<Scene> scenes;
  for (const int type : {kU8, kU16, kU32}) {
    MiniGltf g;
    g.add_mesh_node(kQuad, kQuadIndices, type);
    scenes.push_back(prt::scene::load_scene(g.write("indices_" + std::to_string(type))));
  }
  for (const Scene& s : scenes) {
    REQUIRE(s.triangles.size() == 2);
    CHECK(s.triangles[0] == glm::uvec3(0, 1, 2));
    CHECK(s.triangles[1] == glm::uvec3(0, 2, 3));
    CHECK(s.positions == kQuad);
  }
  MiniGltf flat;
  std::vector<glm::vec3> unrolled;
  for (uint32_t i : kQuadIndices) unrolled.push_back(kQuad[i]);
  flat.add_mesh_node(unrolled, {}, /*index_type=*/0);
  const Scene s = prt::scene::load_scene(flat.write("non_indexed"));
  REQUIRE(s.triangles.size() == 2);
  CHECK(s.triangles[1] == glm::uvec3(3, 4, 5));
  CHECK(s.positions == unrolled);
}

TEST_CASE("glTF errors: missing buffer, NaN position, index out of range, empty scene") {
  {
    MiniGltf g;
    g.add_mesh_node(kTriangle, {0, 1, 2});
    const std::string path = g.write("missing_bin");
    std::filesystem::remove(prt::test::output_path("missing_bin.bin"));
    check_error(error_of(path), path, "missing_bin.bin");
  }
  {
    MiniGltf g;
    g.add_mesh_node({{0, 0, 0}, {NAN, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    const std::string path = g.write("nan_position");
    check_error(error_of(path), path, "vertex 1 ");
  }
  {
    MiniGltf g;
    g.add_mesh_node(kTriangle, {0, 1, 5});
    const std::string path = g.write("index_out_of_range");
    check_error(error_of(path), path, "index 5 out of range");
  }
  {
    MiniGltf g;
    g.add_mesh_node(kTriangle, {0, 1, 2});
    g.doc["scenes"][0]["nodes"] = json::array();
    const std::string path = g.write("empty_scene");
    check_error(error_of(path), path, "no (non-degenerate) triangles");
  }
  {
    const std::string path = prt::test::output_path("garbage.gltf").string();
    std::ofstream(path) << "{ this is not json\n second line";
    check_error(error_of(path), path, "cannot load glTF");
  }
  {
    const std::string path = prt::test::output_path("scene.ply").string();
    std::ofstream(path) << "ply\n";
    check_error(error_of(path), path, "unsupported");
  }
  const std::string absent = prt::test::output_path("does_not_exist.glb").string();
  check_error(error_of(absent), absent, "no such file");
}

TEST_CASE("glTF degenerate triangles are skipped and counted, never producing NaN") {
  MiniGltf g;
  // Triangle 1 repeats an index, triangle 2 is collinear (0, 1 and 4 on the x axis).
  g.add_mesh_node({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}},
                  {0, 1, 2, 0, 0, 3, 0, 1, 4, 0, 2, 3});
  const Scene s = prt::scene::load_scene(g.write("degenerate"));
  CHECK(s.skipped_degenerate_triangles == 2);
  REQUIRE(s.triangles.size() == 2);
  CHECK(s.primitives[0].triangle_count == 2);
  // Vertex 4 is now used by no triangle: it gets the +Y fallback, the others +Z.
  for (std::size_t v = 0; v < 4; ++v)
    CHECK(glm::distance(s.normals[v], glm::vec3(0, 0, 1)) < 1e-6f);
  CHECK(s.normals[4] == glm::vec3(0, 1, 0));
}

TEST_CASE("glTF mirrored node keeps the winding consistent with the transformed normals") {
  for (const bool with_normals : {false, true}) {
    MiniGltf g;
    const std::vector<glm::vec3> normals(3, glm::vec3(0, 0, 1));
    g.add_mesh_node(kTriangle, {0, 1, 2}, kU32, with_normals ? normals : std::vector<glm::vec3>{});
    g.doc["nodes"][0]["scale"] = {-1, 1, 1};
    const Scene s = prt::scene::load_scene(g.write("mirrored"));
    const glm::dvec3 a(s.positions[s.triangles[0].x]), b(s.positions[s.triangles[0].y]),
        c(s.positions[s.triangles[0].z]);
    const glm::dvec3 face = glm::normalize(glm::cross(b - a, c - a));
    // The inverse transpose of diag(-1, 1, 1) maps +Z to +Z; the winding must agree.
    for (const glm::vec3& n : s.normals) CHECK(glm::distance(n, glm::vec3(0, 0, 1)) < 1e-6f);
    CHECK(glm::distance(face, glm::dvec3(0, 0, 1)) < 1e-6);
  }
}

TEST_CASE("glTF materials, albedo override, non-triangle primitives, textures not decoded") {
  MiniGltf g;
  g.add_mesh_node(kTriangle, {0, 1, 2});
  // A second primitive drawn as LINES is skipped.
  json lines = g.doc["meshes"][0]["primitives"][0];
  lines["mode"] = 1;
  g.doc["meshes"][0]["primitives"].push_back(lines);
  g.doc["meshes"][0]["primitives"][0]["material"] = 0;
  g.doc["materials"] = {
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.25, 0.5, 0.75, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}},
      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}};
  // Texture 0's file is missing, texture 1's is not an image at all: neither may stop loading.
  g.doc["textures"] = {{{"source", 0}}, {{"source", 1}}};
  g.doc["images"] = {{{"uri", "not_here.png"}}, {{"uri", "not_an_image.png"}}};
  std::ofstream(prt::test::output_path("not_an_image.png")) << "definitely not a PNG";
  // A second node whose primitive has no material: not the glTF default of white (an albedo of
  // 1, which the baker refuses) but the loader's documented default grey, 0.8.
  g.add_mesh_node(kTriangle, {0, 1, 2});
  g.doc["nodes"][1]["translation"] = {0, 0, 1};
  g.doc["scenes"][0]["nodes"] = {0, 1};
  const std::string path = g.write("materials");
  const Scene s = prt::scene::load_scene(path);
  REQUIRE(s.primitives.size() == 2);
  CHECK(s.triangles.size() == 2);
  CHECK(s.primitives[0].name == "m0/0");
  CHECK(s.primitives[0].albedo == glm::vec3(0.25f, 0.5f, 0.75f));
  CHECK(s.primitives[1].albedo == glm::vec3(0.8f));
  CHECK(s.albedo[0] == glm::vec3(0.25f, 0.5f, 0.75f));
  CHECK(s.albedo[3] == glm::vec3(0.8f));

  prt::scene::LoadOptions options;
  options.albedo_override = glm::vec3(0.1f, 0.2f, 0.3f);
  const Scene overridden = prt::scene::load_scene(path, options);
  for (const auto& p : overridden.primitives) CHECK(p.albedo == glm::vec3(0.1f, 0.2f, 0.3f));
  for (const auto& a : overridden.albedo) CHECK(a == glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST_CASE("glTF perspective camera on a node: eye, -Z view direction, +Y up, yfov") {
  MiniGltf g;
  g.add_mesh_node(kTriangle, {0, 1, 2});
  g.doc["cameras"] = {
      {{"type", "perspective"}, {"name", "cam"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}};
  // Rotated +90 degrees about Y: local -Z turns to -X.
  const double h = std::sqrt(0.5);
  g.doc["nodes"].push_back({{"camera", 0}, {"translation", {5, 1, 2}}, {"rotation", {0, h, 0, h}}});
  g.doc["scenes"][0]["nodes"] = {0, 1};
  const Scene s = prt::scene::load_scene(g.write("camera"));
  REQUIRE(s.cameras.size() == 1);
  const auto& cam = s.cameras[0];
  CHECK(cam.name == "cam");
  CHECK(glm::distance(cam.eye, glm::vec3(5, 1, 2)) < 1e-6f);
  CHECK(glm::distance(glm::normalize(cam.target - cam.eye), glm::vec3(-1, 0, 0)) < 1e-6f);
  CHECK(glm::distance(cam.up, glm::vec3(0, 1, 0)) < 1e-6f);
  CHECK(cam.yfov_radians == Approx(0.6f));
  // glTF gives no target: it is the point of the view axis nearest the centre of the bounds
  // (0.5, 0.5, 0), i.e. (0.5, 1, 2), so a turntable orbits the scene rather than a point a unit
  // in front of the eye (4 units short of the scene).
  CHECK(glm::distance(cam.target, glm::vec3(0.5f, 1.f, 2.f)) < 1e-5f);
}

TEST_CASE("glTF camera looking away from the scene: its target stays ahead of the eye") {
  MiniGltf g;
  g.add_mesh_node(kTriangle, {0, 1, 2});
  g.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}};
  g.doc["nodes"].push_back(
      {{"camera", 0}, {"translation", {0.5, 0.5, 3}}, {"rotation", {0, 1, 0, 0}}});
  g.doc["scenes"][0]["nodes"] = {0, 1};
  const Scene s = prt::scene::load_scene(g.write("camera_away"));
  REQUIRE(s.cameras.size() == 1);
  // Turned 180° about Y: it looks toward +Z, away from the triangle. The target is 1% of the
  // bounds' diagonal (√2) ahead, so the view direction is kept.
  const auto& cam = s.cameras[0];
  CHECK(glm::distance(cam.target, glm::vec3(0.5f, 0.5f, 3.f + 0.01f * std::sqrt(2.f))) < 1e-5f);
}

TEST_CASE("Real glTF: suzanne.gltf (embedded buffer, normals)") {
  const auto path = prt::test::shared_data("meshes/suzanne.gltf");
  PRT_REQUIRE_SHARED_DATA(path);
  const Scene s = prt::scene::load_scene(path.string());
  CHECK(s.positions.size() == 10206);
  CHECK(s.triangles.size() + s.skipped_degenerate_triangles == 15744);
  CHECK(s.computed_normal_vertices == 0);
  for (const glm::vec3& n : s.normals) REQUIRE(glm::length(n) == Approx(1.0).margin(1e-5));
}

TEST_CASE("Real glTF: dutch_ship loads geometry although its textures are missing") {
  const auto path = prt::test::shared_data("meshes/dutch_ship/dutch_ship_medium_1k.gltf");
  PRT_REQUIRE_SHARED_DATA(path);
  const Scene s = prt::scene::load_scene(path.string());
  CHECK(s.primitives.size() >= 3);
  CHECK(s.positions.size() == 64496);
  CHECK(s.triangles.size() + s.skipped_degenerate_triangles == 69162);
  for (const glm::vec3& p : s.positions) REQUIRE(std::isfinite(p.x + p.y + p.z));
  for (const glm::vec3& n : s.normals) REQUIRE(glm::length(n) == Approx(1.0).margin(1e-5));
}

// ---- base-colour textures ----

namespace {

// sRGB decoding written out from IEC 61966-2-1, independently of scene/texture.h.
double linear_of_byte(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The 2×2 test texture, texel (i, j) with i the column and j the row (row 0 at the top).
const int kTexel[2][2][3] = {{{200, 40, 20}, {30, 180, 60}}, {{90, 90, 220}, {128, 128, 128}}};

glm::dvec3 linear_texel(int i, int j) {
  const int* b = kTexel[j][i];
  return {linear_of_byte(b[0]), linear_of_byte(b[1]), linear_of_byte(b[2])};
}

// The texture's samples, row by row.
std::vector<unsigned char> texture_samples() {
  std::vector<unsigned char> samples;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      for (int c = 0; c < 3; ++c) samples.push_back(static_cast<unsigned char>(kTexel[j][i][c]));
  return samples;
}

std::vector<unsigned char> texture_png() {
  return prt::test::encode_png(2, 2, 3, texture_samples());
}

using prt::test::base64;

// A unit quad in z = 0 whose TEXCOORD_1 equals (x, y) and whose TEXCOORD_0 is a decoy (0.9,
// 0.9) everywhere; its material (0) has baseColorFactor (0.5, 1, 1) and baseColorTexture
// {index 0, texCoord 1}. The caller adds textures, samplers and images.
MiniGltf textured_quad() {
  MiniGltf g;
  g.add_mesh_node(kQuad, kQuadIndices, kU32);
  json& primitive = g.doc["meshes"][0]["primitives"][0];
  primitive["attributes"]["TEXCOORD_0"] = g.add_vec2(std::vector<glm::vec2>(4, glm::vec2(0.9f)));
  primitive["attributes"]["TEXCOORD_1"] = g.add_vec2({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  primitive["material"] = 0;
  g.doc["materials"] = {{{"pbrMetallicRoughness",
                          {{"baseColorFactor", {0.5, 1.0, 1.0, 1.0}},
                           {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}};
  g.doc["images"] = json::array();
  return g;
}

const glm::dvec3 kFactor(0.5, 1.0, 1.0);

// The albedo at point (x, y) of the quad (whose UV is (x, y)), through Scene::albedo_at.
glm::vec3 albedo_at_uv(const Scene& s, float x, float y) {
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const glm::uvec3 tri = s.triangles[t];
    const glm::vec2 a = s.texcoords[tri.x], b = s.texcoords[tri.y], c = s.texcoords[tri.z];
    // Solve (x, y) = a + u (b − a) + v (c − a).
    const glm::vec2 e1 = b - a, e2 = c - a, r = glm::vec2(x, y) - a;
    const float det = e1.x * e2.y - e1.y * e2.x;
    const float u = (r.x * e2.y - r.y * e2.x) / det, v = (e1.x * r.y - e1.y * r.x) / det;
    if (u >= -1e-6f && v >= -1e-6f && u + v <= 1.f + 1e-6f) return s.albedo_at(t, u, v);
  }
  FAIL("point outside the quad");
  return {};
}

void check_rgb(const glm::vec3& got, const glm::dvec3& want, double tolerance = 1e-6) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y
               << ", " << want.z << ")");
  for (int c = 0; c < 3; ++c) CHECK(std::fabs(got[c] - want[c]) <= tolerance);
}

}  // namespace

TEST_CASE("glTF baseColorTexture: PNG file beside the .gltf, texCoord 1, factor, CLAMP vs REPEAT") {
  prt::test::write_png(prt::test::output_path("tex 2x2.png").string(), 2, 2, 3, texture_samples());
  for (const bool clamp : {true, false}) {
    MiniGltf g = textured_quad();
    g.doc["images"] = {{{"uri", "tex%202x2.png"}}};  // percent-encoded space
    g.doc["textures"] = {{{"source", 0}}};
    if (clamp) {
      g.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33071}}};
      g.doc["textures"][0]["sampler"] = 0;
    }
    const Scene s = prt::scene::load_scene(g.write(clamp ? "tex_file_clamp" : "tex_file_repeat"));
    INFO((clamp ? "CLAMP_TO_EDGE" : "REPEAT (no sampler)"));
    REQUIRE(s.primitives.size() == 1);
    REQUIRE(s.primitives[0].base_color_texture.has_value());
    CHECK(s.primitives[0].base_color_texture->texcoord == 1);
    REQUIRE(s.texcoords.size() == 4);
    CHECK(s.texcoords[2] == glm::vec2(1, 1));  // TEXCOORD_1, not the decoy TEXCOORD_0
    // Texel centres, anywhere on the surface: factor × the linearised texel.
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        check_rgb(albedo_at_uv(s, 0.25f + 0.5f * static_cast<float>(i),
                               0.25f + 0.5f * static_cast<float>(j)),
                  kFactor * linear_texel(i, j));
    // The corner vertex (0, 0): clamping reads texel (0, 0); repeating blends all four texels.
    const glm::dvec3 mean =
        0.25 * (linear_texel(0, 0) + linear_texel(1, 0) + linear_texel(0, 1) + linear_texel(1, 1));
    check_rgb(s.albedo[0], kFactor * (clamp ? linear_texel(0, 0) : mean));
    // The primitive's flat albedo is factor × the texture's mean.
    check_rgb(s.primitives[0].albedo, kFactor * mean);
  }
}

TEST_CASE("glTF baseColorTexture: a data: URI and a GLB buffer view read like the file") {
  const std::vector<unsigned char> png = texture_png();
  MiniGltf by_uri = textured_quad();
  by_uri.doc["images"] = {{{"uri", "data:image/png;base64," + base64(png)}}};
  by_uri.doc["textures"] = {{{"source", 0}}};
  MiniGltf by_view = textured_quad();
  by_view.add_image_in_buffer(png, "image/png");
  by_view.doc["textures"] = {{{"source", 0}}};
  const Scene a = prt::scene::load_scene(by_uri.write("tex_data_uri"));
  const Scene b = prt::scene::load_scene(by_view.write_glb("tex_buffer_view"));
  for (const Scene* s : {&a, &b}) {
    REQUIRE(s->primitives[0].base_color_texture.has_value());
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        check_rgb(albedo_at_uv(*s, 0.25f + 0.5f * static_cast<float>(i),
                               0.25f + 0.5f * static_cast<float>(j)),
                  kFactor * linear_texel(i, j));
  }
  CHECK(a.albedo == b.albedo);
}

TEST_CASE("glTF baseColorTexture: JPEG decodes through OpenImageIO as sRGB") {
  // A uniform 16×16 JPEG of value 150: baseline JPEG reproduces a flat block to ±1.
  const std::string jpeg = prt::test::output_path("uniform150.jpg").string();
  {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(jpeg);
    REQUIRE(out);
    OIIO::ImageSpec spec(16, 16, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("CompressionQuality", 95);
    REQUIRE(out->open(jpeg, spec));
    const std::vector<unsigned char> pixels(16 * 16 * 3, 150);
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    REQUIRE(out->close());
  }
  MiniGltf g = textured_quad();
  g.doc["images"] = {{{"uri", "uniform150.jpg"}}};
  g.doc["textures"] = {{{"source", 0}}};
  const Scene s = prt::scene::load_scene(g.write("tex_jpeg"));
  REQUIRE(s.primitives[0].base_color_texture.has_value());
  const double want = linear_of_byte(150), step = linear_of_byte(151) - want;
  for (const glm::vec3& a : s.albedo) check_rgb(a, kFactor * want, step);
}

TEST_CASE("glTF baseColorTexture that cannot be used: a warning, and the factor instead") {
  SECTION("missing file") {
    MiniGltf g = textured_quad();
    g.doc["images"] = {{{"uri", "no_such_texture.png"}}};
    g.doc["textures"] = {{{"source", 0}}};
    const Scene s = prt::scene::load_scene(g.write("tex_missing"));
    CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
    // The factor is not the default white, so it is used as it is.
    for (const glm::vec3& a : s.albedo) check_rgb(a, kFactor);
  }
  SECTION("not an image, in a buffer view") {
    MiniGltf g = textured_quad();
    g.add_image_in_buffer({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'},
                          "image/png");
    g.doc["textures"] = {{{"source", 0}}};
    const Scene s = prt::scene::load_scene(g.write_glb("tex_garbage"));
    CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
    for (const glm::vec3& a : s.albedo) check_rgb(a, glm::dvec3(0.5, 1, 1));
  }
  SECTION("a truncated PNG") {
    std::vector<unsigned char> png = texture_png();
    png.resize(png.size() / 2);
    MiniGltf g = textured_quad();
    g.add_image_in_buffer(png, "image/png");
    g.doc["textures"] = {{{"source", 0}}};
    const Scene s = prt::scene::load_scene(g.write_glb("tex_truncated"));
    CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
  }
  SECTION("no TEXCOORD_n for the texture's texCoord") {
    MiniGltf g = textured_quad();
    g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 3;
    g.add_image_in_buffer(texture_png(), "image/png");
    g.doc["textures"] = {{{"source", 0}}};
    const Scene s = prt::scene::load_scene(g.write_glb("tex_no_texcoord"));
    CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
    CHECK(s.texcoords.empty());
  }
}

TEST_CASE("glTF baseColorTexture: --albedo override drops textures") {
  MiniGltf g = textured_quad();
  g.add_image_in_buffer(texture_png(), "image/png");
  g.doc["textures"] = {{{"source", 0}}};
  prt::scene::LoadOptions options;
  options.albedo_override = glm::vec3(0.25f);
  const Scene s = prt::scene::load_scene(g.write_glb("tex_override"), options);
  CHECK_FALSE(s.primitives[0].base_color_texture.has_value());
  CHECK_FALSE(s.textured());
  for (const glm::vec3& a : s.albedo) CHECK(a == glm::vec3(0.25f));
}
