// Sparse, quantised Haar transfer; see prt/haar/transfer.h.
#include "prt/haar/transfer.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "prt/haar/transform.h"

namespace prt {

int haar_quantization_levels(HaarQuantization quantization) noexcept {
  switch (quantization) {
    case HaarQuantization::Bits8:
      return 127;
    case HaarQuantization::Bits16:
      return 32767;
    default:
      return 0;
  }
}

double haar_quantization_error_bound(HaarQuantization quantization, double max_abs) noexcept {
  const int levels = haar_quantization_levels(quantization);
  if (levels == 0) return 0.0;
  return max_abs / (2.0 * levels) + max_abs * std::ldexp(1.0, -22);
}

namespace {
bool valid_channels(int channels) {
  return channels == 1 || channels == 3;
}
}  // namespace

SparseVertexTransfer truncate_vertex_coefficients(const float* coeffs, int size, int channels,
                                                  const HaarTransferOptions& options) {
  SparseVertexTransfer out;
  const size_t count = static_cast<size_t>(kCubeFaceCount) * size * size;
  std::vector<float> magnitude(count, 0.0f);
  float largest = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    float m = 0.0f;
    for (int c = 0; c < channels; ++c) {
      const float v = coeffs[i * channels + c];
      if (std::isfinite(v)) m = std::max(m, std::fabs(v));
    }
    magnitude[i] = m;
    largest = std::max(largest, m);
  }
  const double threshold = std::max(0.0, options.relative_threshold) * largest;
  std::vector<uint32_t> kept;
  for (size_t i = 0; i < count; ++i) {
    if (magnitude[i] > 0.0f && magnitude[i] >= threshold) kept.push_back(static_cast<uint32_t>(i));
  }
  const int64_t limit = options.max_terms_per_vertex;
  if (limit > 0 && static_cast<int64_t>(kept.size()) > limit) {
    const auto before = [&](uint32_t x, uint32_t y) {
      return magnitude[x] != magnitude[y] ? magnitude[x] > magnitude[y] : x < y;
    };
    std::nth_element(kept.begin(), kept.begin() + limit, kept.end(), before);
    kept.resize(static_cast<size_t>(limit));
    std::sort(kept.begin(), kept.end());
  }
  out.values.reserve(kept.size() * channels);
  for (uint32_t i : kept) {
    for (int c = 0; c < channels; ++c) {
      const float v = coeffs[static_cast<size_t>(i) * channels + c];
      out.values.push_back(std::isfinite(v) ? v : 0.0f);
    }
  }
  out.index = std::move(kept);
  return out;
}

Result<SparseVertexTransfer> compress_vertex_transfer(const float* dense, int size, int channels,
                                                      const HaarTransferOptions& options) {
  if (!is_valid_cube_size(size) || !valid_channels(channels)) {
    return Status::Error("compress_vertex_transfer: invalid cube size " + std::to_string(size) +
                         " or channel count " + std::to_string(channels));
  }
  const size_t face_values = static_cast<size_t>(size) * size * channels;
  std::vector<float> coeffs(dense, dense + face_values * kCubeFaceCount);
  int64_t nonfinite = 0;
  for (float& v : coeffs) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++nonfinite;
    }
  }
  for (int face = 0; face < kCubeFaceCount; ++face) {
    for (int c = 0; c < channels; ++c) {
      forward_haar_2d(coeffs.data() + face * face_values + c, size, channels);
    }
  }
  SparseVertexTransfer out = truncate_vertex_coefficients(coeffs.data(), size, channels, options);
  out.nonfinite_count = nonfinite;
  return out;
}

uint64_t HaarTransfer::stored_bytes() const {
  return offsets.size() * sizeof(uint64_t) + vertices.size() * sizeof(uint32_t) +
         values_f32.size() * sizeof(float) + values_i16.size() * sizeof(int16_t) +
         values_i8.size() * sizeof(int8_t) + vertex_step.size() * sizeof(float);
}

uint64_t HaarTransfer::dense_bytes() const {
  return static_cast<uint64_t>(vertex_count) * kCubeFaceCount * size * size * channels *
         sizeof(float);
}

float HaarTransfer::dequantized_value(uint64_t entry, int channel) const {
  const size_t k = entry * channels + channel;
  const float step = vertex_step[vertices[entry]];
  switch (quantization) {
    case HaarQuantization::Bits8:
      return static_cast<float>(values_i8[k]) * step;
    case HaarQuantization::Bits16:
      return static_cast<float>(values_i16[k]) * step;
    default:
      return values_f32[k];
  }
}

