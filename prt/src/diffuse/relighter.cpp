// relighter.cpp — the blocked shading kernel; see prt/diffuse/relighter.h.
//
// This file is compiled with -ffp-contract=off (prt/CMakeLists.txt) so that no path fuses
// the multiply and the add: the AVX2 and the portable paths then round identically.
#include "prt/diffuse/relighter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "core/cpu_features.h"
#include "formats/binary_layout.h"
#include "prt/core/half.h"
#include "prt/formats/transfer_file.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {
namespace {

constexpr std::size_t kLanes = kVertexBlock;  // 16
constexpr std::size_t kAlignment = 64;

struct AlignedFree {
  void operator()(unsigned char* p) const { ::operator delete[](p, std::align_val_t(kAlignment)); }
};
using AlignedBytes = std::unique_ptr<unsigned char[], AlignedFree>;

AlignedBytes allocate_aligned(std::size_t n) {
  return AlignedBytes(static_cast<unsigned char*>(
      ::operator new[](std::max<std::size_t>(n, 1), std::align_val_t(kAlignment), std::nothrow)));
}

}  // namespace

struct Relighter::Impl {
  std::size_t vertex_count = 0;
  int order = 1;
  int channels = 1;
  Precision storage = Precision::F32;
  std::size_t bytes = 0;
  AlignedBytes coefficients;  // blocked layout

  int k_count() const { return order * order; }
};

namespace {

using Impl = Relighter::Impl;

// Per-call kernel arguments.
struct KernelArgs {
  const unsigned char* coefficients;
  int channels;
  int k_stride;  // order_file²
  int k_used;    // min(order_file, order_light)²
  const float* light[3];
  std::size_t first;
  std::size_t count;
  float* out_rgb;
};

// Copies the lanes of one finished block that fall in the requested range, interleaving RGB.
inline void write_block(const KernelArgs& a, std::size_t block, const float (&acc)[3][kLanes]) {
  const std::size_t base = block * kLanes;
  const std::size_t end = a.first + a.count;
  const std::size_t lo = std::max(a.first, base) - base;
  const std::size_t hi = std::min(end, base + kLanes) - base;
  float* o = a.out_rgb + (base + lo - a.first) * 3;
  for (std::size_t lane = lo; lane < hi; ++lane, o += 3) {
    o[0] = acc[0][lane];
    o[1] = acc[1][lane];
    o[2] = acc[2][lane];
  }
}

// ---- portable path: loops over the 16 lanes, auto-vectorised ----

// Branch-free binary16 -> float for finite halves (the kernel's data is validated finite),
// written as a plain loop the compiler vectorises: normals re-bias the exponent; subnormals
// are m · 2^-24 via an exact integer -> float conversion (no float subnormals are involved,
// so it is also right when the caller runs with flush-to-zero / denormals-are-zero).
void convert_finite_halves(const uint16_t* __restrict src, std::size_t n, float* __restrict dst) {
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t h = src[i];
    const uint32_t magnitude = h & 0x7fffu;
    const float sub = static_cast<float>(static_cast<int32_t>(magnitude)) * 0x1p-24f;
    uint32_t sub_bits;
    std::memcpy(&sub_bits, &sub, 4);
    const uint32_t normal = (magnitude << 13) + 0x38000000u;
    const uint32_t is_sub = 0u - static_cast<uint32_t>(magnitude < 0x400u);  // all ones or 0
    const uint32_t bits = ((h & 0x8000u) << 16) | (sub_bits & is_sub) | (normal & ~is_sub);
    std::memcpy(dst + i, &bits, 4);
  }
}

// acc[o][lane] += Σ_{k < k_count} t[k·16 + lane] · light[o][k] for o < NOut, k ascending.
template <int NOut>
void accumulate_floats(const float* t, int k_count, const float* const* light,
                       float (*acc)[kLanes]) {
  for (int k = 0; k < k_count; ++k) {
    const float* lanes = t + static_cast<std::size_t>(k) * kLanes;
    for (int o = 0; o < NOut; ++o) {
      const float l = light[o][k];
      for (std::size_t i = 0; i < kLanes; ++i) acc[o][i] = acc[o][i] + lanes[i] * l;
    }
  }
}

// acc[o][lane] = Σ_k t[k·16 + lane] · light[o][k] for o < NOut.
template <int NOut>
void accumulate_portable(const float* t, int k_used, const float* const* light,
                         float (*acc)[kLanes]) {
  for (int o = 0; o < NOut; ++o) {
    for (std::size_t i = 0; i < kLanes; ++i) acc[o][i] = 0.0f;
  }
  accumulate_floats<NOut>(t, k_used, light, acc);
}

