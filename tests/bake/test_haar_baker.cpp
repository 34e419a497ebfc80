// Tests of the Haar bake (bake/haar_baker.h), relit by the runtime (prt::HaarRelighter) on real
// baked scenes, each against an independent second method.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/haar_baker.h"
#include "bake/transfer_baker.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transform.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/texture.h"
#include "sh/constants.h"
#include "support/test_data.h"

namespace {

using prt::scene::Scene;
using prt::sh::kPi;

// A 2×2 floor (8×8 segments) with a box standing on its left half: the box shadows part of
// the floor for low directions, and its own faces are occluded by the floor.
Scene make_floor_with_box(float albedo) {
  Scene s = prt::scene::make_quad({-1.f, 0.f, 1.f}, {2.f, 0.f, 0.f}, {0.f, 0.f, -2.f}, 8, 8,
                                  glm::vec3(albedo), "floor");
  prt::scene::append_scene(s, prt::scene::make_box({-0.6f, 0.f, -0.3f}, {-0.1f, 0.6f, 0.3f}, 1,
                                                   false, glm::vec3(albedo), "box"));
  s.source_path = "floor_with_box";
  return s;
}

prt::bake::HaarBakeOptions exact_options(int cube) {
  prt::bake::HaarBakeOptions o;
  o.cube_size = cube;
  o.compression.quantization = prt::HaarQuantization::Float32;
  o.compression.relative_threshold = 0.0;  // every non-zero term kept
  return o;
}

// The second method: the dense transfer of vertex v, texel by texel, with single rays from
// RayCaster::occluded (not the baker's packets), texel-centre directions, exact solid angles.
std::vector<float> dense_transfer_by_single_rays(const Scene& scene,
                                                 const prt::scene::RayCaster& caster, uint32_t v,
                                                 int n) {
  std::vector<float> dense(std::size_t(6) * n * n, 0.f);
  const glm::vec3 normal = glm::normalize(scene.normals[v]);
  const glm::vec3 origin = caster.vertex_origin(v);
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        double d[3];
        prt::cube_texel_direction(n, face, col, row, d);
        const glm::vec3 dir{float(d[0]), float(d[1]), float(d[2])};
        const float c = glm::dot(normal, dir);
        if (!(c > 0.f) || caster.occluded(origin, dir, 0.f, INFINITY)) continue;
        dense[(std::size_t(face) * n + row) * n + col] = static_cast<float>(
            scene.albedo[v].x / kPi * c * prt::cube_texel_solid_angle(n, col, row));
      }
  return dense;
}

prt::CubeMap random_cube(int n, unsigned seed) {
  prt::CubeMap cube = prt::make_black_cube_map(n);
  uint32_t x = seed;
  for (float& value : cube.rgb) {
    x = x * 1664525u + 1013904223u;
    value = static_cast<float>(x >> 8) * 0x1p-24f * 4.f;  // in [0, 4)
  }
  return cube;
}

}  // namespace

TEST_CASE("Haar bake: all terms, unquantised, relights equal to the texel sum of single rays") {
  const Scene scene = make_floor_with_box(0.7f);
  const int n = 16;
  const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, exact_options(n));
  REQUIRE(baked.file.transfer.vertex_count == int64_t(scene.vertex_count()));
  REQUIRE(baked.stats.rays > 0);
  const prt::scene::RayCaster caster(scene);
  std::vector<float> dense;
  for (uint32_t v = 0; v < scene.vertex_count(); ++v) {
    const std::vector<float> d = dense_transfer_by_single_rays(scene, caster, v, n);
    dense.insert(dense.end(), d.begin(), d.end());
  }
  const prt::CubeMap light = random_cube(n, 5);
  std::vector<double> reference(3 * scene.vertex_count());
  REQUIRE(prt::shade_dense_reference(dense.data(), int64_t(scene.vertex_count()), n, 1, light,
                                     reference.data())
              .ok());
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(light);
  REQUIRE(wavelets.ok());
  const prt::HaarRelighter relighter(baked.file.transfer);
  std::vector<float> shaded(3 * scene.vertex_count());
  REQUIRE(relighter.shade(prt::keep_all_terms(*wavelets), shaded.data()).ok());
  double scale = 0;
  for (double r : reference) scale = std::max(scale, std::fabs(r));
  REQUIRE(scale > 0);
  // Tolerance 1e-5 of the largest radiance: both sides are sums of ~1500 float products (the
  // relighter accumulates in float; the wavelet transform rounds each coefficient once), so
  // rounding is ~√1500 · 2⁻²⁴ ≈ 2e-6 relative. A packet bug (wrong texel, lost ray) moves a
  // vertex by a whole texel's contribution, ≥ 1e-4 of the total.
  for (std::size_t i = 0; i < shaded.size(); ++i)
    REQUIRE(std::fabs(shaded[i] - reference[i]) <= 1e-5 * scale);
}

