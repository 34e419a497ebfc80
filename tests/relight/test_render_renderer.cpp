// The preview renderer (relight/renderer.h): barycentric shading of hits, environment on misses.
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "relight/renderer.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"
#include "sh/constants.h"
#include "sh/env_map.h"

using prt::sh::kPi;

namespace {

// One large triangle in the plane z = 0, facing +z, vertices with distinct radiance.
prt::scene::Scene make_triangle_scene() {
  prt::scene::Scene scene;
  scene.positions = {glm::vec3(-2.f, -1.5f, 0.f), glm::vec3(2.5f, -1.f, 0.f),
                     glm::vec3(0.3f, 2.f, 0.f)};
  scene.normals.assign(3, glm::vec3(0, 0, 1));
  scene.albedo.assign(3, glm::vec3(0.5f));
  scene.triangles = {glm::uvec3(0, 1, 2)};
  prt::scene::ScenePrimitive primitive;
  primitive.name = "triangle";
  primitive.vertex_count = 3;
  primitive.triangle_count = 1;
  scene.primitives = {primitive};
  return scene;
}

// A smooth analytic radiance: f(d) = (1.5 + d.x, 1.5 + d.y, 1.5 + d.z) · (1, 2, 3).
glm::dvec3 analytic_sky(const glm::dvec3& d) {
  return glm::dvec3(1.5 + d.x, 2.0 * (1.5 + d.y), 3.0 * (1.5 + d.z));
}

prt::sh::EnvMap make_analytic_latlong(int width, int height) {
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = width;
  env.height = height;
  env.rgb.resize(3 * static_cast<std::size_t>(width) * height);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      // Lat-long (README.md, "Conventions"): u = 0.5 + atan2(z, x)/2π, v = acos(y)/π (written out
      // here on purpose).
      const double u = (col + 0.5) / width, v = (row + 0.5) / height;
      const double phi = 2 * kPi * (u - 0.5), theta = kPi * v;
      const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
      const glm::dvec3 f = analytic_sky(d);
      for (int c = 0; c < 3; ++c)
        env.rgb[3 * (static_cast<std::size_t>(row) * width + col) + c] = static_cast<float>(f[c]);
    }
  return env;
}

}  // namespace

