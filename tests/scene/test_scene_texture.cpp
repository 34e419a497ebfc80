// Base-colour texture sampling (scene/texture.h) against values worked out by hand: the sRGB
// curve, texel centres, bilinear midpoints, the three wrap modes, nearest filtering, and the mip
// chain's means.
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "scene/procedural_mesh.h"
#include "scene/scene.h"
#include "scene/texture.h"

using prt::scene::TextureImage;
using prt::scene::TextureSampler;
using prt::scene::TextureWrap;

namespace {

// A 2×2 texture whose texels all differ: red = (1 + i + 2j)/8, green = 2·red, blue = j ? ½ : ¼.
TextureImage two_by_two() {
  std::vector<float> rgb;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const float r = static_cast<float>(1 + i + 2 * j) / 8.f;
      rgb.insert(rgb.end(), {r, 2.f * r, j ? 0.5f : 0.25f});
    }
  return TextureImage::from_linear_rgb(2, 2, rgb, "2x2");
}

glm::vec3 texel(int i, int j) {
  const float r = static_cast<float>(1 + i + 2 * j) / 8.f;
  return {r, 2.f * r, j ? 0.5f : 0.25f};
}

void check_near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-6f) {
  INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z
           << ")");
  CHECK(std::fabs(a.x - b.x) <= tolerance);
  CHECK(std::fabs(a.y - b.y) <= tolerance);
  CHECK(std::fabs(a.z - b.z) <= tolerance);
}

}  // namespace

TEST_CASE("sRGB decoding follows IEC 61966-2-1 (linear toe, 2.4 power above 0.04045)") {
  CHECK(prt::scene::srgb_to_linear(0.0) == 0.0);
  CHECK(prt::scene::srgb_to_linear(1.0) == Approx(1.0).epsilon(1e-12));
  CHECK(prt::scene::srgb_to_linear(0.04045) == Approx(0.04045 / 12.92).epsilon(1e-12));
  // 0.5 encoded is 0.21404 linear (the standard's curve, not 0.5^2.2 = 0.2176).
  CHECK(prt::scene::srgb_to_linear(0.5) == Approx(0.214041140).epsilon(1e-8));
  CHECK(prt::scene::srgb_to_linear(-0.2) == 0.0);
  CHECK(prt::scene::srgb_to_linear(std::nan("")) == 0.0);
}

TEST_CASE("texture: texel centres give the texel, midpoints the mean of two (bilinear)") {
  const TextureImage t = two_by_two();
  const TextureSampler s;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      check_near(
          t.sample({(static_cast<float>(i) + 0.5f) / 2.f, (static_cast<float>(j) + 0.5f) / 2.f}, s),
          texel(i, j));
  // Between the centres of (0,0) and (1,0): their mean; the image centre: the mean of all four.
  check_near(t.sample({0.5f, 0.25f}, s), 0.5f * (texel(0, 0) + texel(1, 0)));
  check_near(t.sample({0.5f, 0.5f}, s),
             0.25f * (texel(0, 0) + texel(1, 0) + texel(0, 1) + texel(1, 1)));
  // A quarter of the way from centre (0,0) to centre (1,0).
  check_near(t.sample({0.375f, 0.25f}, s), 0.75f * texel(0, 0) + 0.25f * texel(1, 0));
}

