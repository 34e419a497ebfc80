// kernel.cpp — the uncompressed glossy kernel (GlossyKernel); see
// prt/glossy/kernel.h.
//
// Compiled with -ffp-contract=off (prt/CMakeLists.txt): no path fuses a multiply and an add,
// so the AVX2 and the portable paths round identically.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <string>

#include "core/cpu_features.h"
#include "prt/glossy/kernel.h"

#if PRT_HAVE_X86_DISPATCH
#include <immintrin.h>
#endif

namespace prt {
namespace {

constexpr std::size_t kLanes = 16;
constexpr std::size_t kAlignment = 64;
constexpr uint32_t kMaxGlossyOrder = 16;

struct AlignedFree {
  void operator()(float* p) const { ::operator delete[](p, std::align_val_t(kAlignment)); }
};
using AlignedFloats = std::unique_ptr<float[], AlignedFree>;

AlignedFloats allocate_floats(std::size_t n) {
  return AlignedFloats(static_cast<float*>(::operator new[](
      std::max<std::size_t>(n, 1) * sizeof(float), std::align_val_t(kAlignment), std::nothrow)));
}

}  // namespace

struct GlossyKernel::Impl {
  std::size_t vertex_count = 0;
  int order = 1;
  int channels = 1;
  std::size_t n2 = 1;
  AlignedFloats blocks;  // [block][c][i][j][lane]
  std::size_t block_floats() const { return std::size_t(channels) * n2 * n2 * kLanes; }
};

namespace {

struct Args {
  const float* block_data;  // the first block of the range
  int channels;
  std::size_t n2;
  int k_used;
  const float* light[3];
  std::size_t first, count;
  const float* b;  // null: transfer only
  int b_channels;
  float* out;
};

// Per block: b transposed to lanes (zero for lanes outside the range), and the lane range.
struct BlockLanes {
  std::size_t block, lo, hi;  // lanes [lo, hi) of block `block` are in the range
};

BlockLanes lanes_of(const Args& a, std::size_t block) {
  const std::size_t base = block * kLanes, end = a.first + a.count;
  return {block, std::max(a.first, base) - base, std::min(end, base + kLanes) - base};
}

// bt[(c·n2 + i)·16 + lane] for the lanes of the block.
void transpose_b(const Args& a, const BlockLanes& bl, float* bt) {
  const std::size_t n2 = a.n2, bc = static_cast<std::size_t>(a.b_channels);
  std::fill(bt, bt + bc * n2 * kLanes, 0.0f);
  for (std::size_t lane = bl.lo; lane < bl.hi; ++lane) {
    const std::size_t rel = bl.block * kLanes + lane - a.first;
    for (std::size_t c = 0; c < bc; ++c) {
      const float* src = a.b + (rel * bc + c) * n2;
      for (std::size_t i = 0; i < n2; ++i) bt[(c * n2 + i) * kLanes + lane] = src[i];
    }
  }
}

// Writes row i of L' (acc[c][lane]) or, at the end, the exit radiance.
void store_row(const Args& a, const BlockLanes& bl, std::size_t i, const float (*acc)[kLanes]) {
  for (std::size_t lane = bl.lo; lane < bl.hi; ++lane) {
    const std::size_t rel = bl.block * kLanes + lane - a.first;
    for (std::size_t c = 0; c < 3; ++c) a.out[(rel * 3 + c) * a.n2 + i] = acc[c][lane];
  }
}
void store_exit(const Args& a, const BlockLanes& bl, const float (*exit)[kLanes]) {
  for (std::size_t lane = bl.lo; lane < bl.hi; ++lane) {
    const std::size_t rel = bl.block * kLanes + lane - a.first;
    for (std::size_t c = 0; c < 3; ++c) a.out[rel * 3 + c] = exit[c][lane];
  }
}

// ---- portable path ----

// acc[o][lane] = Σ_{j < k_used} m[j·16 + lane] · light[o][j], j ascending.
template <int NOut>
void row_portable(const float* m, int k_used, const float* const* light, float (*acc)[kLanes]) {
  for (int o = 0; o < NOut; ++o) std::fill(acc[o], acc[o] + kLanes, 0.0f);
  for (int j = 0; j < k_used; ++j) {
    const float* t = m + static_cast<std::size_t>(j) * kLanes;
    for (int o = 0; o < NOut; ++o) {
      const float l = light[o][j];
      for (std::size_t lane = 0; lane < kLanes; ++lane) acc[o][lane] = acc[o][lane] + t[lane] * l;
    }
  }
}

void block_portable(const Args& a, const float* blk, const BlockLanes& bl, const float* bt) {
  const std::size_t n2 = a.n2;
  float acc[3][kLanes], exit[3][kLanes] = {};
  for (std::size_t i = 0; i < n2; ++i) {
    if (a.channels == 1) {
      row_portable<3>(blk + i * n2 * kLanes, a.k_used, a.light, acc);
    } else {
      for (std::size_t c = 0; c < 3; ++c) {
        row_portable<1>(blk + (c * n2 + i) * n2 * kLanes, a.k_used, &a.light[c], &acc[c]);
      }
    }
    if (a.b == nullptr) {
      store_row(a, bl, i, acc);
      continue;
    }
    for (std::size_t c = 0; c < 3; ++c) {
      const float* bi = bt + ((a.b_channels == 1 ? 0 : c) * n2 + i) * kLanes;
      for (std::size_t lane = 0; lane < kLanes; ++lane) {
        exit[c][lane] = exit[c][lane] + bi[lane] * acc[c][lane];
      }
    }
  }
  if (a.b != nullptr) store_exit(a, bl, exit);
}

// ---- AVX2 path (x86-64 only): the same operations, 8 lanes per instruction ----
#if PRT_HAVE_X86_DISPATCH
#define PRT_AVX2 __attribute__((target("avx2,f16c,fma")))

template <int NOut>
PRT_AVX2 void row_avx2(const float* m, int k_used, const float* const* light,
                       float (*acc)[kLanes]) {
  __m256 lo[NOut], hi[NOut];
  for (int o = 0; o < NOut; ++o) lo[o] = hi[o] = _mm256_setzero_ps();
  for (int j = 0; j < k_used; ++j) {
    const float* t = m + static_cast<std::size_t>(j) * kLanes;
    const __m256 t_lo = _mm256_load_ps(t), t_hi = _mm256_load_ps(t + 8);
    for (int o = 0; o < NOut; ++o) {
      const __m256 l = _mm256_broadcast_ss(light[o] + j);
      lo[o] = _mm256_add_ps(lo[o], _mm256_mul_ps(t_lo, l));  // not fused (file comment)
      hi[o] = _mm256_add_ps(hi[o], _mm256_mul_ps(t_hi, l));
    }
  }
  for (int o = 0; o < NOut; ++o) {
    _mm256_storeu_ps(acc[o], lo[o]);
    _mm256_storeu_ps(acc[o] + 8, hi[o]);
  }
}

PRT_AVX2 void block_avx2(const Args& a, const float* blk, const BlockLanes& bl, const float* bt) {
  const std::size_t n2 = a.n2;
  alignas(32) float acc[3][kLanes];
  __m256 exit_lo[3], exit_hi[3];
  for (int c = 0; c < 3; ++c) exit_lo[c] = exit_hi[c] = _mm256_setzero_ps();
  for (std::size_t i = 0; i < n2; ++i) {
    if (a.channels == 1) {
      row_avx2<3>(blk + i * n2 * kLanes, a.k_used, a.light, acc);
    } else {
      for (std::size_t c = 0; c < 3; ++c) {
        row_avx2<1>(blk + (c * n2 + i) * n2 * kLanes, a.k_used, &a.light[c], &acc[c]);
      }
    }
    if (a.b == nullptr) {
      store_row(a, bl, i, acc);
      continue;
    }
    for (std::size_t c = 0; c < 3; ++c) {
      const float* bi = bt + ((a.b_channels == 1 ? 0 : c) * n2 + i) * kLanes;
      exit_lo[c] =
          _mm256_add_ps(exit_lo[c], _mm256_mul_ps(_mm256_load_ps(bi), _mm256_load_ps(acc[c])));
      exit_hi[c] = _mm256_add_ps(exit_hi[c],
                                 _mm256_mul_ps(_mm256_load_ps(bi + 8), _mm256_load_ps(acc[c] + 8)));
    }
  }
  if (a.b == nullptr) return;
  alignas(32) float exit[3][kLanes];
  for (int c = 0; c < 3; ++c) {
    _mm256_store_ps(exit[c], exit_lo[c]);
    _mm256_store_ps(exit[c] + 8, exit_hi[c]);
  }
  store_exit(a, bl, exit);
}
#undef PRT_AVX2
#endif

bool avx2_available() {
  static const bool available = detail::cpu_supports_avx2_f16c_fma();
  return available;
}

template <bool Avx2>
void run(const Args& a, std::size_t block_floats) {
  // Transposed b of one block: 3 · n² · 16 floats (n ≤ 16: at most 48 KiB).
  alignas(64) float bt[3 * 256 * kLanes];
  const std::size_t end = a.first + a.count;
  for (std::size_t blk = a.first / kLanes; blk * kLanes < end; ++blk) {
    const BlockLanes bl = lanes_of(a, blk);
    if (a.b != nullptr) transpose_b(a, bl, bt);
    const float* data = a.block_data + blk * block_floats;
#if PRT_HAVE_X86_DISPATCH
    if (Avx2) {
      block_avx2(a, data, bl, bt);
      continue;
    }
#endif
    block_portable(a, data, bl, bt);
  }
}

Status check_range(const char* what, std::size_t first, std::size_t count, std::size_t n,
                   const void* out) {
  if (first > n || count > n - first) {
    std::ostringstream os;
    os << what << ": vertex range [" << first << ", +" << count << ") exceeds the " << n
       << " vertices";
    return Status::Error(os.str());
  }
  if (count > 0 && out == nullptr) return Status::Error(std::string(what) + ": null output");
  return Status::Ok();
}

}  // namespace

GlossyKernel::GlossyKernel() : impl_(std::make_unique<Impl>()) {}
GlossyKernel::GlossyKernel(GlossyKernel&&) noexcept = default;
GlossyKernel& GlossyKernel::operator=(GlossyKernel&&) noexcept = default;
GlossyKernel::~GlossyKernel() = default;

Result<GlossyKernel> GlossyKernel::create(const GlossyTransferData& d) {
  if (d.order < 1 || d.order > kMaxGlossyOrder || (d.channels != 1 && d.channels != 3)) {
    return Status::Error("glossy transfer: order outside [1, 16] or channels not 1 or 3");
  }
  const std::size_t n = static_cast<std::size_t>(d.vertex_count), n2 = d.coefficients();
  const std::size_t per_vertex = d.channels * n2 * n2;
  if (d.matrices.size() != n * per_vertex) {
    return Status::Error("glossy transfer: " + std::to_string(d.matrices.size()) +
                         " matrix floats, expected " + std::to_string(n * per_vertex));
  }
  for (std::size_t e = 0; e < d.matrices.size(); ++e) {
    if (!std::isfinite(d.matrices[e])) {
      return Status::Error("glossy transfer: matrix entry " + std::to_string(e % per_vertex) +
                           " of vertex " + std::to_string(e / per_vertex) + " is not finite");
    }
  }
  try {
    GlossyKernel r;
    Impl& im = *r.impl_;
    im.vertex_count = n;
    im.order = static_cast<int>(d.order);
    im.channels = static_cast<int>(d.channels);
    im.n2 = n2;
    const std::size_t blocks = (n + kLanes - 1) / kLanes;
    im.blocks = allocate_floats(blocks * im.block_floats());
    if (!im.blocks) return Status::Error("glossy transfer: out of memory");
    std::fill(im.blocks.get(), im.blocks.get() + blocks * im.block_floats(), 0.0f);
    for (std::size_t v = 0; v < n; ++v) {
      float* blk = im.blocks.get() + (v / kLanes) * im.block_floats() + v % kLanes;
      const float* src = d.matrices.data() + v * per_vertex;
      for (std::size_t e = 0; e < per_vertex; ++e) blk[e * kLanes] = src[e];
    }
    return r;
  } catch (const std::bad_alloc&) {
    return Status::Error("glossy transfer: out of memory");
  }
}

std::size_t GlossyKernel::vertex_count() const {
  return impl_->vertex_count;
}
int GlossyKernel::order() const {
  return impl_->order;
}
int GlossyKernel::channels() const {
  return impl_->channels;
}

Status GlossyKernel::transfer(const ShLighting& light, std::size_t first, std::size_t count,
                              float* out) const {
  return transfer_using(KernelPath::Auto, light, first, count, out);
}

Status GlossyKernel::shade(const ShLighting& light, const float* b, int b_channels,
                           std::size_t first, std::size_t count, float* out_rgb) const {
  return shade_using(KernelPath::Auto, light, b, b_channels, first, count, out_rgb);
}

namespace {

// The kernel for both calls: b == nullptr writes L', else the exit radiance.
Status run_glossy(const GlossyKernel::Impl& im, KernelPath path, const ShLighting& light,
                  const float* b, int b_channels, std::size_t first, std::size_t count, float* out,
                  const char* what) {
  Status s = check_range(what, first, count, im.vertex_count, out);
  if (!s.ok()) return s;
  if (count == 0) return Status::Ok();
  const int used = std::min(im.order, light.order());
  Args a{im.blocks.get(),
         im.channels,
         im.n2,
         used * used,
         {light.coefficients(0), light.coefficients(1), light.coefficients(2)},
         first,
         count,
         b,
         b_channels,
         out};
  if (path == KernelPath::Avx512) {
    return Status::Error(std::string(what) + ": the uncompressed kernel has no AVX-512 path");
  }
  const bool avx2 = path == KernelPath::Avx2 || (path == KernelPath::Auto && avx2_available());
  if (avx2) {
#if PRT_HAVE_X86_DISPATCH
    if (!avx2_available()) return Status::Error(std::string(what) + ": this CPU lacks AVX2");
    run<true>(a, im.block_floats());
    return Status::Ok();
#else
    return Status::Error(std::string(what) + ": the AVX2 path exists on x86-64 only");
#endif
  }
  run<false>(a, im.block_floats());
  return Status::Ok();
}

}  // namespace

Status GlossyKernel::transfer_using(KernelPath path, const ShLighting& light, std::size_t first,
                                    std::size_t count, float* out) const {
  return run_glossy(*impl_, path, light, nullptr, 0, first, count, out, "glossy transfer");
}

Status GlossyKernel::shade_using(KernelPath path, const ShLighting& light, const float* b,
                                 int b_channels, std::size_t first, std::size_t count,
                                 float* out) const {
  if (b_channels != 1 && b_channels != 3) {
    return Status::Error("glossy shade: b has " + std::to_string(b_channels) +
                         " channels, not 1 or 3");
  }
  if (b == nullptr && count > 0) return Status::Error("glossy shade: null b");
  return run_glossy(*impl_, path, light, b, b_channels, first, count, out, "glossy shade");
}

}  // namespace prt
