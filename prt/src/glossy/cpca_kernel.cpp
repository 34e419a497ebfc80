// cpca_kernel.cpp — the CPCA glossy kernel (CpcaKernel); see prt/glossy/cpca_kernel.h and
// docs/GLOSSY_CPCA.md ("Kernels").
//
// Compiled with -ffp-contract=off (prt/CMakeLists.txt): no path fuses a multiply and an add,
// so the AVX2 and the portable paths round identically. (Fused multiply-adds in both paths were
// measured, docs/GLOSSY_CPCA.md: no faster on the AMD EPYC of the benchmarks, which runs the
// separate multiplies and adds on parallel units, and nine times slower in the portable path,
// where std::fma is a library call.)
#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <string>

#include "core/cpu_features.h"
#include "prt/glossy/cpca_kernel.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {

namespace {
constexpr std::size_t kWidth = 8;               // float lanes of one vector
constexpr std::size_t kMaxN2 = 256;             // n² ≤ 256 (order ≤ 16)
constexpr std::size_t kMaxStride = 3 * kMaxN2;  // 3·n², already a multiple of 8 at n = 16
}  // namespace

// The compressed transfer in the kernel's layouts (the means and vectors are kept only in
// `columns`, transposed for `prepare`).
struct CpcaKernel::Impl {
  uint32_t order = 1, channels = 1;
  std::size_t n2 = 1;
  std::size_t stride = 8;      // 3·n² rounded up to 8: one projected vector, channels packed
  std::size_t col_stride = 4;  // n² rounded up to 4: one column of a transposed matrix
  std::size_t clusters = 0, vectors = 0, vertices = 0;
  std::vector<uint32_t> cluster_of_vertex;
  std::vector<float> weights;  // [v][k]
  // [q][k ≤ K][m < channels][j][i < col_stride] (k = 0 the mean), zero beyond i = n².
  std::vector<float> columns;
  // Per output channel c: the vectors [u_lo, u_hi] of a projected vector that hold its lanes,
  // and lane masks (all bits set where lane g = 8u + l has c·n² ≤ g < (c+1)·n²).
  std::size_t u_lo[3] = {0, 0, 0}, u_hi[3] = {0, 0, 0};
  std::vector<uint32_t> mask;  // [c][g < stride]
  std::vector<uint32_t> tail;  // [l < 8]: lane l of the last vector lies below 3·n²
  // Grey b in the AVX2 path, gathered in registers: lane g = 8u + l of the packed b is b[i],
  // i = g mod n²; from b + grey_offset[u] + l where grey_far (i ≥ 8; such lanes are contiguous
  // in b), else lane grey_index of b's first 8 values.
  std::vector<uint32_t> grey_offset;  // [u]
  std::vector<uint32_t> grey_far;     // [u][l]: all bits set or 0
  std::vector<uint32_t> grey_index;   // [u][l]
  std::vector<uint32_t> grey_first;   // [l]: l < n²
};