TEST_CASE("renderer: hits get the barycentric mix of vertex radiance, misses the rotated sky") {
  const prt::scene::Scene scene = make_triangle_scene();
  const prt::scene::RayCaster caster(scene);
  const std::vector<float> radiance = {1.f, 2.f, 3.f, 10.f, 0.f, 5.f, 0.5f, 7.f, 20.f};
  const prt::sh::EnvMap env = make_analytic_latlong(512, 256);
  // Yaw 40°, pitch 25° (a rotation about +Y then +X), written out: M = Ry·Rx.
  const double cy = std::cos(40 * kPi / 180), sy = std::sin(40 * kPi / 180);
  const double cx = std::cos(25 * kPi / 180), sx = std::sin(25 * kPi / 180);
  const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);  // glm is column-major
  const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);
  const glm::dmat3 m = ry * rx;
  std::array<double, 9> rotation{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation[3 * i + j] = m[j][i];  // row-major

  prt::relight::Camera camera;
  camera.eye = glm::vec3(0.f, 0.f, 4.f);
  camera.target = glm::vec3(0.f);
  camera.up = glm::vec3(0, 1, 0);
  camera.yfov_radians = static_cast<float>(70 * kPi / 180);
  prt::relight::RenderOptions options;
  options.width = 80;
  options.height = 60;
  options.samples_per_axis = 1;  // pixel centres only: the mapping is not linear in screen space
  const prt::relight::Image image =
      prt::relight::render(scene, caster, radiance, &env, rotation, camera, options);
  REQUIRE(image.width == 80);
  REQUIRE(image.rgb.size() == 3u * 80 * 60);

  // Independent pinhole model: forward −z, right +x, up +y for this camera.
  const double t = std::tan(35 * kPi / 180), aspect = 80.0 / 60.0;
  const glm::dvec3 p0 = scene.positions[0], p1 = scene.positions[1], p2 = scene.positions[2];
  auto cross_z = [](glm::dvec3 a, glm::dvec3 b) { return a.x * b.y - a.y * b.x; };
  const double area = cross_z(p1 - p0, p2 - p0);
  int hits = 0, misses = 0;
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col) {
      const double x = 2 * (col + 0.5) / image.width - 1, y = 1 - 2 * (row + 0.5) / image.height;
      const glm::dvec3 d = glm::normalize(glm::dvec3(x * t * aspect, y * t, -1));
      const glm::dvec3 p = glm::dvec3(camera.eye) + (4.0 / -d.z) * d;  // on z = 0
      const double b0 = cross_z(p1 - p, p2 - p) / area, b1 = cross_z(p2 - p, p0 - p) / area;
      const double b2 = 1 - b0 - b1;
      const float* pixel = &image.rgb[3 * (static_cast<std::size_t>(row) * image.width + col)];
      const double margin = 0.01;  // stay away from the edges, where float rays may go either way
      if (b0 > margin && b1 > margin && b2 > margin) {
        ++hits;
        for (int c = 0; c < 3; ++c) {
          const double expected = b0 * radiance[c] + b1 * radiance[3 + c] + b2 * radiance[6 + c];
          // Float ray/triangle arithmetic: barycentrics good to ~1e-6, values ≤ 20.
          CHECK(pixel[c] == Approx(expected).margin(1e-4));
        }
      } else if (b0 < -margin || b1 < -margin || b2 < -margin) {
        ++misses;
        const glm::dvec3 source = glm::transpose(m) * d;  // g(d) = f(Mᵀd)
        const glm::dvec3 expected = analytic_sky(source);
        for (int c = 0; c < 3; ++c) {
          // Bilinear interpolation of a function with |second derivative| ≤ 3 per radian² over
          // texels of π/256 rad: error ≤ 3·(2·(π/256)²)/8 ≈ 1.1e-4; plus float storage.
          CHECK(pixel[c] == Approx(expected[c]).margin(3e-4));
        }
      }
    }
  CHECK(hits > 500);
  CHECK(misses > 500);

  // Without a background, misses are black.
  const prt::relight::Image dark = prt::relight::render(
      scene, caster, radiance, nullptr, prt::relight::kIdentityRotation, camera, options);
  CHECK(dark.rgb[0] == 0.f);
}

TEST_CASE("renderer: stratified sub-samples average a pixel, the output is deterministic") {
  const prt::scene::Scene scene = make_triangle_scene();
  const prt::scene::RayCaster caster(scene);
  const std::vector<float> radiance = {1.f, 1.f, 1.f, 1.f, 1.f, 1.f, 1.f, 1.f, 1.f};
  prt::relight::Camera camera;
  camera.eye = glm::vec3(0.f, 0.f, 4.f);
  prt::relight::RenderOptions options;
  options.width = 40;
  options.height = 30;
  options.samples_per_axis = 4;
  const auto a = prt::relight::render(scene, caster, radiance, nullptr,
                                      prt::relight::kIdentityRotation, camera, options);
  const auto b = prt::relight::render(scene, caster, radiance, nullptr,
                                      prt::relight::kIdentityRotation, camera, options);
  CHECK(a.rgb == b.rgb);
  // Radiance 1 on the triangle, 0 outside: edge pixels are partially covered, in steps of 1/16.
  int partial = 0;
  for (float value : a.rgb) {
    CHECK(value >= 0.f);
    CHECK(value <= 1.f + 1e-6f);
    const float sixteenths = value * 16.f;
    CHECK(std::abs(sixteenths - std::round(sixteenths)) < 1e-4f);
    if (value > 0.f && value < 1.f) ++partial;
  }
  CHECK(partial > 0);
}

