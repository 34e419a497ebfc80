// bake/src/compact_gather.cpp — the per-hit gather matrix in Morton order (compact_gather.h).
#include "bake/compact_gather.h"

#include "huge_pages.h"
#include "prt/core/half.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace prt::bake {
namespace {

using detail::resize_huge;

constexpr double kQuantum = 65535.0;
constexpr int kMaxGatherChannels = 4;  // colour channels a row's ρ scales (C = 1 or 3)

// Spreads the low 21 bits of x to every third bit.
uint64_t spread_bits(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

bool hit_less(const CompactHit& a, const CompactHit& b) {
  if (a.triangle != b.triangle) return a.triangle < b.triangle;
  if (a.u != b.u) return a.u < b.u;
  return a.v < b.v;
}

constexpr std::size_t kPrefetchHits = 8;  // x rows are fetched this many hits ahead

// Asks for the cache lines of `bytes` bytes at p (a hint; no effect where unsupported).
inline void prefetch_bytes(const void* p, std::size_t bytes) {
#if defined(__GNUC__)
  const char* c = static_cast<const char*>(p);
  for (std::size_t off = 0; off < bytes; off += 64) __builtin_prefetch(c + off);
  __builtin_prefetch(c + bytes - 1);
#else
  (void)p;
  (void)bytes;
#endif
}

// x rows as the gather reads them: float as stored, binary16 converted (bulk, F16C where the CPU
// has it) into `scratch` first. half -> float is exact, so the sums below are the same either way
// for the same values.
inline const float* row_as_float(const float* x, int, float*) {
  return x;
}
inline const float* row_as_float(const uint16_t* x, int k, float* scratch) {
  convert_halves_to_floats(x, static_cast<std::size_t>(k), scratch);
  return scratch;
}

// A finished row: y_c = f_c·acc_c, rounded once to the output's type.
template <class Out>
inline void store_row(const double* acc, const double* f, int channels, int kc, Out* out, float*) {
  for (int ch = 0; ch < channels; ++ch)
    for (int c = ch * kc; c < (ch + 1) * kc; ++c) out[c] = static_cast<Out>(f[ch] * acc[c]);
}
inline void store_row(const double* acc, const double* f, int channels, int kc, uint16_t* out,
                      float* scratch) {
  store_row(acc, f, channels, kc, scratch, nullptr);
  convert_floats_to_halves(scratch, static_cast<std::size_t>(channels * kc), out);
}

// One hit's terms added to acc in the order every kernel uses: acc_c += (w0·a_c + wu·b_c) + wv·c_c,
// in double, from the three x rows as stored (float, or binary16 widened through scratch).
struct PortableHitSum {
  template <class In>
#if defined(__GNUC__)
  __attribute__((always_inline))
#endif
  inline void
  operator()(const In* a, const In* b, const In* c, double w0, double wu, double wv, int k,
             double* acc, float* scratch) const {
    const float* __restrict xa = row_as_float(a, k, scratch);
    const float* __restrict xb = row_as_float(b, k, scratch + k);
    const float* __restrict xc = row_as_float(c, k, scratch + 2 * k);
    for (int j = 0; j < k; ++j)
      acc[j] += w0 * static_cast<double>(xa[j]) + wu * static_cast<double>(xb[j]) +
                wv * static_cast<double>(xc[j]);
  }
};

// Rows [first, first + count) of one block: y = rho·scale·Σ_hits (q_0 x_a + q_u x_b + q_v x_c),
// x and y rows `ld` elements apart. The block's hits are one stream: the triangle table is
// prefetched 2·kPrefetchHits hits ahead and the three x rows kPrefetchHits ahead (the reads are
// scattered over the scene; without this the loop waits on memory). Cloned for AVX2 where the
// CPU has it (ISO C++, no contraction: every clone adds the same products in the same order, so
// the results are bit-identical across CPUs). add_hit adds one hit's terms (PortableHitSum's
// contract). scratch: 4·k floats.
template <class In, class Out, class HitSum>
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline void
gather_block(const uint32_t* lengths, const CompactHit* hits, std::size_t n_hits, std::size_t first,
             std::size_t count, const glm::uvec3* tri_rows, const double* rho, int channels,
             double scale, const In* x, int k, std::size_t ld, double* acc, float* scratch, Out* y,
             HitSum add_hit) {
  const int kc = k / channels;
  const double inv_q = 1.0 / kQuantum;
  const std::size_t row_bytes = static_cast<std::size_t>(k) * sizeof(In);
  double f[kMaxGatherChannels];
  std::size_t at = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t row = first + i;
    for (int c = 0; c < k; ++c) acc[c] = 0.0;
    for (uint32_t h = 0; h < lengths[i]; ++h, ++at) {
      if (at + 2 * kPrefetchHits < n_hits)
        prefetch_bytes(&tri_rows[hits[at + 2 * kPrefetchHits].triangle], sizeof(glm::uvec3));
      if (at + kPrefetchHits < n_hits) {
        const glm::uvec3 ahead = tri_rows[hits[at + kPrefetchHits].triangle];
        prefetch_bytes(x + static_cast<std::size_t>(ahead.x) * ld, row_bytes);
        prefetch_bytes(x + static_cast<std::size_t>(ahead.y) * ld, row_bytes);
        prefetch_bytes(x + static_cast<std::size_t>(ahead.z) * ld, row_bytes);
      }
      const CompactHit& hit = hits[at];
      const glm::uvec3 t = tri_rows[hit.triangle];
      const double wu = hit.u * inv_q, wv = hit.v * inv_q;
      const double w0 = (kQuantum - hit.u - hit.v) * inv_q;
      add_hit(x + static_cast<std::size_t>(t.x) * ld, x + static_cast<std::size_t>(t.y) * ld,
              x + static_cast<std::size_t>(t.z) * ld, w0, wu, wv, k, acc, scratch);
    }
    for (int ch = 0; ch < channels; ++ch) f[ch] = rho[row * channels + ch] * scale;
    store_row(acc, f, channels, kc, y + row * ld, scratch + 3 * k);
  }
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define PRT_GATHER_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PRT_GATHER_CLONES
#endif

#if defined(__GNUC__) && defined(__x86_64__)
#define PRT_F16C_GATHER 1

// PortableHitSum for binary16 rows with the F16C loads inline: 8 halves of a row become 8 floats
// in one instruction, then two vectors of 4 doubles, instead of each row going through the bulk
// converter into scratch. Separate multiplies and adds in PortableHitSum's order (no FMA is
// enabled here), so the sums are bit-identical to it; columns past the last multiple of 8 take
// the scalar F16C conversion.
struct F16cHitSum {
  __attribute__((target("avx2,f16c"))) inline void operator()(const uint16_t* xa,
                                                              const uint16_t* xb,
                                                              const uint16_t* xc, double w0,
                                                              double wu, double wv, int k,
                                                              double* acc, float*) const {
    const __m256d v0 = _mm256_set1_pd(w0), vu = _mm256_set1_pd(wu), vv = _mm256_set1_pd(wv);
    int c = 0;
    for (; c + 8 <= k; c += 8) {
      const __m256 fa = _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(xa + c)));
      const __m256 fb = _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(xb + c)));
      const __m256 fc = _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(xc + c)));
      const __m256d a[2] = {_mm256_cvtps_pd(_mm256_castps256_ps128(fa)),
                            _mm256_cvtps_pd(_mm256_extractf128_ps(fa, 1))};
      const __m256d b[2] = {_mm256_cvtps_pd(_mm256_castps256_ps128(fb)),
                            _mm256_cvtps_pd(_mm256_extractf128_ps(fb, 1))};
      const __m256d d[2] = {_mm256_cvtps_pd(_mm256_castps256_ps128(fc)),
                            _mm256_cvtps_pd(_mm256_extractf128_ps(fc, 1))};
      for (int half = 0; half < 2; ++half) {
        __m256d s = _mm256_add_pd(_mm256_mul_pd(v0, a[half]), _mm256_mul_pd(vu, b[half]));
        s = _mm256_add_pd(s, _mm256_mul_pd(vv, d[half]));
        double* out = acc + c + 4 * half;
        _mm256_storeu_pd(out, _mm256_add_pd(_mm256_loadu_pd(out), s));
      }
    }
    for (; c < k; ++c)
      acc[c] += w0 * static_cast<double>(_cvtsh_ss(xa[c])) +
                wu * static_cast<double>(_cvtsh_ss(xb[c])) +
                wv * static_cast<double>(_cvtsh_ss(xc[c]));
  }
};