TEST_CASE("Haar bake: a point light in one texel lights exactly the vertices that see it") {
  const Scene scene = make_floor_with_box(0.5f);
  const int n = 16;
  const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, exact_options(n));
  const prt::HaarRelighter relighter(baked.file.transfer);
  const prt::scene::RayCaster caster(scene);
  // A low light from the +X face (grazing, so the box shadows part of the floor): texel
  // (col 8, row 12) of +X looks along (1, −b, a) with b = 0.5625: about 29° above the horizon.
  const int face = 0, col = 8, row = 3;
  prt::CubeMap light = prt::make_black_cube_map(n);
  const std::size_t t = (std::size_t(face) * n + row) * n + col;
  for (int c = 0; c < 3; ++c) light.rgb[3 * t + c] = 1000.f;
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(light);
  REQUIRE(wavelets.ok());
  std::vector<float> shaded(3 * scene.vertex_count());
  REQUIRE(relighter.shade(prt::keep_all_terms(*wavelets), shaded.data()).ok());
  double d[3];
  prt::cube_texel_direction(n, face, col, row, d);
  const glm::vec3 dir{float(d[0]), float(d[1]), float(d[2])};
  const double omega = prt::cube_texel_solid_angle(n, col, row);
  int lit = 0, dark = 0;
  for (uint32_t v = 0; v < scene.vertex_count(); ++v) {
    const float c = glm::dot(glm::normalize(scene.normals[v]), dir);
    const bool sees = c > 0.f && !caster.occluded(caster.vertex_origin(v), dir, 0.f, INFINITY);
    // Exact value: 1000 · ρ/π · cos · Ω for a vertex that sees it; 0 otherwise. Tolerance:
    // 1e-4 of the lit value, float rounding of the 6N² wavelet products of the single-texel
    // map (each about 1000/N of the same order).
    const double expected = sees ? 1000.0 * 0.5 / kPi * c * omega : 0.0;
    const double unit = 1000.0 * 0.5 / kPi * omega;
    for (int ch = 0; ch < 3; ++ch) REQUIRE(std::fabs(shaded[3 * v + ch] - expected) <= 1e-4 * unit);
    (sees ? lit : dark)++;
  }
  // Both classes must be populated for the test to mean anything: the floor behind the box
  // (and the box's −X side) are dark, the rest lit.
  CHECK(lit > 20);
  CHECK(dark > 20);
}

