// scene/src/texture.cpp — linearisation, the box-filtered mip chain and filtered sampling of
// base-colour textures (see scene/texture.h).
#include "scene/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace prt::scene {
namespace {

// Texel index `i` of a row or column of `n` texels under a wrap mode.
int wrap_index(long long i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::ClampToEdge:
      return static_cast<int>(std::clamp<long long>(i, 0, n - 1));
    case TextureWrap::MirroredRepeat: {
      const long long period = 2LL * n;
      long long m = i % period;
      if (m < 0) m += period;
      return static_cast<int>(m < n ? m : period - 1 - m);
    }
    default: {
      long long m = i % n;
      if (m < 0) m += n;
      return static_cast<int>(m);
    }
  }
}

// One texel of a level (indices already wrapped).
glm::vec3 texel(const TextureImage::Level& level, int i, int j) {
  const float* p = &level.rgb[3 * (static_cast<std::size_t>(j) * level.width + i)];
  return glm::vec3(p[0], p[1], p[2]);
}

// Coordinates are taken in double so that large repeat counts keep their fraction.
glm::vec3 sample_nearest(const TextureImage::Level& level, double u, double v,
                         const TextureSampler& s) {
  const int i =
      wrap_index(static_cast<long long>(std::floor(u * level.width)), level.width, s.wrap_s);
  const int j =
      wrap_index(static_cast<long long>(std::floor(v * level.height)), level.height, s.wrap_t);
  return texel(level, i, j);
}

glm::vec3 sample_bilinear(const TextureImage::Level& level, double u, double v,
                          const TextureSampler& s) {
  const double x = u * level.width - 0.5, y = v * level.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const auto xi = static_cast<long long>(x0), yi = static_cast<long long>(y0);
  const int i0 = wrap_index(xi, level.width, s.wrap_s),
            i1 = wrap_index(xi + 1, level.width, s.wrap_s);
  const int j0 = wrap_index(yi, level.height, s.wrap_t),
            j1 = wrap_index(yi + 1, level.height, s.wrap_t);
  const glm::vec3 top = glm::mix(texel(level, i0, j0), texel(level, i1, j0), fx);
  const glm::vec3 bottom = glm::mix(texel(level, i0, j1), texel(level, i1, j1), fx);
  return glm::mix(top, bottom, fy);
}

// Box-filters `n` samples (stride `stride` floats apart, 3 channels each) down to `m` <= n:
// output k averages the input interval [k·n/m, (k+1)·n/m) with fractional end weights.
void box_reduce(const float* in, int n, std::size_t stride, float* out, int m,
                std::size_t out_stride) {
  const double scale = static_cast<double>(n) / m;
  for (int k = 0; k < m; ++k) {
    const double lo = k * scale, hi = (k + 1) * scale;
    double sum[3] = {0, 0, 0};
    for (int i = static_cast<int>(std::floor(lo)); i < n && i < hi; ++i) {
      const double w = std::min<double>(i + 1, hi) - std::max<double>(i, lo);
      if (w <= 0.0) continue;
      for (int c = 0; c < 3; ++c) sum[c] += w * in[static_cast<std::size_t>(i) * stride + c];
    }
    for (int c = 0; c < 3; ++c)
      out[static_cast<std::size_t>(k) * out_stride + c] = static_cast<float>(sum[c] / scale);
  }
}

TextureImage::Level next_level(const TextureImage::Level& a) {
  TextureImage::Level wide;  // columns reduced
  wide.width = std::max(1, a.width / 2);
  wide.height = a.height;
  wide.rgb.resize(3 * static_cast<std::size_t>(wide.width) * wide.height);
  for (int j = 0; j < a.height; ++j)
    box_reduce(&a.rgb[3 * static_cast<std::size_t>(j) * a.width], a.width, 3,
               &wide.rgb[3 * static_cast<std::size_t>(j) * wide.width], wide.width, 3);
  TextureImage::Level b;  // then rows
  b.width = wide.width;
  b.height = std::max(1, a.height / 2);
  b.rgb.resize(3 * static_cast<std::size_t>(b.width) * b.height);
  for (int i = 0; i < b.width; ++i)
    box_reduce(&wide.rgb[3 * static_cast<std::size_t>(i)], wide.height, 3 * std::size_t(b.width),
               &b.rgb[3 * static_cast<std::size_t>(i)], b.height, 3 * std::size_t(b.width));
  return b;
}

}  // namespace

