// The relight path (relight/relight_pipeline.h) against independent references: AO under a
// white sky, direct numerical integration under a sky with a sun, SH rotation vs re-projection
// of a resampled map, and refusal of mismatched or corrupt coefficient files.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/transfer_baker.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/transfer_file.h"
#include "relight/image_io.h"
#include "relight/relight_pipeline.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "sh/constants.h"
#include "sh/env_map.h"
#include "sh/projection.h"
#include "sh/rotation.h"
#include "support/test_data.h"

using prt::sh::kPi;

namespace {

namespace fs = std::filesystem;
using prt::scene::Scene;

// A box standing on a plane: plenty of partial occlusion, contact shadows and a box top.
Scene make_box_on_plane(glm::vec3 plane_albedo, glm::vec3 box_albedo) {
  Scene scene = prt::scene::make_quad(glm::vec3(-2, 0, -2), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0),
                                      16, 16, plane_albedo, "ground");
  prt::scene::append_scene(
      scene, prt::scene::make_box(glm::vec3(-0.5f, 0.f, -0.5f), glm::vec3(0.5f, 1.f, 0.5f), 4,
                                  false, box_albedo, "box"));
  return scene;
}

prt::sh::EnvMap make_latlong(int width, int height, glm::dvec3 (*radiance)(const glm::dvec3&)) {
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = width;
  env.height = height;
  env.rgb.resize(3 * static_cast<std::size_t>(width) * height);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      // Lat-long: u = 0.5 + atan2(z, x)/2π, v = acos(y)/π, written out independently.
      const double phi = 2 * kPi * ((col + 0.5) / width - 0.5), theta = kPi * (row + 0.5) / height;
      const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
      const glm::dvec3 f = radiance(d);
      for (int c = 0; c < 3; ++c)
        env.rgb[3 * (static_cast<std::size_t>(row) * width + col) + c] = static_cast<float>(f[c]);
    }
  return env;
}

// A sky with a sun-like lobe: gradient sky, dim ground, and a narrow bright lobe at elevation
// 40°; smooth enough for bilinear resampling and order-6 projection to be meaningful.
glm::dvec3 sunny_sky(const glm::dvec3& d) {
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.5, 0.64, -0.58));
  const double lobe = 6.0 * std::exp(12.0 * (glm::dot(d, sun) - 1.0));
  const double sky = d.y > 0 ? 0.6 + 0.4 * (1 - d.y) : 0.25;
  return glm::dvec3(sky * 0.7 + lobe, sky * 0.85 + 0.9 * lobe, sky * 1.1 + 0.7 * lobe);
}

glm::dvec3 white_sky(const glm::dvec3&) {
  return glm::dvec3(1.0);
}

glm::dvec3 smooth_sky(const glm::dvec3& d) {
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.8, 0.5));
  const double lobe = std::exp(3.0 * (glm::dot(d, a) - 1.0));
  return glm::dvec3(1 + 0.5 * d.x + lobe, 1 + 0.3 * d.y * d.z + 2 * lobe, 0.7 + 0.2 * d.z);
}

prt::bake::BakeResult bake(const Scene& scene, prt::TransferKind kind, int order, int samples,
                           bool ao, uint64_t seed = 1) {
  prt::bake::BakeOptions options;
  options.kind = kind;
  options.order = order;
  options.samples = samples;
  options.ao = ao;
  options.threads = 2;
  options.seed = seed;
  return prt::bake::bake_transfer(scene, options, nullptr);
}