TEST_CASE("Haar bake agrees with the SH bake under smooth low-frequency light") {
  // L(ω) = 1 + 0.5·y is band-limited to l ≤ 1, so the SH result Σ_k T_k L_k is exact for any
  // order ≥ 2 up to Monte Carlo noise; Haar differs only by its texel quadrature.
  const Scene scene = make_floor_with_box(0.6f);
  prt::bake::BakeOptions sh;
  sh.kind = prt::TransferKind::Shadowed;
  sh.order = 3;
  sh.samples = 4096;
  const prt::bake::BakeResult sh_bake = prt::bake::bake_transfer(scene, sh);
  prt::bake::HaarBakeOptions ho = exact_options(32);
  ho.supersample = 2;
  const prt::bake::HaarBakeResult haar = prt::bake::bake_haar_transfer(scene, ho);

  const double l00 = std::sqrt(4 * kPi), l1m1 = 0.5 / 0.488603;  // SH of 1 + 0.5·y
  const int n = 32;
  prt::CubeMap light = prt::make_black_cube_map(n);
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        double d[3];
        prt::cube_texel_direction(n, face, col, row, d);
        const std::size_t t = (std::size_t(face) * n + row) * n + col;
        for (int c = 0; c < 3; ++c) light.rgb[3 * t + c] = static_cast<float>(1.0 + 0.5 * d[1]);
      }
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(light);
  REQUIRE(wavelets.ok());
  std::vector<float> shaded(3 * scene.vertex_count());
  REQUIRE(prt::HaarRelighter(haar.file.transfer)
              .shade(prt::keep_all_terms(*wavelets), shaded.data())
              .ok());
  double err2 = 0, ref2 = 0, max_err = 0, max_ref = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    const float* t = &sh_bake.data.coefficients[v * 9];
    const double b = t[0] * l00 + t[1] * l1m1;
    err2 += (shaded[3 * v] - b) * (shaded[3 * v] - b);
    ref2 += b * b;
    max_err = std::max(max_err, std::fabs(shaded[3 * v] - b));
    max_ref = std::max(max_ref, std::fabs(b));
  }
  const double rms = std::sqrt(err2 / ref2);
  INFO("relative RMS " << rms << ", max " << max_err / max_ref);
  // Tolerances: 4096 stratified samples give ~0.3% noise; N = 32 with 2×2 supersampling
  // misplaces shadow edges by < 1/64 of a face (~0.5% where the box's silhouette crosses).
  CHECK(rms < 0.01);
  CHECK(max_err < 0.03 * max_ref);
}

// Interreflected Haar bake in the spherical-cavity furnace: inside a
// sphere with an opening of polar half-angle a, under uniform white sky radiance 1, every inner
// point sees the opening with cosine-weighted fraction f = (1 − cos a)/2, so the exit radiance
// is B = ρf / (1 − ρ(1 − f)) at every vertex. All terms kept, unquantised, relit with a constant
// white cube map (every lighting term), so only the bake's discretisation remains.
TEST_CASE(
    "Haar bake: interreflected transfer in the spherical-cavity furnace matches ρf/(1−ρ(1−f))") {
  const float a = static_cast<float>(kPi / 3);  // 60°: f = 0.25
  const double f = (1.0 - std::cos(double(a))) / 2.0;
  const int n = 16;
  prt::CubeMap white = prt::make_black_cube_map(n);
  std::fill(white.rgb.begin(), white.rgb.end(), 1.f);
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(white);
  REQUIRE(wavelets.ok());
  for (const float rho : {0.5f, 0.9f}) {
    CAPTURE(rho);
    Scene scene = prt::scene::make_spherical_cavity(1.f, a, 12, 48, glm::vec3(rho));
    scene.source_path = "cavity";
    prt::bake::HaarBakeOptions o = exact_options(n);
    o.transport = prt::TransferKind::Interreflected;
    o.bounces = -1;  // solved to convergence
    o.bounce_tolerance = 1e-6;
    const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, o);
    REQUIRE(baked.stats.solver_converged);
    const prt::HaarRelighter relighter(baked.file.transfer);
    std::vector<float> b(3 * scene.vertex_count());
    REQUIRE(relighter.shade(prt::keep_all_terms(*wavelets), b.data()).ok());
    const double expected = double(rho) * f / (1.0 - double(rho) * (1.0 - f));
    const double direct_only = double(rho) * f;  // what a bake without bounces would give
    double sum = 0, worst = 0;
    for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
      const double value = b[3 * v + 1];
      REQUIRE(std::isfinite(value));
      sum += value;
      worst = std::max(worst, std::fabs(value / expected - 1.0));
    }
    const double mean = sum / double(scene.vertex_count());
    CAPTURE(expected, mean, worst, direct_only);
    // Tolerances: mean 1%, every vertex 4% (measured: 0.22% / 2.9% at ρ = 0.5, 0.09% / 0.7% at
    // ρ = 0.9). The bake integrates with texel-centre directions
    // at N = 16 (a texel spans ≈ 5.6°): the opening's rim cuts ~100 texels, each counted wholly
    // in or out, which moves a vertex's direct term by up to a few % of f (dB/B = (1−ρ)/(1−ρ+ρf)
    // · df/f: 0.8× at ρ = 0.5, 0.31× at ρ = 0.9), and averages out over vertices; the mesh is
    // faceted (48 segments: the opening polygon's area is 0.3% under the circle's) and its
    // bounce matrix H is gathered from the same texel rays. A bake that lost the bounces (B =
    // ρf: −50% at ρ = 0.5, −77% at ρ = 0.9) or double-counted albedo fails by far more.
    CHECK(std::fabs(mean / expected - 1.0) <= 0.01);
    CHECK(worst <= 0.04);
    CHECK(std::fabs(mean - direct_only) > 0.3 * expected);
  }
}

