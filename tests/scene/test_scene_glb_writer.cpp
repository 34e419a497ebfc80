// GLB writing (scene/glb_writer.h): round trip through load_scene and tinygltf, atomicity.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <tiny_gltf.h>
#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"
#include "support/test_data.h"

using prt::scene::Scene;

namespace {

Scene make_test_scene() {
  Scene s =
      prt::scene::make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 4, 4, glm::vec3(0.7f), "floor");
  prt::scene::append_scene(s, prt::scene::make_uv_sphere({0, 0.5f, 0}, 0.5f, 6, 12, false,
                                                         glm::vec3(0.8f, 0.2f, 0.1f), "ball"));
  prt::scene::SceneCamera camera;
  camera.name = "view";
  camera.eye = {2, 1.5f, 3};
  camera.target = {0, 0.3f, 0};
  camera.yfov_radians = 0.7f;
  s.cameras.push_back(camera);
  return s;
}

// COLOR_0 of every mesh, in node order, read with tinygltf directly.
std::vector<glm::vec3> read_colors(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  REQUIRE(loader.LoadBinaryFromFile(&model, &error, &warning, path));
  std::vector<glm::vec3> colors;
  for (const tinygltf::Mesh& mesh : model.meshes) {
    const auto it = mesh.primitives.at(0).attributes.find("COLOR_0");
    REQUIRE(it != mesh.primitives.at(0).attributes.end());
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(it->second));
    CHECK(accessor.type == TINYGLTF_TYPE_VEC3);
    CHECK(accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
    const tinygltf::BufferView& view =
        model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const unsigned char* data =
        model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data() + view.byteOffset +
        accessor.byteOffset;
    const std::size_t stride = view.byteStride ? view.byteStride : 12;
    for (std::size_t i = 0; i < accessor.count; ++i) {
      glm::vec3 c;
      std::memcpy(&c, data + i * stride, 12);
      colors.push_back(c);
    }
  }
  return colors;
}

}  // namespace

TEST_CASE("write_glb then load_scene gives back geometry, albedo and the camera") {
  const Scene s = make_test_scene();
  const std::string path = prt::test::output_path("round_trip.glb").string();
  prt::scene::write_glb(path, s);

  // A GLB header: magic "glTF", version 2, total length = file size.
  std::ifstream in(path, std::ios::binary);
  uint32_t header[3];
  in.read(reinterpret_cast<char*>(header), sizeof header);
  CHECK(std::memcmp(header, "glTF", 4) == 0);
  CHECK(header[1] == 2);
  CHECK(header[2] == std::filesystem::file_size(path));

  const Scene back = prt::scene::load_scene(path);
  CHECK(back.positions == s.positions);  // float32 written and read: bit-exact
  CHECK(back.normals == s.normals);
  CHECK(back.triangles == s.triangles);
  CHECK(back.albedo == s.albedo);
  CHECK(back.computed_normal_vertices == 0);
  CHECK(back.skipped_degenerate_triangles == 0);
  REQUIRE(back.primitives.size() == s.primitives.size());
  for (std::size_t p = 0; p < s.primitives.size(); ++p) {
    CHECK(back.primitives[p].name == s.primitives[p].name + "/0");
    CHECK(back.primitives[p].first_vertex == s.primitives[p].first_vertex);
    CHECK(back.primitives[p].triangle_count == s.primitives[p].triangle_count);
  }
  REQUIRE(back.cameras.size() == 1);
  const auto& cam = back.cameras[0];
  const auto& want = s.cameras[0];
  CHECK(cam.name == "view");
  CHECK(glm::distance(cam.eye, want.eye) < 1e-6f);
  // The node rotation reproduces the view direction, and an up vector orthogonal to it in the
  // plane of (direction, requested up); 1e-5 allows the quaternion's float round trip.
  const glm::vec3 forward = glm::normalize(want.target - want.eye);
  CHECK(glm::distance(glm::normalize(cam.target - cam.eye), forward) < 1e-5f);
  CHECK(glm::dot(cam.up, forward) == Approx(0.0).margin(1e-5));
  CHECK(glm::dot(cam.up, glm::cross(forward, want.up)) == Approx(0.0).margin(1e-5));
  CHECK(cam.up.y > 0.f);
  CHECK(cam.yfov_radians == Approx(0.7f));

  for (const auto& entry : std::filesystem::directory_iterator(prt::test::output_path(""))) {
    CHECK(entry.path().filename().string().find("round_trip.glb.tmp-") == std::string::npos);
  }
}

