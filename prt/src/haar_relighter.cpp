// Sparse Haar relighting; see prt/haar_relighter.h.
#include "prt/haar_relighter.h"

#include <algorithm>
#include <string>

namespace prt {

namespace {

// Accumulates Σ L̂ · stored for every kept term; the caller applies the per-vertex step.
template <class T, int kChannels>
void accumulate_terms(const HaarTransfer& t, const std::vector<T>& values,
                      const SparseLighting& lighting, float* out) {
  const uint32_t* vertices = t.vertices.data();
  const T* stored = values.data();
  for (size_t k = 0; k < lighting.index.size(); ++k) {
    const float lr = lighting.rgb[3 * k], lg = lighting.rgb[3 * k + 1],
                lb = lighting.rgb[3 * k + 2];
    if (lr == 0.0f && lg == 0.0f && lb == 0.0f) continue;
    const uint32_t i = lighting.index[k];
    const uint64_t begin = t.offsets[i], end = t.offsets[i + 1];
    for (uint64_t e = begin; e < end; ++e) {
      float* dst = out + 3 * static_cast<size_t>(vertices[e]);
      if constexpr (kChannels == 1) {
        const float v = static_cast<float>(stored[e]);
        dst[0] += lr * v;
        dst[1] += lg * v;
        dst[2] += lb * v;
      } else {
        const T* v = stored + 3 * e;
        dst[0] += lr * static_cast<float>(v[0]);
        dst[1] += lg * static_cast<float>(v[1]);
        dst[2] += lb * static_cast<float>(v[2]);
      }
    }
  }
}

template <class T>
void accumulate(const HaarTransfer& t, const std::vector<T>& values, const SparseLighting& lighting,
                float* out) {
  if (t.channels == 1) {
    accumulate_terms<T, 1>(t, values, lighting, out);
  } else {
    accumulate_terms<T, 3>(t, values, lighting, out);
  }
}

}  // namespace

Status HaarRelighter::shade(const SparseLighting& lighting, float* out_rgb) const {
  const HaarTransfer& t = transfer_;
  const size_t out_count = static_cast<size_t>(t.vertex_count) * 3;
  std::fill(out_rgb, out_rgb + out_count, 0.0f);
  if (lighting.size != t.size) {
    return Status::Error("HaarRelighter::shade: lighting cube size " +
                         std::to_string(lighting.size) + " differs from the transfer's " +
                         std::to_string(t.size));
  }
  if (lighting.rgb.size() != lighting.index.size() * 3) {
    return Status::Error("HaarRelighter::shade: lighting has " +
                         std::to_string(lighting.rgb.size()) + " values for " +
                         std::to_string(lighting.index.size()) + " indices");
  }
  const size_t index_count = t.offsets.empty() ? 0 : t.offsets.size() - 1;
  for (uint32_t i : lighting.index) {
    if (i >= index_count) {
      return Status::Error("HaarRelighter::shade: lighting index " + std::to_string(i) +
                           " is out of range");
    }
  }
  switch (t.quantization) {
    case HaarQuantization::Bits8:
      accumulate(t, t.values_i8, lighting, out_rgb);
      break;
    case HaarQuantization::Bits16:
      accumulate(t, t.values_i16, lighting, out_rgb);
      break;
    default:
      accumulate(t, t.values_f32, lighting, out_rgb);
      return Status::Ok();
  }
  for (int64_t v = 0; v < t.vertex_count; ++v) {
    const float step = t.vertex_step[v];
    out_rgb[3 * v] *= step;
    out_rgb[3 * v + 1] *= step;
    out_rgb[3 * v + 2] *= step;
  }
  return Status::Ok();
}

Status shade_dense_reference(const float* dense_transfer, int64_t vertex_count, int size,
                             int channels, const CubeMap& lighting, double* out_rgb) {
  if (lighting.size != size || !is_valid_cube_size(size) ||
      lighting.rgb.size() != static_cast<size_t>(lighting.texel_count()) * 3 ||
      (channels != 1 && channels != 3)) {
    return Status::Error("shade_dense_reference: cube size or channel count mismatch");
  }
  const size_t texels = static_cast<size_t>(lighting.texel_count());
  for (int64_t v = 0; v < vertex_count; ++v) {
    const float* t = dense_transfer + static_cast<size_t>(v) * texels * channels;
    double sum[3] = {0.0, 0.0, 0.0};
    for (size_t x = 0; x < texels; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double tv = t[x * channels + (channels == 1 ? 0 : c)];
        sum[c] += tv * static_cast<double>(lighting.rgb[3 * x + c]);
      }
    }
    for (int c = 0; c < 3; ++c) out_rgb[3 * v + c] = sum[c];
  }
  return Status::Ok();
}

}  // namespace prt