// The same for binary16: converts up to kChunk coefficients' lanes at a time, then sums;
// the summation order (k ascending) is the same as for float data.
template <int NOut>
void accumulate_portable(const uint16_t* t, int k_used, const float* const* light,
                         float (*acc)[kLanes]) {
  constexpr int kChunk = 32;
  for (int o = 0; o < NOut; ++o) {
    for (std::size_t i = 0; i < kLanes; ++i) acc[o][i] = 0.0f;
  }
  float converted[kChunk * kLanes];
  for (int k0 = 0; k0 < k_used; k0 += kChunk) {
    const int n = std::min(kChunk, k_used - k0);
    convert_finite_halves(t + static_cast<std::size_t>(k0) * kLanes,
                          static_cast<std::size_t>(n) * kLanes, converted);
    const float* shifted[3] = {light[0] + k0, NOut > 1 ? light[1] + k0 : nullptr,
                               NOut > 2 ? light[2] + k0 : nullptr};
    accumulate_floats<NOut>(converted, n, shifted, acc);
  }
}

template <class T>
void shade_portable(const KernelArgs& a) {
  const T* data = reinterpret_cast<const T*>(a.coefficients);
  const std::size_t block_values = static_cast<std::size_t>(a.channels) * a.k_stride * kLanes;
  const std::size_t end = a.first + a.count;
  float acc[3][kLanes];
  for (std::size_t b = a.first / kLanes; b * kLanes < end; ++b) {
    const T* block = data + b * block_values;
    if (a.channels == 3) {
      for (int c = 0; c < 3; ++c) {
        accumulate_portable<1>(block + static_cast<std::size_t>(c) * a.k_stride * kLanes, a.k_used,
                               &a.light[c], &acc[c]);
      }
    } else {
      accumulate_portable<3>(block, a.k_used, a.light, acc);
    }
    write_block(a, b, acc);
  }
}

// ---- AVX2 + F16C path (x86-64 only) ----
#if PRT_HAVE_X86_DISPATCH

#define PRT_AVX2 __attribute__((target("avx2,f16c,fma")))

PRT_AVX2 inline void load_lanes_avx2(const float* src, __m256& lo, __m256& hi) {
  lo = _mm256_load_ps(src);
  hi = _mm256_load_ps(src + 8);
}
PRT_AVX2 inline void load_lanes_avx2(const uint16_t* src, __m256& lo, __m256& hi) {
  const __m256i h = _mm256_load_si256(reinterpret_cast<const __m256i*>(src));
  lo = _mm256_cvtph_ps(_mm256_castsi256_si128(h));
  hi = _mm256_cvtph_ps(_mm256_extracti128_si256(h, 1));
}

// Multiply then add, deliberately not fused (see the file comment).
template <class T, int NOut>
PRT_AVX2 void accumulate_avx2(const T* t, int k_used, const float* const* light,
                              float (*acc)[kLanes]) {
  __m256 lo[NOut], hi[NOut];
  for (int o = 0; o < NOut; ++o) lo[o] = hi[o] = _mm256_setzero_ps();
  for (int k = 0; k < k_used; ++k) {
    __m256 t_lo, t_hi;
    load_lanes_avx2(t + static_cast<std::size_t>(k) * kLanes, t_lo, t_hi);
    for (int o = 0; o < NOut; ++o) {
      const __m256 l = _mm256_broadcast_ss(light[o] + k);
      lo[o] = _mm256_add_ps(lo[o], _mm256_mul_ps(t_lo, l));
      hi[o] = _mm256_add_ps(hi[o], _mm256_mul_ps(t_hi, l));
    }
  }
  for (int o = 0; o < NOut; ++o) {
    _mm256_storeu_ps(acc[o], lo[o]);
    _mm256_storeu_ps(acc[o] + 8, hi[o]);
  }
}