TEST_CASE("renderer: bad input is refused with one line") {
  const prt::scene::Scene scene = make_triangle_scene();
  const prt::scene::RayCaster caster(scene);
  prt::relight::Camera camera;
  prt::relight::RenderOptions options;
  options.width = 8;
  options.height = 8;
  const std::vector<float> too_short(6, 1.f);
  CHECK_THROWS_WITH(prt::relight::render(scene, caster, too_short, nullptr,
                                         prt::relight::kIdentityRotation, camera, options),
                    Catch::Contains("need 3 per vertex"));
  const std::vector<float> radiance(9, 1.f);
  options.samples_per_axis = 0;
  CHECK_THROWS_AS(prt::relight::render(scene, caster, radiance, nullptr,
                                       prt::relight::kIdentityRotation, camera, options),
                  std::runtime_error);
  options.samples_per_axis = 1;
  camera.target = camera.eye;
  CHECK_THROWS_WITH(prt::relight::render(scene, caster, radiance, nullptr,
                                         prt::relight::kIdentityRotation, camera, options),
                    Catch::Contains("coincide"));
}

TEST_CASE("renderer: the rows_done callback counts every row once and changes nothing") {
  const prt::scene::Scene scene = make_triangle_scene();
  const prt::scene::RayCaster caster(scene);
  const std::vector<float> radiance = {1.f, 2.f, 3.f, 10.f, 0.f, 5.f, 0.5f, 7.f, 20.f};
  prt::relight::Camera camera;
  camera.eye = glm::vec3(0.f, 0.f, 4.f);
  camera.target = glm::vec3(0.f);
  camera.up = glm::vec3(0, 1, 0);
  camera.yfov_radians = static_cast<float>(70 * kPi / 180);
  prt::relight::RenderOptions options;
  options.width = 64;
  options.height = 301;  // odd, so TBB's row ranges are uneven
  options.samples_per_axis = 2;
  const prt::relight::Image plain = prt::relight::render(
      scene, caster, radiance, nullptr, prt::relight::kIdentityRotation, camera, options);
  std::atomic<int> rows{0}, calls{0};
  options.rows_done = [&](int n) {  // called from the rendering threads
    rows += n;
    ++calls;
  };
  const prt::relight::Image counted = prt::relight::render(
      scene, caster, radiance, nullptr, prt::relight::kIdentityRotation, camera, options);
  CHECK(rows.load() == 301);
  CHECK(calls.load() >= 1);
  CHECK(counted.rgb == plain.rgb);  // bit for bit
}

TEST_CASE("renderer: the back of a one-sided surface is black, never the front's light") {
  // The triangle faces +z (counter-clockwise seen from +z). Its vertex radiance is the light
  // leaving the front; seen from behind (from −z) it must show black, not that light, and not
  // the background either (the surface is there, it hides the sky). Before, both sides showed
  // the front's radiance, so a room seen from outside showed its walls' backs lit.
  const prt::scene::Scene scene = make_triangle_scene();
  const prt::scene::RayCaster caster(scene);
  const std::vector<float> radiance(9, 2.f);
  const prt::sh::EnvMap env = make_analytic_latlong(64, 32);  // at least 0.5 in every direction
  prt::relight::RenderOptions options;
  options.width = 16;
  options.height = 12;
  options.samples_per_axis = 1;
  prt::relight::Camera camera;
  camera.target = glm::vec3(0.3f, 0.f, 0.f);
  camera.yfov_radians = static_cast<float>(90 * kPi / 180);  // the triangle in the middle
  const auto centre_pixel = [&](const prt::relight::Image& image) {
    const std::size_t at = 3 * (static_cast<std::size_t>(image.height / 2) * image.width +
                                static_cast<std::size_t>(image.width / 2));
    return glm::vec3(image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]);
  };
  camera.eye = glm::vec3(0.3f, 0.f, 4.f);  // in front
  const prt::relight::Image front = prt::relight::render(
      scene, caster, radiance, &env, prt::relight::kIdentityRotation, camera, options);
  CHECK(centre_pixel(front) == glm::vec3(2.f));
  camera.eye = glm::vec3(0.3f, 0.f, -4.f);  // behind
  const prt::relight::Image back = prt::relight::render(
      scene, caster, radiance, &env, prt::relight::kIdentityRotation, camera, options);
  CHECK(centre_pixel(back) == glm::vec3(0.f));
  // The corner pixels miss the triangle and show the sky on both sides.
  CHECK(back.rgb[0] > 0.4f);
  CHECK(front.rgb[0] > 0.4f);
}