HaarTransferBuilder::HaarTransferBuilder(int size, int channels, HaarQuantization quantization)
    : size_(size), channels_(channels), quantization_(quantization) {
  if (!is_valid_cube_size(size) || !valid_channels(channels)) return;
  const size_t count = static_cast<size_t>(kCubeFaceCount) * size * size;
  list_vertices_.resize(count);
  switch (quantization) {
    case HaarQuantization::Bits8:
      list_i8_.resize(count);
      break;
    case HaarQuantization::Bits16:
      list_i16_.resize(count);
      break;
    default:
      list_f32_.resize(count);
      break;
  }
}

Status HaarTransferBuilder::add_vertex(const SparseVertexTransfer& vertex) {
  if (list_vertices_.empty()) {
    return Status::Error("HaarTransferBuilder: invalid cube size " + std::to_string(size_) +
                         " or channel count " + std::to_string(channels_));
  }
  const size_t count = vertex.index.size();
  if (vertex.values.size() != count * channels_) {
    return Status::Error("HaarTransferBuilder: vertex " + std::to_string(vertex_count_) + " has " +
                         std::to_string(vertex.values.size()) + " values for " +
                         std::to_string(count) + " indices");
  }
  for (size_t k = 0; k < count; ++k) {
    if (vertex.index[k] >= list_vertices_.size() ||
        (k > 0 && vertex.index[k] <= vertex.index[k - 1])) {
      return Status::Error("HaarTransferBuilder: vertex " + std::to_string(vertex_count_) +
                           " has wavelet indices out of range or not ascending");
    }
  }
  if (vertex_count_ >= int64_t{UINT32_MAX}) {
    return Status::Error("HaarTransferBuilder: more than 2^32-1 vertices");
  }
  const uint32_t v = static_cast<uint32_t>(vertex_count_);
  const int levels = haar_quantization_levels(quantization_);
  float step = 1.0f;
  if (levels > 0) {
    float largest = 0.0f;
    for (float x : vertex.values) {
      if (std::isfinite(x)) largest = std::max(largest, std::fabs(x));
    }
    step = static_cast<float>(static_cast<double>(largest) / levels);
  }
  for (size_t k = 0; k < count; ++k) {
    const uint32_t i = vertex.index[k];
    list_vertices_[i].push_back(v);
    for (int c = 0; c < channels_; ++c) {
      float x = vertex.values[k * channels_ + c];
      if (!std::isfinite(x)) x = 0.0f;
      if (levels == 0) {
        list_f32_[i].push_back(x);
        continue;
      }
      // round(x/step) in double, clamped to [−Q, Q] (|x| ≤ m, so the clamp only guards the
      // float rounding of step).
      const double scaled = step > 0.0f ? static_cast<double>(x) / step : 0.0;
      const long quantised =
          std::clamp(std::lround(scaled), -static_cast<long>(levels), static_cast<long>(levels));
      if (quantization_ == HaarQuantization::Bits8) {
        list_i8_[i].push_back(static_cast<int8_t>(quantised));
      } else {
        list_i16_[i].push_back(static_cast<int16_t>(quantised));
      }
    }
  }
  vertex_step_.push_back(step);
  ++vertex_count_;
  return Status::Ok();
}

namespace {
// Appends each list to `flat`, releasing the list as it goes (peak memory ≈ one copy).
template <class T>
void flatten_lists(std::vector<std::vector<T>>& lists, std::vector<T>* flat) {
  size_t total = 0;
  for (const auto& list : lists) total += list.size();
  flat->reserve(total);
  for (auto& list : lists) {
    flat->insert(flat->end(), list.begin(), list.end());
    std::vector<T>().swap(list);
  }
  lists.clear();
}
}  // namespace

Result<HaarTransfer> HaarTransferBuilder::finish() {
  if (list_vertices_.empty()) {
    return Status::Error("HaarTransferBuilder: invalid cube size " + std::to_string(size_) +
                         " or channel count " + std::to_string(channels_));
  }
  HaarTransfer out;
  out.size = size_;
  out.channels = channels_;
  out.vertex_count = vertex_count_;
  out.quantization = quantization_;
  out.offsets.resize(list_vertices_.size() + 1, 0);
  for (size_t i = 0; i < list_vertices_.size(); ++i) {
    out.offsets[i + 1] = out.offsets[i] + list_vertices_[i].size();
  }
  flatten_lists(list_vertices_, &out.vertices);
  flatten_lists(list_f32_, &out.values_f32);
  flatten_lists(list_i16_, &out.values_i16);
  flatten_lists(list_i8_, &out.values_i8);
  out.vertex_step = std::move(vertex_step_);
  vertex_step_.clear();
  vertex_count_ = 0;
  return out;
}

}  // namespace prt