namespace {

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

// b of vertex `rel` in the packed layout (lane g = c·n² + i), zero beyond 3·n².
inline void packed_b(const Args& a, std::size_t rel, float* dst) {
  const std::size_t n2 = a.im->n2, s = a.im->stride;
  if (a.b_channels == 3) {
    std::memcpy(dst, a.b + rel * 3 * n2, 3 * n2 * sizeof(float));
  } else {
    for (std::size_t c = 0; c < 3; ++c)
      std::memcpy(dst + c * n2, a.b + rel * n2, n2 * sizeof(float));
  }
  std::fill(dst + 3 * n2, dst + s, 0.0f);
}

// Vertices are shaded in chunks, each in the order of its clusters (the results do not depend
// on the order): consecutive vertices then read the same projected vectors, which stay in the
// L1 cache instead of being fetched again for every vertex.
constexpr std::size_t kChunk = 1024;

// Offsets in [0, n) of the vertices first + offset (n ≤ kChunk), stably sorted by cluster id
// (least-significant-digit radix sort on bytes, as many passes as `clusters` − 1 has bytes).
void order_by_cluster(const uint32_t* cluster, std::size_t first, std::size_t n,
                      std::size_t clusters, uint16_t* order) {
  uint16_t tmp[kChunk];
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<uint16_t>(i);
  for (unsigned shift = 0; shift < 32 && ((clusters - 1) >> shift) != 0; shift += 8) {
    std::size_t start[257] = {};
    for (std::size_t i = 0; i < n; ++i) ++start[((cluster[first + order[i]] >> shift) & 255u) + 1];
    for (std::size_t d = 1; d < 257; ++d) start[d] += start[d - 1];
    for (std::size_t i = 0; i < n; ++i)
      tmp[start[(cluster[first + order[i]] >> shift) & 255u]++] = order[i];
    std::copy(tmp, tmp + n, order);
  }
}

// Calls shade_vertex(a, v) for every vertex of the range, chunk by chunk in cluster order.
template <typename F>
inline void for_each_vertex(const Args& a, F shade_vertex) {
  uint16_t order[kChunk];
  const std::size_t end = a.first + a.count;
  for (std::size_t start = a.first; start < end; start += kChunk) {
    const std::size_t n = std::min(kChunk, end - start);
    order_by_cluster(a.im->cluster_of_vertex.data(), start, n, a.im->clusters, order);
    for (std::size_t i = 0; i < n; ++i) shade_vertex(a, start + order[i]);
  }
}

// ---- portable path ----

void vertex_portable(const Args& a, std::size_t v) {
  const CpcaKernel::Impl& im = *a.im;
  const std::size_t k_count = im.vectors, s = im.stride, n2 = im.n2;
  const std::size_t rel = v - a.first;
  const float* p = a.projected + std::size_t(im.cluster_of_vertex[v]) * (k_count + 1) * s;
  const float* w = im.weights.data() + v * k_count;
  alignas(32) float acc[kMaxStride], bp[kMaxStride];
  std::memcpy(acc, p, s * sizeof(float));
  for (std::size_t k = 1; k <= k_count; ++k) {
    const float wk = w[k - 1];
    const float* pk = p + k * s;
    for (std::size_t g = 0; g < s; ++g) acc[g] = acc[g] + pk[g] * wk;
  }
  if (a.b == nullptr) {
    std::memcpy(a.out + rel * 3 * n2, acc, 3 * n2 * sizeof(float));
    return;
  }
  packed_b(a, rel, bp);
  for (std::size_t c = 0; c < 3; ++c) {
    const uint32_t* m = im.mask.data() + c * s;
    const auto lane_b = [&](std::size_t g) { return m[g] != 0 ? bp[g] : 0.0f; };
    float r[kWidth];
    for (std::size_t l = 0, g = im.u_lo[c] * kWidth; l < kWidth; ++l, ++g)
      r[l] = lane_b(g) * acc[g];
    for (std::size_t u = im.u_lo[c] + 1; u <= im.u_hi[c]; ++u) {
      for (std::size_t l = 0, g = u * kWidth; l < kWidth; ++l, ++g) {
        r[l] = r[l] + lane_b(g) * acc[g];
      }
    }
    a.out[rel * 3 + c] = horizontal(r);
  }
}

// Rows [i0, i0 + count) of U·L_c (U: one transposed matrix, `used2` columns) into dst, the sums
// in double with j ascending, each rounded once to float.
void project_rows_portable(const float* col, std::size_t col_stride, const double* l,
                           std::size_t used2, std::size_t i0, std::size_t count, float* dst) {
  for (std::size_t i = i0; i < i0 + count; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < used2; ++j) sum = sum + double(col[j * col_stride + i]) * l[j];
    dst[i - i0] = static_cast<float>(sum);
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

// Order N (0: the order decides at run time; a fixed N lets every vector index be a constant,
// so the accumulators stay in registers).
template <int N>
struct Shape {
  static constexpr std::size_t kN2 = std::size_t(N) * N, kNc = (3 * kN2 + kWidth - 1) / kWidth;
  static constexpr std::size_t kMaxNc = N != 0 ? kNc : kMaxStride / kWidth;
};

// The end of a vertex from its accumulated L' (acc: the stride's nc vectors): L' stored, or the
// exit radiance with b. Each lane's operations and their order are those of vertex_portable;
// both the AVX2 and the AVX-512 paths end here.
template <int N>
PRT_AVX2 __attribute__((always_inline)) inline void finish_avx2(const Args& a, std::size_t rel,
                                                                const __m256* acc) {
  const CpcaKernel::Impl& im = *a.im;
  constexpr std::size_t kN2 = Shape<N>::kN2, kMaxNc = Shape<N>::kMaxNc;
  const std::size_t s = im.stride, n2 = N != 0 ? kN2 : im.n2;
  const std::size_t nc = N != 0 ? Shape<N>::kNc : s / kWidth;
  const __m256i tail = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(im.tail.data()));
  if (a.b == nullptr) {
    float* o = a.out + rel * 3 * n2;
#pragma GCC unroll 16
    for (std::size_t u = 0; u + 1 < nc; ++u) _mm256_storeu_ps(o + u * kWidth, acc[u]);
    _mm256_maskstore_ps(o + (nc - 1) * kWidth, tail, acc[nc - 1]);
    return;
  }
  __m256 bv[kMaxNc];
  if (a.b_channels == 3) {
    const float* src = a.b + rel * 3 * n2;
#pragma GCC unroll 16
    for (std::size_t u = 0; u + 1 < nc; ++u) bv[u] = _mm256_loadu_ps(src + u * kWidth);
    bv[nc - 1] = _mm256_maskload_ps(src + (nc - 1) * kWidth, tail);
  } else {
    // The same values as packed_b(), without a store and reload (data movement only).
    const float* src = a.b + rel * n2;
    const __m256 first8 = _mm256_maskload_ps(
        src, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(im.grey_first.data())));
#pragma GCC unroll 16
    for (std::size_t u = 0; u < nc; ++u) {
      const __m256i far =
          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(im.grey_far.data() + u * kWidth));
      const __m256i index =
          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(im.grey_index.data() + u * kWidth));
      bv[u] = _mm256_blendv_ps(_mm256_permutevar8x32_ps(first8, index),
                               _mm256_maskload_ps(src + im.grey_offset[u], far),
                               _mm256_castsi256_ps(far));
    }
  }