// gather_block with F16cHitSum, compiled for AVX2 and F16C (dispatched at run time below).
__attribute__((target("avx2,f16c"))) void gather_block_f16c(
    const uint32_t* lengths, const CompactHit* hits, std::size_t n_hits, std::size_t first,
    std::size_t count, const glm::uvec3* tri_rows, const double* rho, int channels, double scale,
    const uint16_t* x, int k, std::size_t ld, double* acc, float* scratch, uint16_t* y) {
  gather_block(lengths, hits, n_hits, first, count, tri_rows, rho, channels, scale, x, k, ld, acc,
               scratch, y, F16cHitSum{});
}
#endif

#define PRT_GATHER_VARIANT(NAME, IN, OUT)                                                        \
  PRT_GATHER_CLONES                                                                              \
  void NAME(const uint32_t* lengths, const CompactHit* hits, std::size_t n_hits,                 \
            std::size_t first, std::size_t count, const glm::uvec3* tri_rows, const double* rho, \
            int channels, double scale, const IN* x, int k, std::size_t ld, double* acc,         \
            float* scratch, OUT* y) {                                                            \
    gather_block(lengths, hits, n_hits, first, count, tri_rows, rho, channels, scale, x, k, ld,  \
                 acc, scratch, y, PortableHitSum{});                                             \
  }