template <class T>
PRT_AVX2 void shade_avx2(const KernelArgs& a) {
  const T* data = reinterpret_cast<const T*>(a.coefficients);
  const std::size_t block_values = static_cast<std::size_t>(a.channels) * a.k_stride * kLanes;
  const std::size_t end = a.first + a.count;
  alignas(32) float acc[3][kLanes];
  for (std::size_t b = a.first / kLanes; b * kLanes < end; ++b) {
    const T* block = data + b * block_values;
    if (a.channels == 3) {
      accumulate_avx2<T, 1>(block, a.k_used, &a.light[0], &acc[0]);
      accumulate_avx2<T, 1>(block + static_cast<std::size_t>(a.k_stride) * kLanes, a.k_used,
                            &a.light[1], &acc[1]);
      accumulate_avx2<T, 1>(block + static_cast<std::size_t>(2 * a.k_stride) * kLanes, a.k_used,
                            &a.light[2], &acc[2]);
    } else {
      accumulate_avx2<T, 3>(block, a.k_used, a.light, acc);
    }
    write_block(a, b, acc);
  }
}

#undef PRT_AVX2
#endif

bool avx2_available() {
  static const bool available = detail::cpu_supports_avx2_f16c_fma();
  return available;
}

Status fill_blocked(const TransferData& d, Precision storage, Impl* im) {
  const std::string name = "transfer data";
  if (d.order < 1 || d.order > kMaxTransferOrder) {
    return Status::Error(name + ": SH order " + std::to_string(d.order) + " is outside [1, " +
                         std::to_string(kMaxTransferOrder) + "]");
  }
  if (d.channels != 1 && d.channels != 3) {
    return Status::Error(name + ": channel count " + std::to_string(d.channels) + " is not 1 or 3");
  }
  if (storage != Precision::F32 && storage != Precision::F16) {
    return Status::Error(name + ": unknown storage precision");
  }
  if (d.vertex_count > kMaxTransferVertices) {
    return Status::Error(name + ": vertex count " + std::to_string(d.vertex_count) + " exceeds " +
                         std::to_string(kMaxTransferVertices));
  }
  const std::size_t v = static_cast<std::size_t>(d.vertex_count);
  const std::size_t k = d.coefficients_per_channel();
  const std::size_t c_count = d.channels;
  if (d.coefficients.size() != v * c_count * k) {
    return Status::Error(name + ": " + std::to_string(d.coefficients.size()) +
                         " coefficients, expected " + std::to_string(v * c_count * k));
  }
  for (std::size_t i = 0; i < d.coefficients.size(); ++i) {
    const float x = d.coefficients[i];
    if (!std::isfinite(x) || (storage == Precision::F16 && would_overflow_half(x))) {
      std::ostringstream os;
      os.precision(9);
      os << name << ": coefficient " << x << " of vertex " << i / (c_count * k) << " (channel "
         << (i / k) % c_count << ", index " << i % k << ") "
         << (std::isfinite(x) ? "overflows float16 (largest 65504)" : "is not finite");
      return Status::Error(os.str());
    }
  }
  uint64_t bytes = 0;
  if (!detail::blocked_coefficient_bytes(v, c_count, k, storage == Precision::F16 ? 2 : 4,
                                         &bytes)) {
    return Status::Error(name + ": too many coefficients");
  }
  im->coefficients = allocate_aligned(static_cast<std::size_t>(bytes));
  if (!im->coefficients) return Status::Error(name + ": out of memory");
  std::memset(im->coefficients.get(), 0, static_cast<std::size_t>(bytes));
  im->bytes = static_cast<std::size_t>(bytes);
  im->vertex_count = v;
  im->order = static_cast<int>(d.order);
  im->channels = static_cast<int>(d.channels);
  im->storage = storage;
  float* f32 = reinterpret_cast<float*>(im->coefficients.get());
  uint16_t* f16 = reinterpret_cast<uint16_t*>(im->coefficients.get());
  for (std::size_t vi = 0; vi < v; ++vi) {
    for (std::size_t c = 0; c < c_count; ++c) {
      const float* src = d.coefficients.data() + (vi * c_count + c) * k;
      for (std::size_t ki = 0; ki < k; ++ki) {
        const std::size_t at = blocked_coefficient_index(vi, c, ki, c_count, k);
        if (storage == Precision::F16) {
          f16[at] = float_to_half(src[ki]);
        } else {
          f32[at] = src[ki];
        }
      }
    }
  }
  return Status::Ok();
}

}  // namespace

Relighter::Relighter() : impl_(std::make_unique<Impl>()) {}
Relighter::Relighter(Relighter&&) noexcept = default;
Relighter& Relighter::operator=(Relighter&&) noexcept = default;
Relighter::~Relighter() = default;

Result<Relighter> Relighter::create(const TransferData& data) {
  return create(data, data.storage);
}

