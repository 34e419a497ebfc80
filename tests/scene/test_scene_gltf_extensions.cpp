// glTF extensions (scene/src/gltf_extensions.h): a file that requires an extension prt cannot
// read is refused with the extension named; extensions that are only used, or that change
// nothing prt reads, are fine. The files are written here, by hand (independent of prt's writer).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "gltf_test_files.h"
#include "scene/scene_loader.h"
#include "support/test_data.h"

using gltf_test::base64;
using gltf_test::write_glb;
using gltf_test::write_gltf;
using nlohmann::json;

namespace {

// One triangle (float positions, u16 indices) in an embedded buffer: a file prt reads.
json triangle_document() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t indices[4] = {0, 1, 2, 0};  // padded to 4 bytes
  std::vector<unsigned char> bin(sizeof positions + sizeof indices);
  std::memcpy(bin.data(), positions, sizeof positions);
  std::memcpy(bin.data() + sizeof positions, indices, sizeof indices);
  return {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"meshes",
       json::array(
           {{{"primitives", json::array({{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}})}}})},
      {"accessors",
       json::array(
           {{{"bufferView", 0},
             {"componentType", 5126},
             {"count", 3},
             {"type", "VEC3"},
             {"min", {0, 0, 0}},
             {"max", {1, 1, 0}}},
            {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}})},
      {"bufferViews", json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                                   {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}})},
      {"buffers", json::array({{{"byteLength", bin.size()},
                                {"uri", "data:application/octet-stream;base64," + base64(bin)}}})}};
}

// A Draco-compressed primitive as encoders write it: the accessors have no bufferView (the
// data lives in the compressed bufferView named by the primitive's extension).
json draco_document() {
  json doc = triangle_document();
  doc["accessors"][0].erase("bufferView");
  doc["accessors"][1].erase("bufferView");
  doc["meshes"][0]["primitives"][0]["extensions"] = {
      {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}};
  doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return doc;
}

std::string load_error(const std::string& path) {
  try {
    prt::scene::load_scene(path);
  } catch (const prt::scene::SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("glTF requiring Draco is refused, naming the extension (.gltf and .glb)") {
  // Without the check tinygltf stops at "accessor[1] invalid bufferView", which names no cause.
  for (const std::string& path :
       {write_gltf("draco.gltf", draco_document()), write_glb("draco.glb", draco_document())}) {
    CHECK(load_error(path) ==
          path + ": requires glTF extension KHR_draco_mesh_compression, which prt cannot read");
  }
}

TEST_CASE("glTF requiring meshopt, or several unreadable extensions, is refused") {
  json doc = triangle_document();  // readable data: only the requirement refuses it
  doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  const std::string meshopt = write_gltf("meshopt.gltf", doc);
  CHECK(load_error(meshopt) ==
        meshopt + ": requires glTF extension EXT_meshopt_compression, which prt cannot read");

  doc["extensionsRequired"] = {"KHR_materials_emissive_strength", "KHR_mesh_quantization",
                               "EXT_meshopt_compression"};
  const std::string several = write_gltf("several.gltf", doc);
  CHECK(load_error(several) == several +
                                   ": requires glTF extensions KHR_mesh_quantization, "
                                   "EXT_meshopt_compression, which prt cannot read");
}

TEST_CASE("glTF extensions that are only used, or change nothing prt reads, are fine") {
  json doc = triangle_document();
  doc["extensionsUsed"] = {"KHR_draco_mesh_compression", "KHR_materials_unlit"};
  const std::string used = write_gltf("draco_used_only.gltf", doc);
  CHECK(load_error(used).empty());
  CHECK(prt::scene::load_scene(used).triangles.size() == 1);

  doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_lights_punctual"};
  doc["extensionsRequired"] = {"KHR_materials_emissive_strength", "KHR_lights_punctual"};
  const std::string ignorable = write_glb("ignorable_required.glb", doc);
  CHECK(load_error(ignorable).empty());
  CHECK(prt::scene::load_scene(ignorable).vertex_count() == 3);
}