PRT_GATHER_VARIANT(gather_block_variant, float, double)
PRT_GATHER_VARIANT(gather_block_variant, float, float)
PRT_GATHER_VARIANT(gather_block_portable, uint16_t, uint16_t)
#undef PRT_GATHER_VARIANT

// Binary16 rows: the inline F16C kernel where the CPU has AVX2 and F16C, else the portable one
// (the same sums, bit for bit).
void gather_block_variant(const uint32_t* lengths, const CompactHit* hits, std::size_t n_hits,
                          std::size_t first, std::size_t count, const glm::uvec3* tri_rows,
                          const double* rho, int channels, double scale, const uint16_t* x, int k,
                          std::size_t ld, double* acc, float* scratch, uint16_t* y) {
#if defined(PRT_F16C_GATHER)
  static const bool inline_f16c = cpu_has_f16c() && __builtin_cpu_supports("avx2");
  if (inline_f16c) {
    gather_block_f16c(lengths, hits, n_hits, first, count, tri_rows, rho, channels, scale, x, k, ld,
                      acc, scratch, y);
    return;
  }
#endif
  gather_block_portable(lengths, hits, n_hits, first, count, tri_rows, rho, channels, scale, x, k,
                        ld, acc, scratch, y);
}

}  // namespace

CompactHit quantise_hit(uint32_t triangle, float u, float v) {
  const double cu = std::clamp(static_cast<double>(u), 0.0, 1.0);
  const double cv = std::clamp(static_cast<double>(v), 0.0, 1.0);
  long qu = std::lround(cu * kQuantum), qv = std::lround(cv * kQuantum);
  const long excess = qu + qv - static_cast<long>(kQuantum);
  if (excess > 0) {  // u + v rounded above 1: take it from the larger
    if (qu >= qv)
      qu -= excess;
    else
      qv -= excess;
  }
  return CompactHit{triangle, static_cast<uint16_t>(qu), static_cast<uint16_t>(qv)};
}

std::vector<uint32_t> make_morton_order(const std::vector<glm::vec3>& positions) {
  const std::size_t V = positions.size();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-30f));
  const double cells = static_cast<double>((1u << 21) - 1);
  std::vector<std::pair<uint64_t, uint32_t>> keys(V);
  tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
    uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double t = (static_cast<double>(positions[v][a]) - lo[a]) / extent[a];
      code |= spread_bits(static_cast<uint64_t>(std::clamp(t, 0.0, 1.0) * cells)) << a;
    }
    keys[v] = {code, static_cast<uint32_t>(v)};
  });
  tbb::parallel_sort(keys.begin(), keys.end());  // (code, index) pairs are distinct: unique order
  std::vector<uint32_t> order(V);
  for (std::size_t r = 0; r < V; ++r) order[r] = keys[r].second;
  return order;
}

CompactGather::CompactGather(std::vector<uint32_t> order, const std::vector<glm::uvec3>& triangles,
                             std::size_t block_rows, double row_scale, bool for_solve)
    : order_(std::move(order)), block_rows_(block_rows), row_scale_(row_scale) {
  const std::size_t V = order_.size(), T = triangles.size();
  rank_.assign(V, 0);
  for (std::size_t r = 0; r < V; ++r) rank_[order_[r]] = static_cast<uint32_t>(r);
  // Triangles by the row of their first vertex (ties by index): a stable counting sort.
  std::vector<uint32_t> first_count(V + 1, 0);
  for (const glm::uvec3& t : triangles) ++first_count[rank_[t.x] + 1];
  std::partial_sum(first_count.begin(), first_count.end(), first_count.begin());
  triangle_rank_.assign(T, 0);
  if (for_solve) resize_huge(triangle_rows_, T);
  for (std::size_t i = 0; i < T; ++i) {
    const glm::uvec3 t = triangles[i];
    const uint32_t slot = first_count[rank_[t.x]]++;
    triangle_rank_[i] = slot;
    if (for_solve) triangle_rows_[slot] = glm::uvec3(rank_[t.x], rank_[t.y], rank_[t.z]);
  }
  blocks_.resize(blocks());
}