#pragma GCC unroll 3
  for (std::size_t c = 0; c < 3; ++c) {
    const float* m = reinterpret_cast<const float*>(im.mask.data() + c * s);
    const std::size_t lo = N != 0 ? c * kN2 / kWidth : im.u_lo[c];
    const std::size_t hi = N != 0 ? ((c + 1) * kN2 - 1) / kWidth : im.u_hi[c];
    __m256 r = _mm256_mul_ps(_mm256_and_ps(bv[lo], _mm256_loadu_ps(m + lo * kWidth)), acc[lo]);
#pragma GCC unroll 16
    for (std::size_t u = lo + 1; u <= hi; ++u) {
      r = _mm256_add_ps(
          r, _mm256_mul_ps(_mm256_and_ps(bv[u], _mm256_loadu_ps(m + u * kWidth)), acc[u]));
    }
    a.out[rel * 3 + c] = horizontal_avx2(r);
  }
}

// The accumulation L' = P_0 + Σ_k w_k·P_k, 8 lanes a vector.
template <int N>
PRT_AVX2 void vertex_avx2(const Args& a, std::size_t v) {
  const CpcaKernel::Impl& im = *a.im;
  const std::size_t k_count = im.vectors, s = im.stride;
  const std::size_t nc = N != 0 ? Shape<N>::kNc : s / kWidth;
  const float* p = a.projected + std::size_t(im.cluster_of_vertex[v]) * (k_count + 1) * s;
  const float* w = im.weights.data() + v * k_count;
  __m256 acc[Shape<N>::kMaxNc];
#pragma GCC unroll 16
  for (std::size_t u = 0; u < nc; ++u) acc[u] = _mm256_loadu_ps(p + u * kWidth);
  for (std::size_t k = 1; k <= k_count; ++k) {
    const __m256 wk = _mm256_broadcast_ss(w + k - 1);
    const float* pk = p + k * s;
#pragma GCC unroll 16
    for (std::size_t u = 0; u < nc; ++u) {
      acc[u] = _mm256_add_ps(acc[u], _mm256_mul_ps(_mm256_loadu_ps(pk + u * kWidth), wk));
    }
  }
  finish_avx2<N>(a, v - a.first, acc);
}

template <int N>
PRT_AVX2 void run_avx2_order(const Args& a) {
  for_each_vertex(a, vertex_avx2<N>);
}

PRT_AVX2 void run_avx2(const Args& a) {
  switch (a.im->order) {
    case 1:
      run_avx2_order<1>(a);
      break;
    case 2:
      run_avx2_order<2>(a);
      break;
    case 3:
      run_avx2_order<3>(a);
      break;
    case 4:
      run_avx2_order<4>(a);
      break;
    case 5:
      run_avx2_order<5>(a);
      break;
    case 6:
      run_avx2_order<6>(a);
      break;
    default:
      run_avx2_order<0>(a);
      break;
  }
}

