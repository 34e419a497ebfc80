// Textured scenes from bake to pixel: the transfer keeps the albedo apart (bake/transfer_baker.h),
// the renderer applies the texture per pixel (relight/renderer.h). References: the same scene
// with a flat albedo equal to the texture (exact up to float round-off), a ray–plane
// intersection written here (which half of a two-colour texture each pixel shows), and a flat
// wall of the texture's mean colour (interreflection, within a Monte Carlo tolerance measured
// from the data).
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/transfer_baker.h"
#include "prt/diffuse/relighter.h"
#include "relight/camera.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/texture.h"
#include "sh/constants.h"

using prt::scene::BaseColorTexture;
using prt::scene::Scene;
using prt::scene::TextureImage;

namespace {

// A texture of w × h texels, `left` in the columns below w/2 and `right` in the others (linear).
std::shared_ptr<const TextureImage> halves(int w, int h, glm::vec3 left, glm::vec3 right) {
  std::vector<float> rgb;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const glm::vec3 c = 2 * i < w ? left : right;
      rgb.insert(rgb.end(), {c.x, c.y, c.z});
    }
  return std::make_shared<const TextureImage>(TextureImage::from_linear_rgb(w, h, rgb, "halves"));
}

// Constant white sky of radiance 1, as SH lighting of the given order.
prt::ShLighting white_sky(int order) {
  std::vector<double> c(3 * static_cast<std::size_t>(order) * order, 0.0);
  for (int ch = 0; ch < 3; ++ch)
    c[static_cast<std::size_t>(ch) * order * order] = std::sqrt(4 * prt::sh::kPi);
  auto lighting = prt::ShLighting::from_coefficients(order, c.data());
  REQUIRE(lighting.ok());
  return std::move(lighting).value();
}

// A sky brighter toward +X and up (so that interreflection and colour matter).
prt::ShLighting uneven_sky(int order) {
  std::vector<double> c(3 * static_cast<std::size_t>(order) * order, 0.0);
  for (int ch = 0; ch < 3; ++ch) {
    double* l = &c[static_cast<std::size_t>(ch) * order * order];
    l[0] = std::sqrt(4 * prt::sh::kPi) * (1.0 + 0.2 * ch);
    l[2] = 1.2;  // Y_1,0 ∝ y
    l[3] = 1.5;  // Y_1,1 ∝ x
  }
  auto lighting = prt::ShLighting::from_coefficients(order, c.data());
  REQUIRE(lighting.ok());
  return std::move(lighting).value();
}

prt::bake::BakeResult bake(const Scene& scene, prt::TransferKind kind, int samples, int bounces) {
  prt::bake::BakeOptions options;
  options.kind = kind;
  options.order = 3;
  options.samples = samples;
  options.bounces = bounces;
  options.threads = 2;
  return prt::bake::bake_transfer(scene, options, nullptr);
}

std::vector<float> shade(const prt::TransferData& data, const prt::ShLighting& lighting) {
  auto relighter = prt::Relighter::create(data);
  REQUIRE(relighter.ok());
  return prt::relight::shade_all_vertices(*relighter, lighting, data.vertex_count);
}

// Ground (textured or flat, albedo rho) with a box on it and a flat wall behind.
Scene ground_box_wall(glm::vec3 rho, bool textured) {
  Scene scene = prt::scene::make_quad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, 12, 12, rho, "ground");
  if (textured) {
    BaseColorTexture t;
    t.image = std::make_shared<const TextureImage>(
        TextureImage::from_linear_rgb(1, 1, {rho.x, rho.y, rho.z}, "uniform"));
    scene.primitives[0].base_color_texture = t;
  }
  prt::scene::append_scene(scene, prt::scene::make_box({-0.5f, 0.f, -0.5f}, {0.5f, 1.f, 0.5f}, 3,
                                                       false, glm::vec3(0.7f, 0.3f, 0.2f), "box"));
  prt::scene::append_scene(scene, prt::scene::make_quad({-2, 0, -2}, {4, 0, 0}, {0, 2, 0}, 8, 4,
                                                        glm::vec3(0.2f, 0.5f, 0.6f), "wall"));
  return scene;
}

}  // namespace

