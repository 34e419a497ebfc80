// Camera framing and parsing (relight/camera.h).
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "relight/camera.h"
#include "scene/scene.h"
#include "sh/constants.h"

using prt::relight::Camera;
using prt::sh::kPi;

namespace {

prt::scene::Scene make_two_point_scene(glm::vec3 a, glm::vec3 b) {
  prt::scene::Scene scene;
  scene.positions = {a, b};
  scene.normals = {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};
  scene.albedo = {glm::vec3(0.5f), glm::vec3(0.5f)};
  return scene;
}

}  // namespace

TEST_CASE("frame_bounds keeps every bounding-box corner inside the view, seen from above") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> centre(-100.f, 100.f), size(1e-3f, 50.f);
  const float aspects[] = {0.4f, 1.f, 16.f / 9.f, 3.f};
  for (int trial = 0; trial < 200; ++trial) {
    const glm::vec3 lo(centre(rng), centre(rng), centre(rng));
    const glm::vec3 hi = lo + glm::vec3(size(rng), size(rng), size(rng));
    const float aspect = aspects[trial % 4];
    const Camera camera = prt::relight::frame_bounds(lo, hi, aspect);
    const auto basis = prt::relight::make_camera_basis(camera, aspect);
    CHECK(camera.eye.y > 0.5f * (lo.y + hi.y));  // a view from above
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                        (corner & 4) ? hi.z : lo.z);
      glm::vec2 ndc;
      REQUIRE(prt::relight::project_to_ndc(basis, camera.eye, p, &ndc));
      // The fit is to the bounding sphere with a 5% margin, so corners are strictly inside.
      CHECK(std::abs(ndc.x) < 1.f);
      CHECK(std::abs(ndc.y) < 1.f);
    }
  }
}

TEST_CASE("frame_bounds does not waste the view: the bounding sphere nearly touches its edge") {
  // A cube seen at aspect 1: the sphere's silhouette is a circle that, by construction, spans
  // 1/1.05 of the half-height, so the corner farthest out must reach beyond half of it.
  const Camera camera = prt::relight::frame_bounds(glm::vec3(-1.f), glm::vec3(1.f), 1.f);
  const auto basis = prt::relight::make_camera_basis(camera, 1.f);
  float reach = 0.f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? 1.f : -1.f, (corner & 2) ? 1.f : -1.f,
                      (corner & 4) ? 1.f : -1.f);
    glm::vec2 ndc;
    REQUIRE(prt::relight::project_to_ndc(basis, camera.eye, p, &ndc));
    reach = std::max(reach, std::max(std::abs(ndc.x), std::abs(ndc.y)));
  }
  CHECK(reach > 0.5f);
  CHECK(reach < 1.f);
}

TEST_CASE("ray_direction and project_to_ndc are inverse to each other") {
  Camera camera;
  camera.eye = glm::vec3(1, 2, 3);
  camera.target = glm::vec3(-2, 0.5f, -1);
  camera.up = glm::vec3(0, 1, 0);
  camera.yfov_radians = 0.9f;
  const auto basis = prt::relight::make_camera_basis(camera, 1.5f);
  for (float x = -1.f; x <= 1.f; x += 0.25f)
    for (float y = -1.f; y <= 1.f; y += 0.25f) {
      const glm::vec3 d = prt::relight::ray_direction(basis, x, y);
      glm::vec2 ndc;
      REQUIRE(prt::relight::project_to_ndc(basis, camera.eye, camera.eye + 7.f * d, &ndc));
      CHECK(ndc.x == Approx(x).margin(1e-5));  // float round-off of a few operations
      CHECK(ndc.y == Approx(y).margin(1e-5));
    }
  // The centre ray looks at the target; ndc y up is world up here.
  const glm::vec3 centre = prt::relight::ray_direction(basis, 0.f, 0.f);
  CHECK(glm::length(centre - glm::normalize(camera.target - camera.eye)) < 1e-6f);
  CHECK(prt::relight::ray_direction(basis, 0.f, 1.f).y > centre.y);
}

TEST_CASE("parse_camera: names, explicit numbers and clear errors") {
  prt::scene::Scene scene = make_two_point_scene(glm::vec3(-1.f), glm::vec3(2.f));
  scene.source_path = "scene.glb";

  // auto is not parsed here: the camera rule (relight/auto_camera.h choose_camera) resolves it,
  // so no command can reach a second automatic camera.
  CHECK_THROWS_AS(prt::relight::parse_camera("auto", scene, 1.5f), std::invalid_argument);
  CHECK_THROWS_AS(prt::relight::parse_camera("", scene, 1.5f), std::invalid_argument);

  // NAME picks by name.
  prt::scene::SceneCamera first, second;
  first.eye = glm::vec3(0, 1, 5);
  first.name = "front";
  second.eye = glm::vec3(5, 1, 0);
  second.name = "side";
  second.yfov_radians = 0.5f;
  scene.cameras = {first, second};
  const Camera side = prt::relight::parse_camera("side", scene, 1.f);
  CHECK(side.eye == second.eye);
  CHECK(side.yfov_radians == 0.5f);

  const Camera manual = prt::relight::parse_camera("1,2,3,0,0,0,0,1,0,90", scene, 1.f);
  CHECK(manual.eye == glm::vec3(1, 2, 3));
  CHECK(manual.target == glm::vec3(0.f));
  CHECK(manual.yfov_radians == Approx(kPi / 2).epsilon(1e-6));

  auto message_of = [&](const std::string& spec) {
    try {
      prt::relight::parse_camera(spec, scene, 1.f);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message_of("top"), Catch::Contains("scene.glb") && Catch::Contains("'top'") &&
                                    Catch::Contains("'front'"));
  CHECK_THAT(message_of("1,2,3"), Catch::Contains("expected 10 numbers"));
  CHECK_THAT(message_of("1,2,3,0,0,0,0,1,0,abc"), Catch::Contains("'abc' is not a number"));
  CHECK_THAT(message_of("1,1,1,1,1,1,0,1,0,60"), Catch::Contains("coincide"));
  CHECK_THAT(message_of("0,5,0,0,0,0,0,1,0,60"), Catch::Contains("parallel"));
  CHECK_THAT(message_of("0,0,5,0,0,0,0,1,0,180"), Catch::Contains("field of view"));
  for (const char* spec : {"top", "1,2,3"})
    CHECK(message_of(spec).find('\n') == std::string::npos);  // one line
}