// A textured scene keeps the albedo apart (bake/haar_baker.h). With a uniform texture of value ρ
// and fixed Jacobi bounces, the kept-apart G and the folded T of the same scene with a flat ρ
// satisfy T = ρ·G identically (the same rays, the same H up to where the albedo multiplies), so
// only float round-off separates ρ·G from T (2e-5 of the largest value allowed).
TEST_CASE("Haar bake: a uniform texture of value ρ relights as a flat albedo ρ, albedo apart") {
  const glm::vec3 rho(0.6f, 0.45f, 0.3f);
  Scene flat = make_floor_with_box(0.5f);
  for (glm::vec3& a : flat.albedo) a = rho;
  for (auto& p : flat.primitives) p.albedo = rho;
  Scene textured = flat;
  prt::scene::BaseColorTexture t;
  t.image = std::make_shared<const prt::scene::TextureImage>(
      prt::scene::TextureImage::from_linear_rgb(1, 1, {rho.x, rho.y, rho.z}, "uniform"));
  textured.primitives[0].base_color_texture = t;  // the floor
  const int n = 8;
  const prt::CubeMap sky = random_cube(n, 7);
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(sky);
  REQUIRE(wavelets.ok());
  for (const auto kind : {prt::TransferKind::Shadowed, prt::TransferKind::Interreflected}) {
    CAPTURE(prt::transfer_kind_name(kind));
    prt::bake::HaarBakeOptions o = exact_options(n);
    o.transport = kind;
    o.bounces = 6;
    const prt::bake::HaarBakeResult f = prt::bake::bake_haar_transfer(flat, o);
    const prt::bake::HaarBakeResult g = prt::bake::bake_haar_transfer(textured, o);
    CHECK(f.file.info.albedo_folded);
    CHECK_FALSE(g.file.info.albedo_folded);
    CHECK(g.file.info.channels == (kind == prt::TransferKind::Shadowed ? 1u : 3u));
    std::vector<float> bf(3 * flat.vertex_count()), bg(bf.size());
    REQUIRE(
        prt::HaarRelighter(f.file.transfer).shade(prt::keep_all_terms(*wavelets), bf.data()).ok());
    REQUIRE(
        prt::HaarRelighter(g.file.transfer).shade(prt::keep_all_terms(*wavelets), bg.data()).ok());
    double worst = 0.0, largest = 0.0;
    for (std::size_t v = 0; v < flat.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::fabs(double(rho[c]) * bg[3 * v + c] - bf[3 * v + c]));
        largest = std::max(largest, std::fabs(double(bf[3 * v + c])));
      }
    CAPTURE(worst, largest);
    CHECK(largest > 0.0);
    CHECK(worst <= 2e-5 * largest);
  }
}