TEST_CASE("textures: a uniform texture of value ρ bakes and renders as a flat albedo ρ") {
  // Fixed Jacobi bounces make both systems exact polynomials in the same sampled H: the folded
  // T = Σ_i (ρH)^i ρS and the kept-apart G = Σ_i (Hρ)^i S satisfy T = ρ·G identically, so only
  // float round-off separates them (float32 coefficients: ~1e-7 relative; 2e-5 allowed for the
  // 8 bounces' sums and the kernels' float accumulation).
  const glm::vec3 rho(0.6f, 0.45f, 0.3f);
  const Scene flat = ground_box_wall(rho, false);
  const Scene textured = ground_box_wall(rho, true);
  REQUIRE(textured.textured());
  for (const auto kind : {prt::TransferKind::Shadowed, prt::TransferKind::Interreflected}) {
    const prt::bake::BakeResult f = bake(flat, kind, 128, 8);
    const prt::bake::BakeResult t = bake(textured, kind, 128, 8);
    INFO(prt::transfer_kind_name(kind));
    CHECK(f.data.albedo_folded);
    CHECK_FALSE(t.data.albedo_folded);
    CHECK(t.data.channels == (kind == prt::TransferKind::Shadowed ? 1u : 3u));
    const prt::ShLighting lighting = uneven_sky(3);
    const std::vector<float> bf = shade(f.data, lighting), bt = shade(t.data, lighting);
    double worst = 0.0, largest = 0.0;
    for (std::size_t v = 0; v < flat.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c) {
        const double want = bf[3 * v + c], got = textured.albedo[v][c] * bt[3 * v + c];
        worst = std::max(worst, std::fabs(got - want));
        largest = std::max(largest, std::fabs(want));
      }
    CHECK(worst <= 2e-5 * largest);

    // The pictures: folded radiance rendered as it is, kept-apart radiance × albedo per pixel.
    prt::relight::RenderOptions ro;
    ro.width = 48;
    ro.height = 32;
    ro.samples_per_axis = 2;
    const prt::relight::Camera camera{{2.5f, 2.f, 3.f}, {0.f, 0.3f, 0.f}, {0, 1, 0}, 0.8f};
    const prt::scene::RayCaster cf(flat), ct(textured);
    const prt::relight::Image a =
        prt::relight::render(flat, cf, bf, nullptr, prt::relight::kIdentityRotation, camera, ro);
    ro.multiply_albedo = true;
    const prt::relight::Image b = prt::relight::render(textured, ct, bt, nullptr,
                                                       prt::relight::kIdentityRotation, camera, ro);
    double pixel_worst = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
      pixel_worst = std::max(pixel_worst, static_cast<double>(std::fabs(a.rgb[i] - b.rgb[i])));
    CHECK(pixel_worst <= 2e-5 * largest);
  }
}

