// tests/scene/test_scene_fuzz_regressions.cpp — regression tests for bugs the fuzzers (fuzz/)
// found in the scene loaders. Each input is the minimal form of the finding.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene_loader.h"
#include "support/test_data.h"

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = prt::test::output_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

}  // namespace

TEST_CASE("OBJ normals that are not unit length are normalised (fuzz_scene_obj)", "[regression]") {
  const std::string path = write_file("regression_vn_not_unit.obj",
                                      "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvn 5 1 0\nvn 0 0 0\n"
                                      "f 1//1 4//1 3//1\nf 1//2 3//2 2//2\n");
  const prt::scene::Scene scene = prt::scene::load_scene(path);
  REQUIRE(scene.vertex_count() > 0);
  for (const glm::vec3& n : scene.normals) {
    // Unit to float rounding (scene.h promises unit normals).
    CHECK(std::fabs(glm::length(n) - 1.0f) < 1e-5f);
  }
  // (5, 1, 0) normalised: the direction is kept.
  CHECK(scene.normals[0].x == Approx(5.0 / std::sqrt(26.0)).epsilon(1e-6));
}

TEST_CASE(
    "A glTF accessor index out of range is a SceneError, not std::out_of_range "
    "(fuzz_scene_gltf)",
    "[regression]") {
  const std::string path =
      write_file("regression_bad_accessor.gltf",
                 R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]})");
  try {
    (void)prt::scene::load_scene(path);
    FAIL("the file was accepted");
  } catch (const prt::scene::SceneError& e) {
    const std::string m = e.what();
    CHECK(m.rfind(path + ": ", 0) == 0);
    CHECK(m.find('\n') == std::string::npos);
  }
}