double srgb_to_linear(double encoded) {
  if (!(encoded > 0.0)) return 0.0;  // NaN and negatives as 0
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

TextureImage TextureImage::from_image(const FloatImage& image, std::string name,
                                      bool srgb_encoded) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() < static_cast<std::size_t>(image.width) * image.height *
                                static_cast<std::size_t>(image.channels))
    throw std::runtime_error(name + ": the texture image is empty or truncated");
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  std::vector<float> rgb(3 * texels);
  const int channels = image.channels;
  for (std::size_t t = 0; t < texels; ++t) {
    const float* in = &image.pixels[t * static_cast<std::size_t>(channels)];
    for (int c = 0; c < 3; ++c) {
      const double encoded =
          std::clamp(static_cast<double>(channels >= 3 ? in[c] : in[0]), 0.0, 1.0);
      rgb[3 * t + static_cast<std::size_t>(c)] =
          static_cast<float>(srgb_encoded ? srgb_to_linear(encoded) : encoded);
    }
  }
  return from_linear_rgb(image.width, image.height, std::move(rgb), std::move(name));
}

TextureImage TextureImage::from_image_alpha(const FloatImage& image, std::string name) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() < static_cast<std::size_t>(image.width) * image.height *
                                static_cast<std::size_t>(image.channels))
    throw std::runtime_error(name + ": the texture image is empty or truncated");
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  const int channels = image.channels;
  const bool has_alpha = channels == 2 || channels >= 4;
  std::vector<float> rgb(3 * texels, 1.f);
  for (std::size_t t = 0; t < texels && has_alpha; ++t) {
    const float a = image.pixels[t * static_cast<std::size_t>(channels) +
                                 static_cast<std::size_t>(channels == 2 ? 1 : 3)];
    const float clamped = std::isfinite(a) ? std::clamp(a, 0.f, 1.f) : 0.f;
    for (std::size_t c = 0; c < 3; ++c) rgb[3 * t + c] = clamped;
  }
  return from_linear_rgb(image.width, image.height, std::move(rgb), std::move(name));
}

TextureImage TextureImage::from_linear_rgb(int width, int height, std::vector<float> rgb,
                                           std::string name) {
  if (width <= 0 || height <= 0 || rgb.size() != 3 * static_cast<std::size_t>(width) * height)
    throw std::runtime_error(name + ": texture size and sample count disagree");
  TextureImage t;
  t.name_ = std::move(name);
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    for (int c = 0; c < 3; ++c) {
      float& x = rgb[i + static_cast<std::size_t>(c)];
      if (!std::isfinite(x) || x < 0.f) x = 0.f;
      sum[c] += x;
      t.maximum_[c] = std::max(t.maximum_[c], x);
    }
    t.grey_ = t.grey_ && rgb[i] == rgb[i + 1] && rgb[i + 1] == rgb[i + 2];
  }
  t.mean_ = sum / (static_cast<double>(width) * height);
  t.levels_.push_back(Level{width, height, std::move(rgb)});
  while (t.levels_.back().width > 1 || t.levels_.back().height > 1)
    t.levels_.push_back(next_level(t.levels_.back()));
  return t;
}

glm::vec3 TextureImage::sample(glm::vec2 uv, const TextureSampler& sampler, float footprint) const {
  // Non-finite coordinates read (0, 0); huge ones are held to ±2^30 (a float there has no
  // fraction left anyway) so that texel indices fit in 64 bits.
  const auto coordinate = [](float x) {
    return std::isfinite(x) ? std::clamp(static_cast<double>(x), -0x1p30, 0x1p30) : 0.0;
  };
  const double u = coordinate(uv.x), v = coordinate(uv.y);
  const double texels = static_cast<double>(std::max(width(), height()));
  const double lambda =
      footprint > 0.f && std::isfinite(footprint) ? std::log2(footprint * texels) : -1.0;
  if (lambda <= 0.0 || !sampler.mipmaps) {
    const bool nearest =
        lambda <= 0.0 ? sampler.nearest_magnification : sampler.nearest_minification;
    return nearest ? sample_nearest(levels_.front(), u, v, sampler)
                   : sample_bilinear(levels_.front(), u, v, sampler);
  }
  const double last = static_cast<double>(levels_.size() - 1);
  const double level = std::min(lambda, last);
  const auto k = static_cast<std::size_t>(std::floor(level));
  const auto blend = static_cast<float>(level - static_cast<double>(k));
  const auto at = [&](std::size_t i) {
    return sampler.nearest_minification ? sample_nearest(levels_[i], u, v, sampler)
                                        : sample_bilinear(levels_[i], u, v, sampler);
  };
  if (blend == 0.f || k + 1 >= levels_.size()) return at(k);
  return glm::mix(at(k), at(k + 1), blend);
}

glm::vec3 BaseColorTexture::albedo(glm::vec2 uv, float footprint) const {
  const glm::vec3 texture = image ? image->sample(uv, sampler, footprint) : glm::vec3(1.f);
  return glm::clamp(factor * texture, glm::vec3(0.f), glm::vec3(kMaxTexturedAlbedo));
}

}  // namespace prt::scene
