// cpca_kernel.cpp — the CPCA glossy kernel (CpcaKernel); see prt/glossy_kernel.h.
//
// Compiled with -ffp-contract=off (prt/CMakeLists.txt): no path fuses a multiply and an add,
// so the AVX2 and the portable paths round identically.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <string>

#include "cpu_features.h"
#include "prt/glossy_kernel.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {

struct CpcaKernel::Impl {
  CpcaTransfer t;
  std::size_t n2 = 1, stride = 8;
};

namespace {

constexpr std::size_t kWidth = 8;        // lanes of one vector
constexpr std::size_t kMaxStride = 256;  // n² ≤ 256 (order ≤ 16)

struct Args {
  const CpcaKernel::Impl* im;
  const float* projected;
  std::size_t first, count;
  const float* b;  // null: transfer only
  int b_channels;
  float* out;
};

// The 8-lane horizontal sum of both paths: ((r0+r4)+(r2+r6)) + ((r1+r5)+(r3+r7)).
inline float horizontal(const float* r) {
  const float s0 = r[0] + r[4], s1 = r[1] + r[5], s2 = r[2] + r[6], s3 = r[3] + r[7];
  return (s0 + s2) + (s1 + s3);
}

// b of one channel padded with zeros to the stride.
inline void pad_b(const float* src, std::size_t n2, std::size_t stride, float* dst) {
  std::memcpy(dst, src, n2 * sizeof(float));
  std::fill(dst + n2, dst + stride, 0.0f);
}

// ---- portable path ----

void vertex_portable(const Args& a, std::size_t v) {
  const CpcaKernel::Impl& im = *a.im;
  const std::size_t k_count = im.t.vector_count, s = im.stride, n2 = im.n2;
  const std::size_t rel = v - a.first;
  const float* p = a.projected + std::size_t(im.t.cluster_of_vertex[v]) * (k_count + 1) * 3 * s;
  const float* w = im.t.weights.data() + v * k_count;
  alignas(32) float acc[kMaxStride], bp[kMaxStride];
  for (std::size_t c = 0; c < 3; ++c) {
    std::memcpy(acc, p + c * s, s * sizeof(float));
    for (std::size_t k = 1; k <= k_count; ++k) {
      const float wk = w[k - 1];
      const float* pk = p + (k * 3 + c) * s;
      for (std::size_t i = 0; i < s; ++i) acc[i] = acc[i] + pk[i] * wk;
    }
    if (a.b == nullptr) {
      std::memcpy(a.out + (rel * 3 + c) * n2, acc, n2 * sizeof(float));
      continue;
    }
    const std::size_t bc = static_cast<std::size_t>(a.b_channels);
    pad_b(a.b + (rel * bc + (bc == 1 ? 0 : c)) * n2, n2, s, bp);
    float r[kWidth];
    for (std::size_t l = 0; l < kWidth; ++l) r[l] = bp[l] * acc[l];
    for (std::size_t i0 = kWidth; i0 < s; i0 += kWidth) {
      for (std::size_t l = 0; l < kWidth; ++l) r[l] = r[l] + bp[i0 + l] * acc[i0 + l];
    }
    a.out[rel * 3 + c] = horizontal(r);
  }
}

// ---- AVX2 path ----
#if PRT_HAVE_X86_DISPATCH
#define PRT_AVX2 __attribute__((target("avx2,f16c,fma")))

PRT_AVX2 inline float horizontal_avx2(__m256 r) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(r), _mm256_extractf128_ps(r, 1));  // s0..s3
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));  // (s0+s2), (s1+s3)
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_shuffle_ps(t, t, 1)));
}