// ---- AVX-512 path: the AVX2 path with the accumulation 16 lanes a vector ----
#define PRT_AVX512 __attribute__((target("avx512f,avx2,f16c,fma")))

// Lane l of wide vector u is lane l mod 8 of AVX2 vector 2u + l / 8 and goes through the same
// multiply and add in the same k order, so it holds the same bits; the halves then go through
// the AVX2 path's end (finish_avx2) unchanged. An odd last AVX2 vector is loaded with its upper
// half masked off (no read beyond it).
template <int N>
PRT_AVX512 void vertex_avx512(const Args& a, std::size_t v) {
  constexpr std::size_t kWide = 2 * kWidth, kMaxNw = (Shape<N>::kMaxNc + 1) / 2;
  const CpcaKernel::Impl& im = *a.im;
  const std::size_t k_count = im.vectors, s = im.stride;
  const std::size_t nc = N != 0 ? Shape<N>::kNc : s / kWidth, nw = (nc + 1) / 2;
  const __mmask16 last = nc % 2 != 0 ? __mmask16(0x00FF) : __mmask16(0xFFFF);
  const float* p = a.projected + std::size_t(im.cluster_of_vertex[v]) * (k_count + 1) * s;
  const float* w = im.weights.data() + v * k_count;
  __m512 acc[kMaxNw];
#pragma GCC unroll 8
  for (std::size_t u = 0; u + 1 < nw; ++u) acc[u] = _mm512_loadu_ps(p + u * kWide);
  acc[nw - 1] = _mm512_maskz_loadu_ps(last, p + (nw - 1) * kWide);
  for (std::size_t k = 1; k <= k_count; ++k) {
    const __m512 wk = _mm512_set1_ps(w[k - 1]);
    const float* pk = p + k * s;
#pragma GCC unroll 8
    for (std::size_t u = 0; u + 1 < nw; ++u) {
      acc[u] = _mm512_add_ps(acc[u], _mm512_mul_ps(_mm512_loadu_ps(pk + u * kWide), wk));
    }
    acc[nw - 1] = _mm512_add_ps(
        acc[nw - 1], _mm512_mul_ps(_mm512_maskz_loadu_ps(last, pk + (nw - 1) * kWide), wk));
  }
  __m256 halves[Shape<N>::kMaxNc];
#pragma GCC unroll 16
  for (std::size_t u = 0; u < nc; ++u) {
    const __m512 wide = acc[u / 2];
    // (Not _mm512_castps512_ps256/_mm512_extractf32x8_ps: GCC 12's header warns about an
    // uninitialised variable in them, and the latter needs AVX-512DQ.)
    halves[u] = u % 2 == 0 ? __builtin_shufflevector(wide, wide, 0, 1, 2, 3, 4, 5, 6, 7)
                           : __builtin_shufflevector(wide, wide, 8, 9, 10, 11, 12, 13, 14, 15);
  }
  finish_avx2<N>(a, v - a.first, halves);
}

template <int N>
PRT_AVX512 void run_avx512_order(const Args& a) {
  for_each_vertex(a, vertex_avx512<N>);
}

PRT_AVX512 void run_avx512(const Args& a) {
  static constexpr void (*kByOrder[])(const Args&) = {
      run_avx512_order<0>, run_avx512_order<1>, run_avx512_order<2>, run_avx512_order<3>,
      run_avx512_order<4>, run_avx512_order<5>, run_avx512_order<6>};
  kByOrder[a.im->order < 7 ? a.im->order : 0](a);
}
#undef PRT_AVX512

// project_rows_portable for NV·4 rows at once (lanes over i; the same operations per row).
template <int NV>
PRT_AVX2 void project_rows_avx2(const float* col, std::size_t col_stride, const double* l,
                                std::size_t used2, std::size_t i0, float* dst) {
  __m256d acc[NV];
  for (int u = 0; u < NV; ++u) acc[u] = _mm256_setzero_pd();
  for (std::size_t j = 0; j < used2; ++j) {
    const __m256d lj = _mm256_broadcast_sd(l + j);
    const float* row = col + j * col_stride + i0;
    for (int u = 0; u < NV; ++u) {
      const __m256d m = _mm256_cvtps_pd(_mm_loadu_ps(row + 4 * u));
      acc[u] = _mm256_add_pd(acc[u], _mm256_mul_pd(m, lj));
    }
  }
  for (int u = 0; u < NV; ++u) _mm_storeu_ps(dst + 4 * u, _mm256_cvtpd_ps(acc[u]));
}