std::vector<float> shade(const prt::TransferData& data, const prt::ShLighting& lighting) {
  auto relighter = prt::Relighter::create(data);
  REQUIRE(relighter.ok());
  return prt::relight::shade_all_vertices(*relighter, lighting, data.vertex_count);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("relight: under a constant white sky, shadowed radiance = albedo × AO") {
  const Scene scene = make_box_on_plane(glm::vec3(0.6f, 0.4f, 0.2f), glm::vec3(0.3f, 0.7f, 0.5f));
  const int order = 4;
  const prt::bake::BakeResult baked = bake(scene, prt::TransferKind::Shadowed, order, 256, true);
  const prt::TransferData& data = baked.data;
  REQUIRE(data.channels == 3);
  REQUIRE(data.ao.size() == scene.vertex_count());

  const prt::sh::EnvMap env = make_latlong(128, 64, white_sky);
  const prt::ShLighting lighting = prt::relight::project_lighting(env, order, {});
  const std::vector<float> radiance = shade(data, lighting);

  // The projection of a constant is exact only up to quadrature: L_00 = √(4π), while the
  // zonal L_l0 (l even) pick up the small error of the row quadrature. Bound its effect:
  // |ΔB| ≤ Σ_k |T_k| |L_k − L_exact_k|. Besides that, B = Σ_s albedo·V_s·Y_00·√(4π)/N and
  // AO = Σ_s V_s/N are the same estimator, so the rest is float round-off (~1e-6; 1e-5 allowed).
  const int k_count = order * order;
  int partially_occluded = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    const float ao = data.ao[v];
    if (ao > 0.05f && ao < 0.95f) ++partially_occluded;
    for (int c = 0; c < 3; ++c) {
      const float* t = &data.coefficients[(v * 3 + c) * k_count];
      double bound = 0;
      for (int k = 0; k < k_count; ++k) {
        const double exact = k == 0 ? std::sqrt(4 * kPi) : 0.0;
        bound += std::abs(t[k]) * std::abs(lighting.coefficients_double(c)[k] - exact);
      }
      const double expected = scene.albedo[v][c] * ao;
      INFO("vertex " << v << " channel " << c << " AO " << ao);
      CHECK(radiance[3 * v + c] == Approx(expected).margin(bound + 1e-5));
    }
  }
  CHECK(partially_occluded > 20);  // the scene really tests occlusion
}

TEST_CASE("relight: radiance under a sunny sky equals a direct integration of L·V·cos·ρ/π") {
  const Scene scene = make_box_on_plane(glm::vec3(0.7f), glm::vec3(0.7f));
  const int order = 5, samples = 1024, seeds = 16;
  const prt::sh::EnvMap env = make_latlong(256, 128, sunny_sky);
  const prt::ShLighting lighting = prt::relight::project_lighting(env, order, {});
  // The file under test (seed 1), and 15 more bakes with other seeds to measure the baker's
  // actual error (its scrambled low-discrepancy samples beat plain Monte Carlo by far).
  std::vector<std::vector<float>> relit;
  for (int seed = 1; seed <= seeds; ++seed)
    relit.push_back(shade(
        bake(scene, prt::TransferKind::Shadowed, order, samples, false, static_cast<uint64_t>(seed))
            .data,
        lighting));
  const std::vector<float>& radiance = relit.front();
  std::vector<double> coefficients(3 * order * order);
  for (int c = 0; c < 3; ++c)
    std::copy(lighting.coefficients_double(c), lighting.coefficients_double(c) + order * order,
              coefficients.begin() + c * order * order);

  // Independent reference: an equal-area stratified grid on the sphere (cells uniform in
  // cos θ and φ about +Y, centre of each cell), with visibility from RayCaster::occluded and the
  // SH-projected lighting from prt::sh::reconstruct. B = ∫ L_proj V max(n·ω, 0) ρ/π dω: the relit
  // value is exactly this integral when T is the exact projection of V·cos·ρ/π.
  const prt::scene::RayCaster caster(scene);
  struct Moments {
    double b[3] = {0, 0, 0}, second[3] = {0, 0, 0};
  };
  auto integrate = [&](std::size_t v, int rows) {
    const int cols = 2 * rows;
    const double cell = 4 * kPi / (static_cast<double>(rows) * cols);
    const glm::vec3 n = scene.normals[v];
    const glm::vec3 origin = caster.vertex_origin(static_cast<uint32_t>(v));
    Moments m;
    for (int i = 0; i < rows; ++i) {
      const double y = 1 - 2 * (i + 0.5) / rows, s = std::sqrt(std::max(0.0, 1 - y * y));
      for (int j = 0; j < cols; ++j) {
        const double phi = 2 * kPi * (j + 0.5) / cols;
        const double dir[3] = {s * std::cos(phi), y, s * std::sin(phi)};
        const double cosine = n.x * dir[0] + n.y * dir[1] + n.z * dir[2];
        if (cosine <= 0) continue;
        const glm::vec3 d(static_cast<float>(dir[0]), static_cast<float>(dir[1]),
                          static_cast<float>(dir[2]));
        if (caster.occluded(origin, d, 0.f, INFINITY)) continue;
        double l[3];
        prt::sh::reconstruct(coefficients.data(), 3, order, dir, l);
        for (int c = 0; c < 3; ++c) {
          const double g = scene.albedo[v][c] * l[c];  // the baker's per-sample value
          m.b[c] += g * cosine / kPi * cell;
          m.second[c] += g * g * cosine / kPi * cell;  // E_cos[g²]
        }
      }
    }
    return m;
  };

  // Ground grid vertex (i, j) sits at z = −2 + i/4, x = −2 + j/4 (make_quad's order); the box
  // covers i, j ∈ [6, 10]. Probes: beside the box (contact shadow), a little farther, the
  // other side, two far ground points; then box faces (make_box: +X, −X, +Y, … of 5×5 each).
  const std::size_t probes[] = {17 * 8 + 5, 17 * 8 + 4, 17 * 11 + 8, 17 * 2 + 2, 17 * 16 + 16};
  std::vector<std::size_t> vertices(std::begin(probes), std::end(probes));
  const std::size_t ground = 17 * 17;
  vertices.push_back(ground + 1 * 25 + 12);  // centre of the −X face
  vertices.push_back(ground + 2 * 25 + 12);  // centre of the top
  vertices.push_back(ground + 4 * 25 + 12);  // centre of the +Z face
  for (std::size_t v : vertices) {
    const Moments fine = integrate(v, 512), coarse = integrate(v, 256);
    for (int c = 0; c < 3; ++c) {
      // Baker error: its estimator averages g = ρ·V·L_proj over N cosine-distributed samples,
      // so its standard error is at most √((E_cos[g²] − B²)/N) (plain Monte Carlo; the baker's
      // scrambled low-discrepancy samples do better). Allow 4σ. The grid reference's own error
      // is estimated by the change from the coarse to the fine grid (visibility edges converge
      // like 1/rows). Float shading adds ~1e-6 relative.
      const double sigma =
          std::sqrt(std::max(0.0, fine.second[c] - fine.b[c] * fine.b[c]) / samples);
      const double grid_error = std::abs(fine.b[c] - coarse.b[c]);
      const double tolerance = 4 * sigma + 2 * grid_error + 1e-5 * std::abs(fine.b[c]);
      INFO("vertex " << v << " channel " << c << " reference " << fine.b[c] << " sigma " << sigma
                     << " grid " << grid_error);
      CHECK(radiance[3 * v + c] == Approx(fine.b[c]).margin(tolerance));
      CHECK(tolerance < 0.25 * std::abs(fine.b[c]));  // the check is not vacuous

      // The tighter check: the mean over the seeds against the reference, within 5 standard
      // errors of that mean as measured from the seeds' spread (15 degrees of freedom: a 5σ
      // excursion has probability ~2e-4; the bakes are deterministic, so the outcome is fixed),
      // plus the grid error and a 1e-4 relative floor for seeds that agree closely.
      double mean = 0, spread = 0;
      for (const auto& r : relit) mean += r[3 * v + c] / seeds;
      for (const auto& r : relit) spread += (r[3 * v + c] - mean) * (r[3 * v + c] - mean);
      const double standard_error = std::sqrt(spread / (seeds - 1) / seeds);
      CHECK(mean == Approx(fine.b[c]).margin(5 * standard_error + 2 * grid_error +
                                             1e-4 * std::abs(fine.b[c])));
    }
  }
}