// NC vectors per channel (0: the stride decides at run time). The three channels advance
// together over k (3·NC independent sums keep the adders busy); each lane's operations and
// their order are those of vertex_portable.
template <int NC>
PRT_AVX2 void vertex_avx2(const Args& a, std::size_t v) {
  const CpcaKernel::Impl& im = *a.im;
  const std::size_t k_count = im.t.vector_count, s = im.stride, n2 = im.n2;
  const std::size_t nc = NC != 0 ? static_cast<std::size_t>(NC) : s / kWidth;
  constexpr std::size_t kMaxNc = NC != 0 ? static_cast<std::size_t>(NC) : kMaxStride / kWidth;
  const std::size_t rel = v - a.first;
  const float* p = a.projected + std::size_t(im.t.cluster_of_vertex[v]) * (k_count + 1) * 3 * s;
  const float* w = im.t.weights.data() + v * k_count;
  __m256 acc[3][kMaxNc];
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t u = 0; u < nc; ++u) acc[c][u] = _mm256_loadu_ps(p + c * s + u * kWidth);
  }
  for (std::size_t k = 1; k <= k_count; ++k) {
    const __m256 wk = _mm256_broadcast_ss(w + k - 1);
    for (std::size_t c = 0; c < 3; ++c) {
      const float* pk = p + (k * 3 + c) * s;
      for (std::size_t u = 0; u < nc; ++u) {
        acc[c][u] = _mm256_add_ps(acc[c][u], _mm256_mul_ps(_mm256_loadu_ps(pk + u * kWidth), wk));
      }
    }
  }
  alignas(32) float bp[kMaxStride], tmp[kMaxStride];
  for (std::size_t c = 0; c < 3; ++c) {
    if (a.b == nullptr) {
      for (std::size_t u = 0; u < nc; ++u) _mm256_store_ps(tmp + u * kWidth, acc[c][u]);
      std::memcpy(a.out + (rel * 3 + c) * n2, tmp, n2 * sizeof(float));
      continue;
    }
    const std::size_t bc = static_cast<std::size_t>(a.b_channels);
    if (c == 0 || bc == 3) pad_b(a.b + (rel * bc + (bc == 1 ? 0 : c)) * n2, n2, s, bp);
    __m256 r = _mm256_mul_ps(_mm256_load_ps(bp), acc[c][0]);
    for (std::size_t u = 1; u < nc; ++u) {
      r = _mm256_add_ps(r, _mm256_mul_ps(_mm256_load_ps(bp + u * kWidth), acc[c][u]));
    }
    a.out[rel * 3 + c] = horizontal_avx2(r);
  }
}

PRT_AVX2 void run_avx2(const Args& a) {
  const std::size_t nc = a.im->stride / kWidth, end = a.first + a.count;
  for (std::size_t v = a.first; v < end; ++v) {
    switch (nc) {
      case 1:
        vertex_avx2<1>(a, v);
        break;
      case 2:
        vertex_avx2<2>(a, v);
        break;
      case 4:
        vertex_avx2<4>(a, v);
        break;
      default:
        vertex_avx2<0>(a, v);
        break;
    }
  }
}
#undef PRT_AVX2
#endif

bool avx2_available() {
  static const bool available = detail::cpu_supports_avx2_f16c_fma();
  return available;
}

Status run_cpca(const CpcaKernel::Impl& im, KernelPath path, const CpcaFrame& frame,
                const float* b, int b_channels, std::size_t first, std::size_t count, float* out,
                const char* what) {
  const std::size_t n = static_cast<std::size_t>(im.t.vertex_count);
  if (first > n || count > n - first) {
    std::ostringstream os;
    os << what << ": vertex range [" << first << ", +" << count << ") exceeds the " << n
       << " vertices";
    return Status::Error(os.str());
  }
  if (frame.owner != &im || frame.stride != im.stride ||
      frame.projected.size() != im.t.cluster_count * (im.t.vector_count + 1) * 3 * im.stride) {
    return Status::Error(std::string(what) + ": the frame was not prepared by this relighter");
  }
  if (count == 0) return Status::Ok();
  if (out == nullptr) return Status::Error(std::string(what) + ": null output");
  Args a{&im, frame.projected.data(), first, count, b, b_channels, out};
  const bool avx2 = path == KernelPath::Avx2 || (path == KernelPath::Auto && avx2_available());
  if (avx2) {
#if PRT_HAVE_X86_DISPATCH
    if (!avx2_available()) return Status::Error(std::string(what) + ": this CPU lacks AVX2");
    run_avx2(a);
    return Status::Ok();
#else
    return Status::Error(std::string(what) + ": the AVX2 path exists on x86-64 only");
#endif
  }
  for (std::size_t v = first; v < first + count; ++v) vertex_portable(a, v);
  return Status::Ok();
}

}  // namespace

