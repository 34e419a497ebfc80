// fuzz/fuzz_texture.cpp — libFuzzer target: base-colour and parameter textures as the scene
// loaders read them for the bakes (scene/texture.h): PNG or JPEG bytes → the OpenImageIO plugin
// (scene::decode_image_memory, unassociated alpha as textures read it) → TextureImage (sRGB
// colour, linear data, or alpha as grey) with its mip chain → sampling; or a raw float image
// straight into TextureImage, which reaches NaN, Inf and out-of-range samples that 8-bit files
// cannot hold.
//
// Input: byte 0 picks the source (b % 4: 0 PNG, 1 JPEG, 2 and 3 raw), the content ((b / 4) % 3:
// sRGB colour, linear, alpha) and the sampler (b / 16: wrap modes, nearest, mipmaps). Raw: bytes
// 1..3 give width 1 + b1 % 64, height 1 + b2 % 64 and channels 1 + b3 % 4; the rest are float32
// samples, zero-padded to the image's size unless b3 ≥ 128 (then a short image must be refused).
// Decoding must refuse a malformed file with a one-line runtime_error "fuzz.png: …" (images over
// 2^16 texels by the size cap); an accepted image has the announced size. Every texture must have
// the mip chain scene/texture.h describes (⌊w/2⌋ × ⌊h/2⌋, at least 1, down to 1 × 1, each level
// keeping the image's mean within 1e-4), samples in [0, 1] at every level, and sample() and
// BaseColorTexture::albedo() must return finite values in [0, 1] (albedo ≤ 0.99) for any
// coordinates and footprints, NaN and huge ones included.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "one_line_error.h"
#include "scene/image_codec.h"
#include "scene/texture.h"

namespace {

using prt::scene::FloatImage;
using prt::scene::TextureImage;

constexpr std::size_t kMaxFuzzTexels = std::size_t{1} << 16;
constexpr float kTolerance = 1e-5f;  // float rounding of a bilinear or trilinear blend

FloatImage raw_image(const uint8_t* data, std::size_t size) {
  FloatImage image;
  if (size < 3) return image;  // width 0: refused by TextureImage
  image.width = 1 + data[0] % 64;
  image.height = 1 + data[1] % 64;
  image.channels = 1 + data[2] % 4;
  const std::size_t floats = (size - 3) / 4;
  image.pixels.resize(floats);
  if (floats > 0) std::memcpy(image.pixels.data(), data + 3, floats * 4);
  const std::size_t want = static_cast<std::size_t>(image.width) * image.height *
                           static_cast<std::size_t>(image.channels);
  if (data[2] < 128 || image.pixels.size() > want) image.pixels.resize(want, 0.0f);
  return image;
}

bool in_unit(float x) {
  return std::isfinite(x) && x >= -kTolerance && x <= 1.0f + kTolerance;
}

void check_levels(const TextureImage& t, const FloatImage& image) {
  const auto& levels = t.levels();
  if (levels.empty() || levels[0].width != image.width || levels[0].height != image.height)
    std::abort();
  double mean0[3] = {0, 0, 0};
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const TextureImage::Level& l = levels[k];
    if (l.rgb.size() != 3 * static_cast<std::size_t>(l.width) * l.height) std::abort();
    if (k > 0 && (l.width != std::max(1, levels[k - 1].width / 2) ||
                  l.height != std::max(1, levels[k - 1].height / 2)))
      std::abort();
    double sum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < l.rgb.size(); ++i) {
      if (!in_unit(l.rgb[i])) std::abort();
      sum[i % 3] += l.rgb[i];
    }
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c] / (static_cast<double>(l.width) * l.height);
      if (k == 0) mean0[c] = mean;
      if (std::fabs(mean - mean0[c]) > 1e-4) std::abort();
    }
  }
  if (levels.back().width != 1 || levels.back().height != 1) std::abort();
}

void check_samples(const TextureImage& t, uint8_t selector) {
  prt::scene::BaseColorTexture texture;
  texture.image = std::make_shared<const TextureImage>(t);
  const auto wrap = [](int w) { return static_cast<prt::scene::TextureWrap>(w % 3); };
  texture.sampler.wrap_s = wrap(selector >> 4);
  texture.sampler.wrap_t = wrap((selector >> 4) / 3);
  texture.sampler.nearest_magnification = (selector & 0x40) != 0;
  texture.sampler.nearest_minification = (selector & 0x80) != 0;
  texture.sampler.mipmaps = (selector & 0x10) == 0;
  texture.factor = {1.0f, 0.5f, 2.0f};
  const float coordinates[] = {0.0f, 0.37f, 1.0f, -2.25f, 1e9f, -1e30f, NAN, INFINITY};
  const float footprints[] = {0.0f, 1e-3f, 0.1f, 0.7f, 4.0f, 1e30f, NAN, -1.0f};
  for (float u : coordinates) {
    for (float v : coordinates) {
      for (float f : footprints) {
        const glm::vec3 s = t.sample({u, v}, texture.sampler, f);
        if (!in_unit(s.x) || !in_unit(s.y) || !in_unit(s.z)) std::abort();
        const glm::vec3 a = texture.albedo({u, v}, f);
        for (int c = 0; c < 3; ++c)
          if (!(a[c] >= 0.0f && a[c] <= prt::scene::kMaxTexturedAlbedo)) std::abort();
      }
    }
  }
}

}  // namespace

// Opens the OpenImageIO plugin (and its ~250 libraries) once before the first execution, so that
// the start-up is not timed as part of one input.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const unsigned char not_png[8] = {0x89, 'P', 'N', 'G', 0, 0, 0, 0};
  try {
    prt::scene::decode_image_memory(not_png, sizeof not_png, "png", "warm-up", 1);
  } catch (const std::runtime_error&) {
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  const int source = selector % 4;
  const int content = (selector / 4) % 3;
  const std::string name = source == 1 ? "fuzz.jpg" : "fuzz.png";
  FloatImage image;
  if (source < 2) {
    prt::scene::ImageReadOptions options;
    options.unassociated_alpha = true;
    try {
      image = prt::scene::decode_image_memory(data + 1, size - 1, source == 0 ? "png" : "jpeg",
                                              name, kMaxFuzzTexels, options);
    } catch (const std::runtime_error& e) {
      prt::fuzz::check_one_line_error(e.what(), name);
      return 0;
    }
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
        static_cast<std::size_t>(image.width) * image.height > kMaxFuzzTexels ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height *
                                   static_cast<std::size_t>(image.channels))
      std::abort();
  } else {
    image = raw_image(data + 1, size - 1);
  }
  try {
    const TextureImage t = content == 2 ? TextureImage::from_image_alpha(image, name)
                                        : TextureImage::from_image(image, name, content == 0);
    check_levels(t, image);
    check_samples(t, selector);
  } catch (const std::runtime_error& e) {
    // Only a raw image that is empty or short may be refused.
    const std::size_t want = static_cast<std::size_t>(image.width) * image.height *
                             static_cast<std::size_t>(image.channels);
    if (source < 2 || (image.width > 0 && image.pixels.size() >= want)) std::abort();
    prt::fuzz::check_one_line_error(e.what(), name);
  }
  return 0;
}