TEST_CASE("relight: SH-rotated lighting equals projecting the rotated (resampled) map") {
  const int order = 6;
  const prt::sh::EnvMap env = make_latlong(512, 256, smooth_sky);
  const std::array<double, 9> m = prt::sh::rotation_from_yaw_pitch_roll(70.0, -35.0, 20.0);
  const prt::ShLighting rotated =
      prt::relight::rotate_lighting(prt::relight::project_lighting(env, order, {}), m);

  // Resample: texel of the new map in direction d takes the original at Mᵀd (g(d) = f(Mᵀd)).
  prt::sh::EnvMap resampled = env;
  for (int row = 0; row < env.height; ++row)
    for (int col = 0; col < env.width; ++col) {
      double d[3];
      REQUIRE(prt::sh::texel_direction(env.layout, env.width, env.height, col, row, d));
      double source[3];
      for (int i = 0; i < 3; ++i) source[i] = m[i] * d[0] + m[3 + i] * d[1] + m[6 + i] * d[2];
      prt::sh::sample_bilinear(
          env, source, &resampled.rgb[3 * (static_cast<std::size_t>(row) * env.width + col)]);
    }
  const prt::ShLighting projected = prt::relight::project_lighting(resampled, order, {});
  const prt::ShLighting unrotated = prt::relight::project_lighting(env, order, {});

  // Tolerance: bilinear resampling of a function whose second derivatives are ≤ ~10 per rad²
  // (the lobe exp(3(cos γ − 1)) and the linear terms), texels of π/256 rad: pointwise error
  // ≤ 10·2·(π/256)²/8 ≈ 4e-4, so each coefficient moves by at most √(4π)·4e-4 ≈ 1.3e-3
  // (Cauchy–Schwarz, ‖Y‖ = 1). 2e-3 leaves a margin; the rotation itself is exact to ~1e-12.
  double max_difference = 0, max_rotation_effect = 0;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < order * order; ++k) {
      const double a = rotated.coefficients_double(c)[k], b = projected.coefficients_double(c)[k];
      CHECK(a == Approx(b).margin(2e-3));
      max_difference = std::max(max_difference, std::abs(a - b));
      max_rotation_effect =
          std::max(max_rotation_effect, std::abs(a - unrotated.coefficients_double(c)[k]));
    }
  INFO("max |SH rotation − re-projection| " << max_difference);
  CHECK(max_rotation_effect > 0.1);  // the rotation changes the coefficients a lot
}