PRT_AVX2 void project_avx2(const float* col, std::size_t col_stride, const double* l,
                           std::size_t used2, float* dst) {
  std::size_t i0 = 0;
  for (; i0 + 32 <= col_stride; i0 += 32)
    project_rows_avx2<8>(col, col_stride, l, used2, i0, dst + i0);
  switch ((col_stride - i0) / 4) {
    case 7:
      project_rows_avx2<7>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 6:
      project_rows_avx2<6>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 5:
      project_rows_avx2<5>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 4:
      project_rows_avx2<4>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 3:
      project_rows_avx2<3>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 2:
      project_rows_avx2<2>(col, col_stride, l, used2, i0, dst + i0);
      break;
    case 1:
      project_rows_avx2<1>(col, col_stride, l, used2, i0, dst + i0);
      break;
    default:
      break;
  }
}
#undef PRT_AVX2
#endif

bool avx2_available() {
  static const bool available = detail::cpu_supports_avx2_f16c_fma();
  return available;
}
bool avx512_available() {
  static const bool available = detail::cpu_supports_avx512f_avx2_f16c_fma();
  return available;
}

Status run_cpca(const CpcaKernel::Impl& im, KernelPath path, const CpcaFrame& frame, const float* b,
                int b_channels, std::size_t first, std::size_t count, float* out,
                const char* what) {
  const std::size_t n = im.vertices;
  if (first > n || count > n - first) {
    std::ostringstream os;
    os << what << ": vertex range [" << first << ", +" << count << ") exceeds the " << n
       << " vertices";
    return Status::Error(os.str());
  }
  if (frame.owner != &im || frame.stride != im.stride ||
      frame.projected.size() != im.clusters * (im.vectors + 1) * im.stride) {
    return Status::Error(std::string(what) + ": the frame was not prepared by this relighter");
  }
  if (count == 0) return Status::Ok();
  if (out == nullptr) return Status::Error(std::string(what) + ": null output");
  Args a{&im, frame.projected.data(), first, count, b, b_channels, out};
  const bool avx512 =
      path == KernelPath::Avx512 || (path == KernelPath::Auto && avx512_available());
  if (avx512) {
#if PRT_HAVE_X86_DISPATCH
    if (!avx512_available()) return Status::Error(std::string(what) + ": this CPU lacks AVX-512F");
    run_avx512(a);
    return Status::Ok();
#else
    return Status::Error(std::string(what) + ": the AVX-512 path exists on x86-64 only");
#endif
  }
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
  for_each_vertex(a, vertex_portable);
  return Status::Ok();
}

