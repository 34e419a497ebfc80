// relight/glossy_relight.h: the turntable's camera orbit, the --eye requirement, and the parallel
// shading of every vertex against the kernel's own call.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "relight/glossy_relight.h"
#include "sh/rotation.h"

using prt::relight::Camera;

TEST_CASE("Glossy turntable: the camera orbits the vertical line through the scene's centre",
          "[glossy]") {
  // A scene camera as glTF gives it: a direction, here with its target a unit in front of the
  // eye, while the scene's centre is 5 units away. Orbiting that nearby target (as before) swings
  // the view off the scene; orbiting the centre keeps the centre where frame 0 shows it.
  Camera c;
  c.eye = {1.f, 2.f, 5.f};
  c.target = {0.8f, 1.7f, 4.05f};
  const glm::vec3 centre{0.f, 0.5f, 0.f};
  const float aspect = 1.5f;
  const auto ndc_of_centre = [&](const Camera& camera) {
    glm::vec2 ndc(9.f);
    const auto basis = prt::relight::make_camera_basis(camera, aspect);
    REQUIRE(prt::relight::project_to_ndc(basis, camera.eye, centre, &ndc));
    return ndc;
  };
  const glm::vec2 first = ndc_of_centre(c);
  REQUIRE(std::abs(first.x) < 1.f);
  REQUIRE(std::abs(first.y) < 1.f);
  const int n = 8;
  for (int i = 0; i <= n; ++i) {
    const Camera o = prt::relight::orbit_camera(c, centre, i, n);
    // Distance to the axis, height and the view are kept: the centre stays at the same pixel
    // (float round-off of a rotation and a projection).
    const auto radius = [&](glm::vec3 p) { return std::hypot(p.x - centre.x, p.z - centre.z); };
    CHECK(radius(o.eye) == Approx(radius(c.eye)).epsilon(1e-6));
    CHECK(o.eye.y == Approx(c.eye.y).margin(1e-6));
    CHECK(glm::length(o.target - o.eye) == Approx(glm::length(c.target - c.eye)).epsilon(1e-5));
    const glm::vec2 ndc = ndc_of_centre(o);
    CHECK(ndc.x == Approx(first.x).margin(1e-4));
    CHECK(ndc.y == Approx(first.y).margin(1e-4));
    // Frame i is turned by 360°·i/N: the horizontal offset's angle.
    const float angle = std::atan2(o.eye.x - centre.x, o.eye.z - centre.z);
    const float start = std::atan2(c.eye.x - centre.x, c.eye.z - centre.z);
    const float expected = start + 2.f * prt::numerics::kPiFloat * float(i) / n;
    CHECK(std::remainder(angle - expected, 2.f * prt::numerics::kPiFloat) ==
          Approx(0.f).margin(1e-5));
  }
  // Frame 0 is the camera itself.
  const Camera zero = prt::relight::orbit_camera(c, centre, 0, n);
  CHECK(zero.eye == c.eye);
  CHECK(zero.target == c.target);
}

TEST_CASE("Glossy relight: CSV and vertex colours need an eye point", "[glossy]") {
  prt::relight::RelightRequest request;
  request.transfer_path = "shiny.prtg";
  prt::relight::GlossyRelightOptions options;
  CHECK_NOTHROW(prt::relight::check_glossy_request(request, options));  // images only
  request.csv_path = "out.csv";
  try {
    prt::relight::check_glossy_request(request, options);
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    CHECK(message.find("shiny.prtg") == 0);
    CHECK(message.find("--eye") != std::string::npos);
  }
  options.eye = glm::vec3(0.f, 1.f, 2.f);
  CHECK_NOTHROW(prt::relight::check_glossy_request(request, options));
  options.eye = glm::vec3(0.f, NAN, 2.f);
  CHECK_THROWS(prt::relight::check_glossy_request(request, options));
}

TEST_CASE("Glossy relight: parallel shading equals the kernel called once", "[glossy]") {
  // 3000 vertices on a sphere (more than two of the parallel ranges), unshadowed order-3
  // transfer (M = the SH rotation into each tangent frame), a Blinn-Phong material.
  prt::GlossyTransferData d;
  const std::size_t count = 3000;
  d.order = 3;
  d.vertex_count = count;
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kBlinnPhong;
  m.diffuse = prt::brdf::grey(0.3);
  m.specular = prt::brdf::grey(0.4);
  m.exponent = 30;
  d.materials = {m};
  d.material_of_vertex.assign(count, 0);
  for (std::size_t v = 0; v < count; ++v) {
    const double z = 1.0 - (2.0 * double(v) + 1.0) / double(count), r = std::sqrt(1 - z * z);
    const double phi = 2.39996 * double(v);
    const double n[3] = {r * std::cos(phi), r * std::sin(phi), z};
    const double s = std::copysign(1.0, n[2]), a = -1.0 / (s + n[2]), b = n[0] * n[1] * a;
    const double t[3] = {1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]};
    const double bt[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                          n[0] * t[1] - n[1] * t[0]};
    for (int k = 0; k < 3; ++k) {
      d.positions.push_back(float(n[k]));
      d.normals.push_back(float(n[k]));
      d.tangents.push_back(float(t[k]));
    }
    d.tangents.push_back(1.f);
    const prt::sh::Rotation rot(3, {t[0], t[1], t[2], bt[0], bt[1], bt[2], n[0], n[1], n[2]});
    std::vector<float> block(81, 0.f);
    for (int l = 0; l < 3; ++l) {
      const double* band = rot.band_matrix(l);
      const int w = 2 * l + 1, o = l * l;
      for (int i = 0; i < w; ++i)
        for (int j = 0; j < w; ++j)
          block[std::size_t((o + i) * 9 + o + j)] = float(band[i * w + j]);
    }
    d.matrices.insert(d.matrices.end(), block.begin(), block.end());
  }
  auto relighter = prt::GlossyRelighter::create(d);
  REQUIRE(relighter.ok());
  std::vector<double> rgb(27, 0.0);
  for (int c = 0; c < 3; ++c) rgb[std::size_t(c * 9)] = 1.0, rgb[std::size_t(c * 9 + 2)] = 0.5;
  auto light = prt::ShLighting::from_coefficients(3, rgb.data());
  REQUIRE(light.ok());
  const glm::vec3 eye(0.5f, 1.f, 3.f);
  const std::vector<float> parallel = prt::relight::shade_glossy_vertices(*relighter, *light, eye);
  std::vector<float> once(3 * count);
  const float e[3] = {eye.x, eye.y, eye.z};
  REQUIRE(relighter->shade(*light, e, 0, count, once.data()).ok());
  REQUIRE(parallel == once);
  float brightest = 0.f;
  for (float x : once) brightest = std::max(brightest, x);
  REQUIRE(brightest > 0.f);
}