TEST_CASE("texture: REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT, per axis") {
  const TextureImage t = two_by_two();
  TextureSampler repeat, clamp, mirror;
  clamp.wrap_s = clamp.wrap_t = TextureWrap::ClampToEdge;
  mirror.wrap_s = mirror.wrap_t = TextureWrap::MirroredRepeat;
  // u = 1.25: repeat → 0.25 (texel 0); mirrored → 0.75 (texel 1); clamp → the last texel (1).
  check_near(t.sample({1.25f, 0.25f}, repeat), texel(0, 0));
  check_near(t.sample({1.25f, 0.25f}, mirror), texel(1, 0));
  check_near(t.sample({1.25f, 0.25f}, clamp), texel(1, 0));
  // Far outside, negative: u = -3.75 ≡ 0.25 under repeat; clamp gives texel 0.
  check_near(t.sample({-3.75f, 0.75f}, repeat), texel(0, 1));
  check_near(t.sample({-3.75f, 0.75f}, clamp), texel(0, 1));
  // The corner (0, 0): repeat blends the four texels (its neighbours wrap around), clamp gives
  // texel (0, 0) alone.
  check_near(t.sample({0.f, 0.f}, repeat),
             0.25f * (texel(0, 0) + texel(1, 0) + texel(0, 1) + texel(1, 1)));
  check_near(t.sample({0.f, 0.f}, clamp), texel(0, 0));
  // Mixed: clamp in u, repeat in v.
  TextureSampler mixed;
  mixed.wrap_s = TextureWrap::ClampToEdge;
  check_near(t.sample({-1.f, 1.75f}, mixed), texel(0, 1));
  // A repeat count in the millions keeps its fraction (coordinates taken in double).
  check_near(t.sample({1048576.25f, 0.25f}, repeat), texel(0, 0));
  // Non-finite coordinates read (0, 0); absurdly large ones read a texel, without overflow.
  check_near(t.sample({std::nanf(""), 0.f}, repeat), t.sample({0.f, 0.f}, repeat));
  const glm::vec3 far = t.sample({3e38f, -3e38f}, mirror);
  CHECK(std::isfinite(far.x + far.y + far.z));
}

TEST_CASE("texture: NEAREST magnification returns whole texels") {
  const TextureImage t = two_by_two();
  TextureSampler nearest;
  nearest.nearest_magnification = true;
  check_near(t.sample({0.49f, 0.01f}, nearest), texel(0, 0));
  check_near(t.sample({0.51f, 0.99f}, nearest), texel(1, 1));
}

TEST_CASE("texture: mip levels keep the mean (odd sizes too), a huge footprint reads the mean") {
  for (const auto& [w, h] : {std::pair{8, 8}, std::pair{5, 3}, std::pair{7, 1}, std::pair{1, 6}}) {
    std::vector<float> rgb;
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < w * h; ++k) {
      const float v[3] = {static_cast<float>((k * 37) % 11) / 11.f, static_cast<float>(k % 3) / 3.f,
                          0.5f};
      for (int c = 0; c < 3; ++c) sum[c] += v[c];
      rgb.insert(rgb.end(), v, v + 3);
    }
    const TextureImage t = TextureImage::from_linear_rgb(w, h, rgb, "odd");
    INFO(w << "x" << h);
    const glm::vec3 mean(static_cast<float>(sum[0] / (w * h)), static_cast<float>(sum[1] / (w * h)),
                         static_cast<float>(sum[2] / (w * h)));
    check_near(glm::vec3(t.mean()), mean, 1e-6f);
    for (const TextureImage::Level& level : t.levels()) {
      double s[3] = {0, 0, 0};
      for (std::size_t i = 0; i < level.rgb.size(); ++i) s[i % 3] += level.rgb[i];
      const double n = static_cast<double>(level.width) * level.height;
      check_near(glm::vec3(s[0] / n, s[1] / n, s[2] / n), mean, 1e-5f);
    }
    CHECK(t.levels().back().width == 1);
    CHECK(t.levels().back().height == 1);
    check_near(t.sample({0.3f, 0.6f}, TextureSampler{}, 1e6f), mean, 1e-5f);
    // Without mipmaps the footprint is ignored (level 0, bilinear).
    TextureSampler no_mips;
    no_mips.mipmaps = false;
    check_near(t.sample({0.3f, 0.6f}, no_mips, 1e6f), t.sample({0.3f, 0.6f}, no_mips), 0.f);
  }
}