TEST_CASE("textures: a two-colour texture on a 4-vertex quad is applied per pixel") {
  // The quad y = 0, x and z in [0, 1], one cell (4 vertices): texture coordinates (x, z) (from
  // make_quad: s along edge_u = +X, t along edge_v = +Z). Under a white sky of radiance 1 an
  // open surface's exit radiance equals its albedo (order-3 SH of a constant is exact). Per
  // vertex the two colours would be interpolated into a ramp across the whole quad; per pixel
  // each half keeps its colour up to the bilinear filter's half-texel blend at the seam.
  const glm::vec3 left(0.8f, 0.1f, 0.1f), right(0.1f, 0.2f, 0.9f);
  constexpr int kTexels = 16;
  const float half_texel = 0.5f / kTexels;
  for (const bool repeat : {false, true}) {
    Scene scene = prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 1, 1, glm::vec3(0.5f));
    // make_quad's front is cross(+X, +Z) = −Y; the quad is seen from below, by a camera at y < 0.
    REQUIRE(scene.vertex_count() == 4);
    BaseColorTexture t;
    t.image = halves(kTexels, kTexels, left, right);
    t.sampler.wrap_s =
        repeat ? prt::scene::TextureWrap::Repeat : prt::scene::TextureWrap::ClampToEdge;
    scene.primitives[0].base_color_texture = t;
    // Coordinates s = 2x: REPEAT shows left, right, left, right; CLAMP left then right to the end.
    for (glm::vec2& uv : scene.texcoords) uv.x *= 2.f;
    const prt::bake::BakeResult baked = bake(scene, prt::TransferKind::Shadowed, 16, 0);
    REQUIRE_FALSE(baked.data.albedo_folded);
    const std::vector<float> shading = shade(baked.data, white_sky(3));
    for (float s : shading) REQUIRE(s == Approx(1.0f).margin(1e-5));

    prt::relight::RenderOptions ro;
    ro.width = 64;
    ro.height = 64;
    ro.samples_per_axis = 1;
    ro.multiply_albedo = true;
    const prt::relight::Camera camera{{0.5f, -1.2f, 0.5f}, {0.5f, 0.f, 0.5f}, {0, 0, 1}, 0.9f};
    const prt::scene::RayCaster caster(scene);
    const prt::relight::Image image = prt::relight::render(
        scene, caster, shading, nullptr, prt::relight::kIdentityRotation, camera, ro);
    const prt::relight::CameraBasis basis = prt::relight::make_camera_basis(camera, 1.f);
    int checked = 0, on_ramp_would_fail = 0;
    for (int row = 0; row < ro.height; ++row)
      for (int col = 0; col < ro.width; ++col) {
        // The pixel centre's ray, intersected with the plane y = 0 here.
        const float nx =
            2.f * (static_cast<float>(col) + 0.5f) / static_cast<float>(ro.width) - 1.f;
        const float ny =
            1.f - 2.f * (static_cast<float>(row) + 0.5f) / static_cast<float>(ro.height);
        const glm::vec3 d = prt::relight::ray_direction(basis, nx, ny);
        const glm::vec3 p = camera.eye + d * (-camera.eye.y / d.y);
        if (p.x < 0.02f || p.x > 0.98f || p.z < 0.02f || p.z > 0.98f) continue;
        const float s = 2.f * p.x;  // texture coordinate
        const float f = repeat ? s - std::floor(s) : std::min(s, 1.f);
        // Skip the blend zones: half a texel around each seam (and the wrap at s = 1 for REPEAT).
        const bool near_seam = std::fabs(f - 0.5f) < half_texel + 0.01f ||
                               (repeat && (f < half_texel + 0.01f || f > 1.f - half_texel - 0.01f));
        if (near_seam) continue;
        const glm::vec3 want = f < 0.5f ? left : right;
        const float* got = &image.rgb[3 * (static_cast<std::size_t>(row) * ro.width + col)];
        INFO("pixel " << col << "," << row << " x " << p.x << " s " << s);
        for (int c = 0; c < 3; ++c) REQUIRE(got[c] == Approx(want[c]).margin(2e-5));
        ++checked;
        // Per-vertex shading would show the corners' albedo (the texture at each corner)
        // interpolated instead: along x, from corner (0, 0) to corner (1, 0).
        const glm::vec3 ramp =
            glm::mix(t.albedo(scene.texcoords[0]), t.albedo(scene.texcoords[1]), p.x);
        if (glm::length(ramp - want) > 0.05f) ++on_ramp_would_fail;
      }
    INFO((repeat ? "REPEAT" : "CLAMP_TO_EDGE"));
    CHECK(checked > 2000);
    CHECK(on_ramp_would_fail > checked / 4);
  }
}