CpcaKernel::CpcaKernel() : impl_(std::make_unique<Impl>()) {}
CpcaKernel::CpcaKernel(CpcaKernel&&) noexcept = default;
CpcaKernel& CpcaKernel::operator=(CpcaKernel&&) noexcept = default;
CpcaKernel::~CpcaKernel() = default;

Result<CpcaKernel> CpcaKernel::create(const CpcaTransfer& cpca) {
  Status s = cpca_validate(cpca);
  if (!s.ok()) return s;
  try {
    CpcaKernel r;
    r.impl_->t = cpca;
    r.impl_->n2 = std::size_t(cpca.order) * cpca.order;
    r.impl_->stride = (r.impl_->n2 + kWidth - 1) / kWidth * kWidth;
    return r;
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca: out of memory");
  }
}

std::size_t CpcaKernel::vertex_count() const {
  return static_cast<std::size_t>(impl_->t.vertex_count);
}
int CpcaKernel::order() const {
  return static_cast<int>(impl_->t.order);
}
int CpcaKernel::channels() const {
  return static_cast<int>(impl_->t.channels);
}
int CpcaKernel::vectors() const {
  return static_cast<int>(impl_->t.vector_count);
}

Status CpcaKernel::prepare(const ShLighting& light, CpcaFrame* frame) const {
  if (frame == nullptr) return Status::Error("cpca prepare: null frame");
  const Impl& im = *impl_;
  const std::size_t n2 = im.n2, s = im.stride, k1 = im.t.vector_count + 1;
  const std::size_t d = im.t.dimension(), q_count = im.t.cluster_count;
  const std::size_t used =
      static_cast<std::size_t>(std::min<int>(static_cast<int>(im.t.order), light.order()));
  try {
    frame->projected.assign(q_count * k1 * 3 * s, 0.0f);
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca prepare: out of memory");
  }
  frame->stride = s;
  frame->cluster_count = q_count;
  frame->vectors = k1 - 1;
  frame->owner = impl_.get();
  for (std::size_t q = 0; q < q_count; ++q) {
    for (std::size_t k = 0; k < k1; ++k) {
      const float* m =
          k == 0 ? im.t.means.data() + q * d : im.t.basis.data() + (q * (k1 - 1) + k - 1) * d;
      for (std::size_t c = 0; c < 3; ++c) {
        const float* mc = m + (im.t.channels == 1 ? 0 : c) * n2 * n2;
        const double* l = light.coefficients_double(static_cast<int>(c));
        float* dst = frame->projected.data() + ((q * k1 + k) * 3 + c) * s;
        for (std::size_t i = 0; i < n2; ++i) {
          double sum = 0.0;
          for (std::size_t j = 0; j < used * used; ++j) sum += double(mc[i * n2 + j]) * l[j];
          dst[i] = static_cast<float>(sum);
        }
      }
    }
  }
  return Status::Ok();
}

Status CpcaKernel::transfer(const CpcaFrame& frame, std::size_t first, std::size_t count,
                               float* out) const {
  return transfer_using(KernelPath::Auto, frame, first, count, out);
}
Status CpcaKernel::shade(const CpcaFrame& frame, const float* b, int b_channels,
                            std::size_t first, std::size_t count, float* out_rgb) const {
  return shade_using(KernelPath::Auto, frame, b, b_channels, first, count, out_rgb);
}
Status CpcaKernel::transfer_using(KernelPath path, const CpcaFrame& frame, std::size_t first,
                                     std::size_t count, float* out) const {
  return run_cpca(*impl_, path, frame, nullptr, 0, first, count, out, "cpca transfer");
}
Status CpcaKernel::shade_using(KernelPath path, const CpcaFrame& frame, const float* b,
                                  int b_channels, std::size_t first, std::size_t count,
                                  float* out_rgb) const {
  if (b_channels != 1 && b_channels != 3) {
    return Status::Error("cpca shade: b has " + std::to_string(b_channels) +
                         " channels, not 1 or 3");
  }
  if (b == nullptr && count > 0) return Status::Error("cpca shade: null b");
  return run_cpca(*impl_, path, frame, b, b_channels, first, count, out_rgb, "cpca shade");
}

}  // namespace prt