TEST_CASE("write_glb with vertex colours: COLOR_0 as given, on unlit white materials") {
  // Baked colours already hold the lighting and the albedo: a viewer must show them as they are,
  // so every material is KHR_materials_unlit (declared in extensionsUsed, not required: a viewer
  // without it falls back to a lit white material) with a white base colour.
  const Scene s = make_test_scene();
  std::vector<glm::vec3> colors;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    colors.emplace_back(static_cast<float>(v) * 0.01f, 0.5f, 2.5f);  // linear, may exceed 1
  }
  const std::string path = prt::test::output_path("baked_colors.glb").string();
  prt::scene::write_glb(path, s, &colors);
  CHECK(read_colors(path) == colors);

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  REQUIRE(loader.LoadBinaryFromFile(&model, &error, &warning, path));
  CHECK(model.extensionsUsed == std::vector<std::string>{"KHR_materials_unlit"});
  CHECK(model.extensionsRequired.empty());
  REQUIRE(model.materials.size() == s.primitives.size());
  for (const tinygltf::Material& material : model.materials) {
    CHECK(material.extensions.count("KHR_materials_unlit") == 1);
    CHECK(material.pbrMetallicRoughness.baseColorFactor == std::vector<double>{1, 1, 1, 1});
  }
  // Without colours the materials stay lit, with the albedo, and no extension is declared.
  const std::string plain = prt::test::output_path("plain_materials.glb").string();
  prt::scene::write_glb(plain, s);
  tinygltf::Model plain_model;
  REQUIRE(loader.LoadBinaryFromFile(&plain_model, &error, &warning, plain));
  CHECK(plain_model.extensionsUsed.empty());
  CHECK(plain_model.materials.at(1).extensions.empty());
  CHECK(plain_model.materials.at(1).pbrMetallicRoughness.baseColorFactor.at(0) == Approx(0.8));
}

TEST_CASE("write_glb fails with one line and leaves nothing behind") {
  const Scene s = make_test_scene();
  const std::string path = prt::test::output_path("no_such_dir/out.glb").string();
  try {
    prt::scene::write_glb(path, s);
    FAIL("write_glb into a missing directory did not throw");
  } catch (const prt::scene::SceneError& e) {
    const std::string message = e.what();
    CHECK(message.rfind(path + ": ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(prt::test::output_path("no_such_dir")));

  const std::string wrong_colors = prt::test::output_path("wrong_colors.glb").string();
  const std::vector<glm::vec3> too_few(3, glm::vec3(1.f));
  CHECK_THROWS_AS(prt::scene::write_glb(wrong_colors, s, &too_few), prt::scene::SceneError);
  CHECK_FALSE(std::filesystem::exists(wrong_colors));
}

TEST_CASE("data/demo.glb is the current make_demo_scene") {
  const auto path = prt::test::project_data("demo.glb");
  REQUIRE(std::filesystem::exists(path));
  CHECK(std::filesystem::file_size(path) < 1500000);
  const Scene demo = prt::scene::make_demo_scene();
  const Scene loaded = prt::scene::load_scene(path.string());
  CHECK(loaded.positions == demo.positions);
  CHECK(loaded.triangles == demo.triangles);
  CHECK(loaded.albedo == demo.albedo);
  CHECK(loaded.cameras.size() == 1);
}

// Emission: glTF's emissiveFactor is limited to [0, 1], so a brighter colour is written as the
// colour over its largest channel times KHR_materials_emissive_strength; the loader's product
// gives it back (float rounding: 1e-6 relative).
TEST_CASE("write_glb keeps emission, through KHR_materials_emissive_strength above 1") {
  Scene s = make_test_scene();
  s.primitives[0].emission = glm::vec3(0.5f, 0.25f, 0.f);  // within [0, 1]: the factor alone
  s.primitives[1].emission = glm::vec3(12.f, 9.36f, 6.f);
  const std::string path = prt::test::output_path("emission.glb").string();
  prt::scene::write_glb(path, s);
  const Scene loaded = prt::scene::load_scene(path);
  REQUIRE(loaded.primitives.size() == 2);
  for (int p = 0; p < 2; ++p)
    for (int c = 0; c < 3; ++c)
      CHECK(loaded.primitives[p].emission[c] ==
            Approx(s.primitives[p].emission[c]).epsilon(1e-6).margin(1e-7));
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  REQUIRE(loader.LoadBinaryFromFile(&model, &error, &warning, path));
  CHECK(model.materials.at(0).extensions.count("KHR_materials_emissive_strength") == 0);
  CHECK(model.materials.at(1).extensions.count("KHR_materials_emissive_strength") == 1);
  CHECK(model.materials.at(1).emissiveFactor.at(0) == 1.0);
  CHECK(std::count(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                   "KHR_materials_emissive_strength") == 1);
}