// The kernel's layouts of a validated CPCA form.
void build_layouts(const CpcaTransfer& t, CpcaKernel::Impl& im) {
  const std::size_t n2 = std::size_t(t.order) * t.order, k1 = std::size_t(t.vector_count) + 1;
  const std::size_t d = t.dimension(), ch = t.channels;
  im.order = t.order;
  im.channels = t.channels;
  im.n2 = n2;
  im.stride = (3 * n2 + kWidth - 1) / kWidth * kWidth;
  im.col_stride = (n2 + 3) / 4 * 4;
  im.clusters = t.cluster_count;
  im.vectors = t.vector_count;
  im.vertices = static_cast<std::size_t>(t.vertex_count);
  im.cluster_of_vertex = t.cluster_of_vertex;
  im.weights = t.weights;
  im.columns.assign(im.clusters * k1 * ch * n2 * im.col_stride, 0.0f);
  for (std::size_t q = 0; q < im.clusters; ++q) {
    for (std::size_t k = 0; k < k1; ++k) {
      const float* m =
          k == 0 ? t.means.data() + q * d : t.basis.data() + (q * (k1 - 1) + k - 1) * d;
      float* dst = im.columns.data() + (q * k1 + k) * ch * n2 * im.col_stride;
      for (std::size_t c = 0; c < ch; ++c) {
        for (std::size_t i = 0; i < n2; ++i) {
          for (std::size_t j = 0; j < n2; ++j) {
            dst[(c * n2 + j) * im.col_stride + i] = m[(c * n2 + i) * n2 + j];
          }
        }
      }
    }
  }
  im.mask.assign(3 * im.stride, 0u);
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t g = c * n2; g < (c + 1) * n2; ++g) im.mask[c * im.stride + g] = ~0u;
    im.u_lo[c] = c * n2 / kWidth;
    im.u_hi[c] = ((c + 1) * n2 - 1) / kWidth;
  }
  const std::size_t nc = im.stride / kWidth;
  im.grey_offset.assign(nc, 0u);
  im.grey_far.assign(nc * kWidth, 0u);
  im.grey_index.assign(nc * kWidth, 0u);
  im.grey_first.assign(kWidth, 0u);
  for (std::size_t l = 0; l < kWidth && l < n2; ++l) im.grey_first[l] = ~0u;
  for (std::size_t u = 0; u < nc; ++u) {
    im.grey_offset[u] = static_cast<uint32_t>(u * kWidth % n2);
    for (std::size_t l = 0; l < kWidth; ++l) {
      const std::size_t g = u * kWidth + l, i = g % n2;
      if (g >= 3 * n2) continue;
      // Lanes with i ≥ 8 come before the vector's wrap to i = 0 (i cannot reach 8 again within
      // 8 lanes), so i = offset + l for them.
      if (i >= kWidth) im.grey_far[u * kWidth + l] = ~0u;
      im.grey_index[u * kWidth + l] = static_cast<uint32_t>(i % kWidth);
    }
  }
  im.tail.assign(kWidth, 0u);
  for (std::size_t l = 0; l < kWidth; ++l) {
    if (im.stride - kWidth + l < 3 * n2) im.tail[l] = ~0u;
  }
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
    build_layouts(cpca, *r.impl_);
    return r;
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca: out of memory");
  }
}

bool CpcaKernel::avx512_path_available() {
  return avx512_available();
}

std::size_t CpcaKernel::vertex_count() const {
  return impl_->vertices;
}
int CpcaKernel::order() const {
  return static_cast<int>(impl_->order);
}
int CpcaKernel::channels() const {
  return static_cast<int>(impl_->channels);
}
int CpcaKernel::vectors() const {
  return static_cast<int>(impl_->vectors);
}

Status CpcaKernel::prepare(const ShLighting& light, CpcaFrame* frame) const {
  if (frame == nullptr) return Status::Error("cpca prepare: null frame");
  const Impl& im = *impl_;
  const std::size_t n2 = im.n2, s = im.stride, k1 = im.vectors + 1, cs = im.col_stride;
  const std::size_t q_count = im.clusters, ch = im.channels;
  const std::size_t used = static_cast<std::size_t>(std::min<int>(int(im.order), light.order()));
  try {
    frame->projected.resize(q_count * k1 * s);
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca prepare: out of memory");
  }
  frame->stride = s;
  frame->cluster_count = q_count;
  frame->vectors = k1 - 1;
  frame->owner = impl_.get();
  const bool avx2 = avx2_available();
  alignas(32) float rows[kMaxN2];
  for (std::size_t qk = 0; qk < q_count * k1; ++qk) {
    float* dst = frame->projected.data() + qk * s;
    for (std::size_t c = 0; c < 3; ++c) {
      const float* col = im.columns.data() + (qk * ch + (ch == 1 ? 0 : c)) * n2 * cs;
      const double* l = light.coefficients_double(static_cast<int>(c));
#if PRT_HAVE_X86_DISPATCH
      if (avx2) {
        project_avx2(col, cs, l, used * used, rows);
      } else {
        project_rows_portable(col, cs, l, used * used, 0, n2, rows);
      }
#else
      (void)avx2;
      project_rows_portable(col, cs, l, used * used, 0, n2, rows);
#endif
      std::memcpy(dst + c * n2, rows, n2 * sizeof(float));
    }
    std::fill(dst + 3 * n2, dst + s, 0.0f);
  }
  return Status::Ok();
}

Status CpcaKernel::transfer(const CpcaFrame& frame, std::size_t first, std::size_t count,
                            float* out) const {
  return transfer_using(KernelPath::Auto, frame, first, count, out);
}
Status CpcaKernel::shade(const CpcaFrame& frame, const float* b, int b_channels, std::size_t first,
                         std::size_t count, float* out_rgb) const {
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
