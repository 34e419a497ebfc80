// Sparse Haar relighting; see prt/haar/relighter.h.
#include "prt/haar/relighter.h"

#include <algorithm>
#include <string>

namespace prt {

namespace {

// Checks the lighting against a transfer of cube size `size` with `index_count` wavelet indices.
Status check_lighting(const SparseLighting& lighting, int size, size_t index_count) {
  if (lighting.size != size) {
    return Status::Error("HaarRelighter::shade: lighting cube size " +
                         std::to_string(lighting.size) + " differs from the transfer's " +
                         std::to_string(size));
  }
  if (lighting.rgb.size() != lighting.index.size() * 3) {
    return Status::Error("HaarRelighter::shade: lighting has " +
                         std::to_string(lighting.rgb.size()) + " values for " +
                         std::to_string(lighting.index.size()) + " indices");
  }
  for (uint32_t i : lighting.index) {
    if (i >= index_count) {
      return Status::Error("HaarRelighter::shade: lighting index " + std::to_string(i) +
                           " is out of range");
    }
  }
  return Status::Ok();
}

// Plain list walk: accumulates Σ L̂ · stored for every kept term; the caller applies the step.
template <class T, int kChannels>
void accumulate_lists(const HaarTransfer& t, const std::vector<T>& values,
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
void accumulate_lists(const HaarTransfer& t, const std::vector<T>& values,
                      const SparseLighting& lighting, float* out) {
  if (t.channels == 1) {
    accumulate_lists<T, 1>(t, values, lighting, out);
  } else {
    accumulate_lists<T, 3>(t, values, lighting, out);
  }
}

// Dense RGB column: acc[j] += light[j mod 3] · stored[j] for j < 3·count (interleaved RGB).
// Chunks of 8 vertices (24 floats) with the lighting repeated 8 times, so the compiler
// vectorises without a modulo.
template <class T>
void axpy_dense_rgb(const float light[3], const T* stored, int64_t count, float* acc) {
  float pattern[24];
  for (int q = 0; q < 24; ++q) pattern[q] = light[q % 3];
  const int64_t n = 3 * count;
  int64_t j = 0;
  for (; j + 24 <= n; j += 24) {
    for (int q = 0; q < 24; ++q) acc[j + q] += pattern[q] * static_cast<float>(stored[j + q]);
  }
  for (; j < n; ++j) acc[j] += pattern[j % 3] * static_cast<float>(stored[j]);
}

// Dense grey column into planar accumulators r, g, b.
template <class T>
void axpy_dense_grey(const float light[3], const T* stored, int64_t count, float* r, float* g,
                     float* b) {
  const float lr = light[0], lg = light[1], lb = light[2];
  for (int64_t j = 0; j < count; ++j) {
    const float v = static_cast<float>(stored[j]);
    r[j] += lr * v;
    g[j] += lg * v;
    b[j] += lb * v;
  }
}

// Requests the cache lines of slice `index` of a block (values and offsets) ahead of use: the
// next term's slice is a fresh stream the hardware prefetcher would only pick up part-way.
template <class T, class Slot>
void prefetch_slice(const Slot* slot, uint32_t index, const T* stored, bool grey,
                    const uint16_t* offsets) {
  const Slot& s = slot[index];
  const Slot& next = (&s)[1];
  const int channels = grey ? 1 : 3;
  const char* begin = reinterpret_cast<const char*>(stored + s.entry * channels);
  const char* end = reinterpret_cast<const char*>(stored + next.entry * channels);
  for (const char* p = begin; p < end; p += 64) __builtin_prefetch(p);
  const char* obegin = reinterpret_cast<const char*>(offsets + s.offset);
  const char* oend = reinterpret_cast<const char*>(offsets + next.offset);
  for (const char* p = obegin; p < oend; p += 64) __builtin_prefetch(p);
}

}  // namespace

HaarRelighter::HaarRelighter(HaarTransfer transfer, HaarRelighterLayout layout)
    : transfer_(std::move(transfer)), layout_(layout) {
  layout_.block_vertices = std::clamp(layout_.block_vertices, 1, 65536);
  const HaarTransfer& t = transfer_;
  const size_t index_count = t.offsets.empty() ? 0 : t.offsets.size() - 1;
  const int channels = t.channels == 1 ? 1 : 3;
  const int64_t block = layout_.block_vertices;
  block_count_ = t.vertex_count <= 0 ? 0 : (t.vertex_count + block - 1) / block;
  // An inconsistent transfer (no lists, or too few vertex entries) gets an empty layout;
  // shade() then reports it.
  if (index_count == 0 || t.vertices.size() != t.offsets.back()) {
    block_count_ = 0;
    return;
  }
  const std::vector<float>* src_f32 = nullptr;
  const std::vector<int16_t>* src_i16 = nullptr;
  const std::vector<int8_t>* src_i8 = nullptr;
  switch (t.quantization) {
    case HaarQuantization::Bits8:
      src_i8 = &t.values_i8;
      break;
    case HaarQuantization::Bits16:
      src_i16 = &t.values_i16;
      break;
    default:
      src_f32 = &t.values_f32;
      break;
  }
  const size_t value_count = src_f32 ? src_f32->size() : src_i16 ? src_i16->size() : src_i8->size();
  if (value_count != t.vertices.size() * channels) {
    block_count_ = 0;
    return;
  }
  // Steps for every vertex (quantised), each list ascending and within [0, vertex_count).
  if (t.quantization != HaarQuantization::Float32 &&
      t.vertex_step.size() != static_cast<size_t>(t.vertex_count)) {
    block_count_ = 0;
    return;
  }
  for (size_t i = 0; i < index_count; ++i) {
    if (t.offsets[i] > t.offsets[i + 1]) {
      block_count_ = 0;
      return;
    }
    for (uint64_t e = t.offsets[i]; e < t.offsets[i + 1]; ++e) {
      if (t.vertices[e] >= t.vertex_count ||
          (e > t.offsets[i] && t.vertices[e] <= t.vertices[e - 1])) {
        block_count_ = 0;
        return;
      }
    }
  }
  // Appends entry e's channel values (zeros instead when `zero`) to the blocked copy.
  const auto append_entry = [&](uint64_t e, bool zero) {
    for (int c = 0; c < channels; ++c) {
      const size_t k = static_cast<size_t>(e) * channels + c;
      if (src_f32) values_f32_.push_back(zero ? 0.0f : (*src_f32)[k]);
      if (src_i16) values_i16_.push_back(zero ? int16_t{0} : (*src_i16)[k]);
      if (src_i8) values_i8_.push_back(zero ? int8_t{0} : (*src_i8)[k]);
    }
  };
  if (src_f32) values_f32_.reserve(value_count);
  if (src_i16) values_i16_.reserve(value_count);
  if (src_i8) values_i8_.reserve(value_count);
  block_offsets_.reserve(t.vertices.size());
  slots_.resize(static_cast<size_t>(block_count_) * (index_count + 1));
  std::vector<uint64_t> cursor(t.offsets.begin(), t.offsets.end() - 1);  // per index
  uint64_t entries = 0;
  for (int64_t b = 0; b < block_count_; ++b) {
    const uint64_t first = static_cast<uint64_t>(b * block);
    const uint64_t last = std::min<uint64_t>(first + block, static_cast<uint64_t>(t.vertex_count));
    const int64_t length = static_cast<int64_t>(last - first);
    Slot* slot = &slots_[static_cast<size_t>(b) * (index_count + 1)];
    for (size_t i = 0; i < index_count; ++i) {
      slot[i].entry = entries;
      slot[i].offset = block_offsets_.size();
      const uint64_t begin = cursor[i], list_end = t.offsets[i + 1];
      uint64_t end = begin;
      while (end < list_end && t.vertices[end] < last) ++end;
      cursor[i] = end;
      const uint64_t count = end - begin;
      if (count == 0) continue;
      const bool dense =
          static_cast<double>(count) >= layout_.dense_fraction * static_cast<double>(length);
      if (dense) {
        uint64_t e = begin;
        for (uint64_t v = first; v < last; ++v) {
          const bool has = e < end && t.vertices[e] == v;
          append_entry(e, !has);
          if (has) ++e;
        }
        entries += static_cast<uint64_t>(length);
        ++dense_slices_;
        dense_entries_ += static_cast<uint64_t>(length);
      } else {
        for (uint64_t e = begin; e < end; ++e) {
          append_entry(e, false);
          block_offsets_.push_back(static_cast<uint16_t>(t.vertices[e] - first));
        }
        entries += count;
      }
    }
    slot[index_count].entry = entries;
    slot[index_count].offset = block_offsets_.size();
  }
  values_f32_.shrink_to_fit();
  values_i16_.shrink_to_fit();
  values_i8_.shrink_to_fit();
  block_offsets_.shrink_to_fit();
}

uint64_t HaarRelighter::blocked_bytes() const {
  return slots_.size() * sizeof(Slot) + block_offsets_.size() * sizeof(uint16_t) +
         values_f32_.size() * sizeof(float) + values_i16_.size() * sizeof(int16_t) +
         values_i8_.size() * sizeof(int8_t) + transfer_.vertex_step.size() * sizeof(float);
}

template <class T>
void HaarRelighter::shade_blocks(const std::vector<T>& values, const SparseLighting& lighting,
                                 float* out_rgb) const {
  const HaarTransfer& t = transfer_;
  const size_t index_count = t.offsets.size() - 1;
  const bool grey = t.channels == 1;
  const bool scaled = t.quantization != HaarQuantization::Float32;
  const int64_t block = layout_.block_vertices;
  const T* stored = values.data();
  const uint16_t* offsets = block_offsets_.data();
  // Grey transfer accumulates into planar R, G, B (dense columns then vectorise); RGB transfer
  // accumulates straight into the block's part of out_rgb.
  std::vector<float> planar(grey ? 3 * static_cast<size_t>(block) : 0);
  for (int64_t b = 0; b < block_count_; ++b) {
    const int64_t first = b * block;
    const int64_t length = std::min(block, t.vertex_count - first);
    const Slot* slot = &slots_[static_cast<size_t>(b) * (index_count + 1)];
    float* acc = out_rgb + 3 * first;
    float* r = planar.data();  // the planar sums exist only for grey transfer
    float* g = grey ? r + block : nullptr;
    float* bl = grey ? g + block : nullptr;
    if (grey) {
      std::fill(r, r + length, 0.0f);
      std::fill(g, g + length, 0.0f);
      std::fill(bl, bl + length, 0.0f);
    }
    for (size_t k = 0; k < lighting.index.size(); ++k) {
      const float light[3] = {lighting.rgb[3 * k], lighting.rgb[3 * k + 1],
                              lighting.rgb[3 * k + 2]};
      if (light[0] == 0.0f && light[1] == 0.0f && light[2] == 0.0f) continue;
      if (k + 1 < lighting.index.size())
        prefetch_slice(slot, lighting.index[k + 1], stored, grey, offsets);
      const Slot& s = slot[lighting.index[k]];
      const Slot& next = (&s)[1];
      const uint64_t entry_count = next.entry - s.entry;
      if (entry_count == 0) continue;
      const uint64_t offset_count = next.offset - s.offset;
      if (offset_count == 0) {  // dense column: one value (set) per vertex of the block
        if (grey) {
          axpy_dense_grey(light, stored + s.entry, length, r, g, bl);
        } else {
          axpy_dense_rgb(light, stored + 3 * s.entry, length, acc);
        }
        continue;
      }
      const uint16_t* o = offsets + s.offset;
      if (grey) {
        const T* v = stored + s.entry;
        for (uint64_t e = 0; e < entry_count; ++e) {
          const float x = static_cast<float>(v[e]);
          const uint16_t j = o[e];
          r[j] += light[0] * x;
          g[j] += light[1] * x;
          bl[j] += light[2] * x;
        }
      } else {
        const T* v = stored + 3 * s.entry;
        for (uint64_t e = 0; e < entry_count; ++e) {
          float* dst = acc + 3 * static_cast<size_t>(o[e]);
          dst[0] += light[0] * static_cast<float>(v[3 * e]);
          dst[1] += light[1] * static_cast<float>(v[3 * e + 1]);
          dst[2] += light[2] * static_cast<float>(v[3 * e + 2]);
        }
      }
    }
    const float* step = t.vertex_step.data() + first;
    if (grey) {
      for (int64_t j = 0; j < length; ++j) {
        const float m = scaled ? step[j] : 1.0f;
        acc[3 * j] = r[j] * m;
        acc[3 * j + 1] = g[j] * m;
        acc[3 * j + 2] = bl[j] * m;
      }
    } else if (scaled) {
      for (int64_t j = 0; j < length; ++j) {
        acc[3 * j] *= step[j];
        acc[3 * j + 1] *= step[j];
        acc[3 * j + 2] *= step[j];
      }
    }
  }
}

Status HaarRelighter::shade(const SparseLighting& lighting, float* out_rgb) const {
  const HaarTransfer& t = transfer_;
  const size_t out_count = static_cast<size_t>(t.vertex_count) * 3;
  std::fill(out_rgb, out_rgb + out_count, 0.0f);
  const size_t index_count = t.offsets.empty() ? 0 : t.offsets.size() - 1;
  const Status ok = check_lighting(lighting, t.size, index_count);
  if (!ok.ok()) return ok;
  if (t.vertex_count > 0 && block_count_ == 0) {
    return Status::Error("HaarRelighter::shade: the transfer's lists are inconsistent");
  }
  switch (t.quantization) {
    case HaarQuantization::Bits8:
      shade_blocks(values_i8_, lighting, out_rgb);
      break;
    case HaarQuantization::Bits16:
      shade_blocks(values_i16_, lighting, out_rgb);
      break;
    default:
      shade_blocks(values_f32_, lighting, out_rgb);
      break;
  }
  return Status::Ok();
}

Status shade_index_lists(const HaarTransfer& t, const SparseLighting& lighting, float* out_rgb) {
  const size_t out_count = static_cast<size_t>(t.vertex_count) * 3;
  std::fill(out_rgb, out_rgb + out_count, 0.0f);
  const size_t index_count = t.offsets.empty() ? 0 : t.offsets.size() - 1;
  const Status ok = check_lighting(lighting, t.size, index_count);
  if (!ok.ok()) return ok;
  switch (t.quantization) {
    case HaarQuantization::Bits8:
      accumulate_lists(t, t.values_i8, lighting, out_rgb);
      break;
    case HaarQuantization::Bits16:
      accumulate_lists(t, t.values_i16, lighting, out_rgb);
      break;
    default:
      accumulate_lists(t, t.values_f32, lighting, out_rgb);
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