void CompactGather::set_block(std::size_t b, Block block) {
  std::size_t at = 0;
  for (uint32_t len : block.lengths) {
    std::sort(block.hits.begin() + static_cast<std::ptrdiff_t>(at),
              block.hits.begin() + static_cast<std::ptrdiff_t>(at + len), hit_less);
    at += len;
  }
  blocks_[b] = std::move(block);
}

uint64_t CompactGather::hits() const {
  uint64_t n = 0;
  for (const Block& b : blocks_) n += b.hits.size();
  return n;
}

uint64_t CompactGather::bytes() const {
  uint64_t n = (order_.size() + rank_.size() + triangle_rank_.size()) * sizeof(uint32_t) +
               triangle_rows_.size() * sizeof(glm::uvec3);
  for (const Block& b : blocks_) n += block_bytes(b.lengths.size(), b.hits.size());
  return n;
}

double CompactGather::max_weighted_row_sum(const std::vector<double>& rho, int channels) const {
  double q = 0.0;
  const auto C = static_cast<std::size_t>(channels);
  for (std::size_t b = 0; b < blocks_.size(); ++b)
    for (std::size_t i = 0; i < blocks_[b].lengths.size(); ++i)
      for (std::size_t c = 0; c < C; ++c)
        q = std::max(q, rho[(b * block_rows_ + i) * C + c] * blocks_[b].lengths[i] * row_scale_);
  return q;
}

template <class In, class Out>
void CompactGather::multiply_into(const std::vector<double>& rho, int channels, const In* x, int k,
                                  std::size_t ld, Out* y) const {
  if (channels < 1 || channels > kMaxGatherChannels || k % channels != 0)
    throw std::invalid_argument("CompactGather::multiply: channels must be in [1, " +
                                std::to_string(kMaxGatherChannels) + "] and divide the columns");
  tbb::parallel_for(std::size_t(0), blocks_.size(), [&](std::size_t b) {
    std::vector<double> acc(static_cast<std::size_t>(k));
    std::vector<float> scratch(4 * static_cast<std::size_t>(k));
    const Block& blk = blocks_[b];
    const std::size_t first = b * block_rows_;
    const std::size_t count = std::min(block_rows_, rows() - first);
    const std::size_t filled = std::min(count, blk.lengths.size());
    gather_block_variant(blk.lengths.data(), blk.hits.data(), blk.hits.size(), first, filled,
                         triangle_rows_.data(), rho.data(), channels, row_scale_, x, k, ld,
                         acc.data(), scratch.data(), y);
    // Rows of a block never filled (no sampling pass ran) gather nothing.
    for (std::size_t r = first + filled; r < first + count; ++r) std::fill_n(y + r * ld, k, Out(0));
  });
}

void CompactGather::multiply(const std::vector<double>& rho, int channels, const float* x,
                             int columns, double* y) const {
  multiply_into(rho, channels, x, columns, static_cast<std::size_t>(columns), y);
}

void CompactGather::multiply(const std::vector<double>& rho, int channels, const float* x,
                             int columns, float* y, std::size_t ld) const {
  multiply_into(rho, channels, x, columns, ld == 0 ? static_cast<std::size_t>(columns) : ld, y);
}

void CompactGather::multiply(const std::vector<double>& rho, int channels, const uint16_t* x,
                             int columns, uint16_t* y, std::size_t ld) const {
  multiply_into(rho, channels, x, columns, ld == 0 ? static_cast<std::size_t>(columns) : ld, y);
}

std::size_t padded_row_elements(int columns) {
  const std::size_t c = static_cast<std::size_t>(columns);
  return (c + 15) / 16 * 16;
}

void CompactGatherOperator::apply(const double* x, int columns, double* y) const {
  const std::size_t n = h_.rows() * static_cast<std::size_t>(columns);
  resize_huge(x_float_, n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        x_float_[i] = static_cast<float>(x[i]);
                    });
  h_.multiply(rho_, channels_, x_float_.data(), columns, y);
}

}  // namespace prt::bake