Result<Relighter> Relighter::create(const TransferData& data, Precision storage) {
  try {
    Relighter r;
    Status s = fill_blocked(data, storage, r.impl_.get());
    if (!s.ok()) return s;
    return r;
  } catch (const std::bad_alloc&) {
    return Status::Error("transfer data: out of memory");
  }
}

Result<Relighter> Relighter::from_file_bytes(const void* bytes, std::size_t size,
                                             const std::string& name) {
  try {
    detail::ParsedTransferFile parsed;
    Status s = detail::parse_transfer_file(bytes, size, name, &parsed);
    if (!s.ok()) return s;
    Relighter r;
    Impl& im = *r.impl_;
    im.coefficients = allocate_aligned(parsed.coefficient_bytes);
    if (!im.coefficients) return Status::Error(name + ": out of memory");
    if (parsed.coefficient_bytes) {
      std::memcpy(im.coefficients.get(), parsed.coefficients, parsed.coefficient_bytes);
    }
    im.bytes = parsed.coefficient_bytes;
    im.vertex_count = static_cast<std::size_t>(parsed.data.vertex_count);
    im.order = static_cast<int>(parsed.data.order);
    im.channels = static_cast<int>(parsed.data.channels);
    im.storage = parsed.data.storage;
    return r;
  } catch (const std::bad_alloc&) {
    return Status::Error(name + ": out of memory");
  }
}

Result<Relighter> Relighter::from_file(const std::string& path) {
  std::vector<unsigned char> bytes;
  Status s = detail::read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  return from_file_bytes(bytes.data(), bytes.size(), path);
}

std::size_t Relighter::vertex_count() const {
  return impl_->vertex_count;
}
int Relighter::order() const {
  return impl_->order;
}
int Relighter::channels() const {
  return impl_->channels;
}
Precision Relighter::storage() const {
  return impl_->storage;
}

bool Relighter::avx2_path_available() {
  return avx2_available();
}

Status Relighter::shade(const ShLighting& light, std::size_t first_vertex, std::size_t count,
                        float* out_rgb) const {
  return shade_using(KernelPath::Auto, light, first_vertex, count, out_rgb);
}

Status Relighter::shade_using(KernelPath path, const ShLighting& light, std::size_t first_vertex,
                              std::size_t count, float* out_rgb) const {
  const Impl& im = *impl_;
  if (first_vertex > im.vertex_count || count > im.vertex_count - first_vertex) {
    std::ostringstream os;
    os << "shade: vertex range [" << first_vertex << ", +" << count << ") exceeds the "
       << im.vertex_count << " vertices";
    return Status::Error(os.str());
  }
  if (count == 0) return Status::Ok();
  if (out_rgb == nullptr) return Status::Error("shade: output pointer is null");
  const int order_used = std::min(im.order, light.order());
  KernelArgs a{im.coefficients.get(),
               im.channels,
               im.k_count(),
               order_used * order_used,
               {light.coefficients(0), light.coefficients(1), light.coefficients(2)},
               first_vertex,
               count,
               out_rgb};
  const bool half = im.storage == Precision::F16;
  if (path == KernelPath::Avx512) return Status::Error("shade: this kernel has no AVX-512 path");
  const bool use_avx2 = path == KernelPath::Avx2 || (path == KernelPath::Auto && avx2_available());
  if (use_avx2) {
#if PRT_HAVE_X86_DISPATCH
    if (!avx2_available()) return Status::Error("shade: this CPU lacks AVX2/F16C/FMA");
    if (half) {
      shade_avx2<uint16_t>(a);
    } else {
      shade_avx2<float>(a);
    }
    return Status::Ok();
#else
    return Status::Error("shade: the AVX2 path exists on x86-64 only");
#endif
  }
  if (half) {
    shade_portable<uint16_t>(a);
  } else {
    shade_portable<float>(a);
  }
  return Status::Ok();
}