TEST_CASE("relight: turntable frames turn about +Y on top of --rotate") {
  const std::array<double, 9> base = prt::sh::rotation_from_yaw_pitch_roll(10.0, 20.0, 30.0);
  const std::array<double, 9> frame = prt::relight::turntable_rotation(base, 1, 4);
  const std::array<double, 9> expected = prt::sh::rotation_from_yaw_pitch_roll(100.0, 20.0, 30.0);
  for (int i = 0; i < 9; ++i) CHECK(frame[i] == Approx(expected[i]).margin(1e-12));
  CHECK(prt::relight::turntable_frame_path("dir/out.png", 7) == "dir/out_007.png");
  CHECK(prt::relight::turntable_frame_path("out.exr", 123) == "out_123.exr");
}

TEST_CASE("relight: a mismatched or corrupt coefficient file is refused, nothing is written") {
  const fs::path dir = prt::test::output_path("relight_refusal");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Scene scene_a = make_box_on_plane(glm::vec3(0.5f), glm::vec3(0.5f));
  Scene scene_b = scene_a;
  scene_b.positions[3].y += 0.25f;  // a different mesh with the same vertex count
  const std::string scene_a_path = (dir / "a.glb").string(),
                    scene_b_path = (dir / "b.glb").string();
  prt::scene::write_glb(scene_a_path, scene_a);
  prt::scene::write_glb(scene_b_path, scene_b);
  const std::string prt_path = (dir / "a.prt").string();
  REQUIRE(prt::write_transfer_file(prt_path,
                                   bake(scene_a, prt::TransferKind::Unshadowed, 3, 16, false).data)
              .ok());
  const prt::sh::EnvMap env = make_latlong(64, 32, smooth_sky);
  const std::string env_path = (dir / "sky.exr").string();
  prt::relight::write_image(env_path, env.width, env.height, 3, env.rgb.data());

  prt::relight::RelightRequest request;
  request.scene_path = scene_a_path;
  request.transfer_path = prt_path;
  request.environment_path = env_path;
  request.output_path = (dir / "out.png").string();
  request.csv_path = (dir / "out.csv").string();
  request.render.width = 48;
  request.render.height = 32;

  // The matching file works (and writes what was asked).
  const prt::relight::RelightSummary summary = prt::relight::run_relight(request);
  CHECK(summary.vertex_count == scene_a.vertex_count());
  CHECK(fs::exists(request.output_path));
  std::ifstream csv(request.csv_path);
  const std::size_t lines = static_cast<std::size_t>(
      std::count(std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>(), '\n'));
  CHECK(lines == scene_a.vertex_count() + 1);
  fs::remove(request.output_path);
  fs::remove(request.csv_path);

  // A different mesh.
  request.scene_path = scene_b_path;
  std::string message = error_of([&] { prt::relight::run_relight(request); });
  CHECK_THAT(message, Catch::Contains(prt_path) && Catch::Contains("was not baked for"));
  CHECK(message.find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(request.output_path));
  CHECK_FALSE(fs::exists(request.csv_path));

  // A flipped byte in the middle of the coefficients.
  request.scene_path = scene_a_path;
  {
    std::fstream file(prt_path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekg(0, std::ios::end);
    const auto size = static_cast<std::streamoff>(file.tellg());
    file.seekg(size / 2);
    char byte = 0;
    file.read(&byte, 1);
    byte = static_cast<char>(byte ^ 0x10);
    file.seekp(size / 2);
    file.write(&byte, 1);
  }
  message = error_of([&] { prt::relight::run_relight(request); });
  CHECK_THAT(message, Catch::Contains(prt_path));
  CHECK(message != "no error");
  CHECK(message.find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(request.output_path));

  // load_transfer_for_scene refuses both on its own too.
  CHECK_THROWS_WITH(prt::relight::load_transfer_for_scene(prt_path, scene_a),
                    Catch::Contains(prt_path));
  CHECK_THROWS_WITH(prt::relight::load_transfer_for_scene((dir / "missing.prt").string(), scene_a),
                    Catch::Contains("missing.prt"));
}