TEST_CASE("texture: trilinear blends the two levels around log2(footprint · size)") {
  // 4×4 checker of 0 and 1: level 1 (2×2) is all 0.5.
  std::vector<float> rgb;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const float v = static_cast<float>((i + j) % 2);
      rgb.insert(rgb.end(), {v, v, v});
    }
  const TextureImage t = TextureImage::from_linear_rgb(4, 4, rgb, "checker");
  const glm::vec2 centre_of_texel_00(0.125f, 0.125f);
  const TextureSampler s;
  check_near(t.sample(centre_of_texel_00, s, 0.f), glm::vec3(0.f));    // level 0
  check_near(t.sample(centre_of_texel_00, s, 0.25f), glm::vec3(0.f));  // λ = 0: still level 0
  check_near(t.sample(centre_of_texel_00, s, 0.5f), glm::vec3(0.5f));  // λ = 1: level 1
  // λ = 0.5: halfway between level 0 (0) and level 1 (0.5).
  check_near(t.sample(centre_of_texel_00, s, std::sqrt(2.f) * 0.25f), glm::vec3(0.25f), 1e-6f);
}

TEST_CASE("textured albedo = factor × texture, clamped to kMaxTexturedAlbedo") {
  prt::scene::BaseColorTexture b;
  b.image = std::make_shared<const TextureImage>(
      TextureImage::from_linear_rgb(1, 1, {1.f, 0.5f, 0.2f}, "one"));
  b.factor = glm::vec3(0.5f, 1.f, 2.f);
  check_near(b.albedo({0.3f, 0.3f}), glm::vec3(0.5f, 0.5f, 0.4f));
  b.factor = glm::vec3(1.f);
  check_near(b.albedo({0.3f, 0.3f}), glm::vec3(prt::scene::kMaxTexturedAlbedo, 0.5f, 0.2f));
}

TEST_CASE("Scene::albedo_at: flat primitives interpolate vertex albedo, textured ones sample") {
  // Two quads side by side: the left flat red-ish, the right textured with a 1×2 image.
  prt::scene::Scene s = prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1,
                                              glm::vec3(0.3f, 0.2f, 0.1f), "flat");
  prt::scene::Scene right =
      prt::scene::make_quad({1, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1, glm::vec3(0.5f), "textured");
  prt::scene::BaseColorTexture tex;
  tex.image = std::make_shared<const TextureImage>(
      TextureImage::from_linear_rgb(1, 2, {0.1f, 0.2f, 0.3f, 0.7f, 0.6f, 0.5f}, "1x2"));
  tex.sampler.nearest_magnification = true;
  right.primitives[0].base_color_texture = tex;
  prt::scene::append_scene(s, right);
  REQUIRE(s.texcoords.size() == s.positions.size());
  REQUIRE(s.triangles.size() == 4);
  for (uint32_t t = 0; t < 2; ++t) {
    CHECK(s.primitive_of_triangle(t)->name == "flat");
    check_near(s.albedo_at(t, 0.2f, 0.3f), glm::vec3(0.3f, 0.2f, 0.1f));
  }
  for (uint32_t t = 2; t < 4; ++t) {
    CHECK(s.primitive_of_triangle(t)->name == "textured");
    // Each textured point reads the texel row its v falls in (nearest): v < 0.5 → row 0.
    const glm::uvec3 tri = s.triangles[t];
    const float u = 0.25f, v = 0.25f;
    const glm::vec2 uv =
        (1.f - u - v) * s.texcoords[tri.x] + u * s.texcoords[tri.y] + v * s.texcoords[tri.z];
    const glm::vec3 want = uv.y < 0.5f ? glm::vec3(0.1f, 0.2f, 0.3f) : glm::vec3(0.7f, 0.6f, 0.5f);
    check_near(s.albedo_at(t, u, v), want);
  }
  CHECK(s.primitive_of_triangle(4) == nullptr);
}