namespace {

// The sRGB formula (IEC 61966-2-1) with 8-bit rounding, in double: the definition.
int srgb8_by_formula(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  const double x = linear;
  const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
  return static_cast<int>(s * 255.0 + 0.5);
}

// threshold[j − 1] = the smallest float x with srgb8_by_formula(x) >= j, j = 1..255, and
// +Inf at the end. The formula is non-decreasing in x, so the number of thresholds <= x is
// exactly srgb8_by_formula(x): a table lookup that can never disagree with the formula.
struct SrgbThresholds {
  float threshold[256];
  SrgbThresholds() {
    for (int j = 1; j <= 255; ++j) {
      const double s = (j - 0.5) / 255.0;  // the encoded value where rounding reaches j
      const double x = s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
      float t = static_cast<float>(x);
      while (srgb8_by_formula(t) < j) t = std::nextafter(t, 2.0f);
      while (srgb8_by_formula(std::nextafter(t, 0.0f)) >= j) t = std::nextafter(t, 0.0f);
      threshold[j - 1] = t;
    }
    threshold[255] = INFINITY;
    // start[b] = the code of the smallest float whose bits >> 16 equal b (x in (0, 1)): a
    // lower bound from which a short forward scan over `threshold` finds the exact code.
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const uint32_t bits = b << 16;
      float x;
      std::memcpy(&x, &bits, 4);
      start[b] = static_cast<uint8_t>(srgb8_by_formula(x));
    }
  }
  static constexpr uint32_t kBuckets = 0x3f81;  // bit patterns of [0, 1] >> 16
  uint8_t start[kBuckets];
};

const SrgbThresholds& srgb_thresholds() {
  static const SrgbThresholds table;  // thread-safe one-time initialisation
  return table;
}

}  // namespace

uint8_t encode_srgb8(float linear) {
  // Branch-free clamp to [0, 1] (NaN -> 0): shading output has unpredictable signs and
  // saturation, and mispredicted branches would cost more than the lookup.
  float x = linear > 0.0f ? linear : 0.0f;
  x = x < 1.0f ? x : 1.0f;
  const SrgbThresholds& table = srgb_thresholds();
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  unsigned code = table.start[bits >> 16];
  // A bucket spans less than one code step, so at most one threshold lies in it: one
  // branch-free step, plus a loop that never runs (kept so correctness needs no proof).
  code += table.threshold[code] <= x ? 1u : 0u;
  while (table.threshold[code] <= x) ++code;
  return static_cast<uint8_t>(code);
}

Status Relighter::shade_rgba8(const ShLighting& light, std::size_t first_vertex, std::size_t count,
                              float exposure_ev, uint8_t* out_rgba) const {
  if (!std::isfinite(exposure_ev)) return Status::Error("shade_rgba8: exposure is not finite");
  if (count > 0 && out_rgba == nullptr) {
    return Status::Error("shade_rgba8: output pointer is null");
  }
  const float scale = std::exp2(exposure_ev);
  constexpr std::size_t kChunk = 256;
  float rgb[kChunk * 3];
  for (std::size_t done = 0; done < count || done == 0; done += kChunk) {
    const std::size_t n = std::min(kChunk, count - done);
    Status s = shade(light, first_vertex + done, n, rgb);
    if (!s.ok()) return s;
    for (std::size_t i = 0; i < n; ++i) {
      uint8_t* o = out_rgba + 4 * (done + i);
      o[0] = encode_srgb8(rgb[3 * i] * scale);
      o[1] = encode_srgb8(rgb[3 * i + 1] * scale);
      o[2] = encode_srgb8(rgb[3 * i + 2] * scale);
      o[3] = 255;
    }
    if (count == 0) break;
  }
  return Status::Ok();
}

Status shade_reference(const TransferData& d, const ShLighting& light, std::size_t v,
                       double out_rgb[3]) {
  if (v >= d.vertex_count) return Status::Error("shade_reference: vertex out of range");
  if ((d.channels != 1 && d.channels != 3) || d.order < 1) {
    return Status::Error("shade_reference: bad channels or order");
  }
  const std::size_t k_file = d.coefficients_per_channel();
  if (d.coefficients.size() != d.vertex_count * d.channels * k_file) {
    return Status::Error("shade_reference: coefficient array has the wrong size");
  }
  const int order_used = std::min(static_cast<int>(d.order), light.order());
  const std::size_t k_used = static_cast<std::size_t>(order_used) * order_used;
  for (int c = 0; c < 3; ++c) {
    const std::size_t tc = d.channels == 1 ? 0 : static_cast<std::size_t>(c);
    const float* t = d.coefficients.data() + (v * d.channels + tc) * k_file;
    const double* l = light.coefficients_double(c);
    double sum = 0.0;
    for (std::size_t k = 0; k < k_used; ++k) sum += static_cast<double>(t[k]) * l[k];
    out_rgb[c] = sum;
  }
  return Status::Ok();
}

}  // namespace prt