TEST_CASE("textures: a textured wall bleeds onto the floor like a flat wall of its mean colour") {
  // A floor (flat grey) and a wall along its back edge, textured with a fine checker of a red and
  // a blue (32 × 32 squares: every floor vertex's rays hit many squares), against the same wall
  // flat at the checker's mean. Same seed: the same rays hit the same points, so the floor's
  // difference d_v is (ρ_floor/N)·Σ_hits b·(ρ_texture(hit) − mean)·G_wall(hit)·L — zero-mean
  // noise from where the rays happen to land. The mean of d over the floor must lie within 4
  // standard errors (measured from d's spread over the vertices) of 0; a flat wall of either
  // checker colour instead must be far outside that band (the test can fail). The floor's row
  // along the wall's foot is left out: those vertices lie in the wall's plane, half their rays
  // hit the wall within a ray offset of the vertex, so they see the colour at that one point of
  // the texture, not its mean (with the checker's seams on the vertices, ~5% off; physically
  // right, but not what this test compares).
  const glm::vec3 red(0.85f, 0.1f, 0.1f), blue(0.1f, 0.1f, 0.85f), mean = 0.5f * (red + blue);
  std::vector<float> rgb;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const glm::vec3 c = ((i / 2 + j / 2) % 2) ? red : blue;
      rgb.insert(rgb.end(), {c.x, c.y, c.z});
    }
  const auto checker =
      std::make_shared<const TextureImage>(TextureImage::from_linear_rgb(64, 64, rgb, "checker"));
  const auto make = [&](glm::vec3 wall_albedo, bool textured) {
    Scene scene =
        prt::scene::make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 16, 16, glm::vec3(0.5f), "floor");
    Scene wall =
        prt::scene::make_quad({-1, 0, -1}, {2, 0, 0}, {0, 1, 0}, 16, 8, wall_albedo, "wall");
    if (textured) {
      BaseColorTexture t;
      t.image = checker;
      t.sampler.nearest_magnification = true;  // crisp squares: the mean is exactly the mid colour
      wall.primitives[0].base_color_texture = t;
      for (glm::vec3& a : wall.albedo) a = mean;
    }
    prt::scene::append_scene(scene, wall);
    return scene;
  };
  const Scene textured = make(mean, true);
  const prt::ShLighting lighting = uneven_sky(3);
  const auto floor_radiance = [&](const Scene& scene) {
    prt::bake::BakeOptions o;
    o.kind = prt::TransferKind::Interreflected;
    o.order = 3;
    o.samples = 512;
    o.threads = 2;
    o.keep_albedo_apart = true;  // the same solve for every variant
    const prt::bake::BakeResult r = prt::bake::bake_transfer(scene, o, nullptr);
    const std::vector<float> b = shade(r.data, lighting);
    std::vector<glm::dvec3> out;
    for (std::size_t v = 0; v < scene.primitives[0].vertex_count; ++v)
      if (scene.positions[v].z > -0.99f)
        out.emplace_back(glm::dvec3(b[3 * v], b[3 * v + 1], b[3 * v + 2]) * 0.5);
    return out;
  };
  const std::vector<glm::dvec3> with_texture = floor_radiance(textured);
  const std::vector<glm::dvec3> with_mean = floor_radiance(make(mean, false));
  const std::vector<glm::dvec3> with_red = floor_radiance(make(red, false));
  const std::vector<glm::dvec3> with_blue = floor_radiance(make(blue, false));
  const std::size_t count = with_texture.size();
  const double n = static_cast<double>(count);
  for (int c : {0, 2}) {
    double sum = 0.0, sum2 = 0.0, bleed = 0.0, shift_red = 0.0, shift_blue = 0.0;
    for (std::size_t v = 0; v < count; ++v) {
      const double d = with_texture[v][c] - with_mean[v][c];
      sum += d;
      sum2 += d * d;
      shift_red += with_red[v][c] - with_mean[v][c];
      shift_blue += with_blue[v][c] - with_mean[v][c];
      bleed += with_mean[v][c];
    }
    const double m = sum / n, se = std::sqrt((sum2 / n - m * m) / (n - 1));
    INFO("channel " << c << ": mean difference " << m << ", standard error " << se
                    << ", mean floor radiance " << bleed / n << ", red wall shifts by "
                    << shift_red / n << ", blue wall by " << shift_blue / n);
    CHECK(std::fabs(m) <= 4 * se);
    CHECK(se < 0.01 * bleed / n);  // the tolerance is tight: under 1% of the floor's radiance
    CHECK(std::fabs(shift_red / n) > 20 * se);
    CHECK(std::fabs(shift_blue / n) > 20 * se);
  }
}
