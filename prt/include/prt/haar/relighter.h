// prt/haar/relighter.h — relighting with sparse Haar lighting × sparse Haar transfer.
//
// Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003, Sec. 6: exit radiance is the product of a
// sparse lighting vector (prt/haar/approximation.h) and the sparse transport matrix stored
// per lighting coefficient (prt/haar/transfer.h):
//     B_v,c = Σ_{kept i} T̂_v,i,c · L̂_i,c
// (grey transfer, channels = 1, uses the same T̂ for R, G and B). With every term kept and no
// quantisation it equals the brute-force texel sum Σ_t T_v,t,c · L_t,c, because the Haar
// transform is orthonormal.
//
// Fast path (the constructor reorganises the transfer once; results are those of the plain
// per-index list walk, shade_index_lists, up to float rounding — in practice bit for bit):
//   * Vertices are cut into blocks of HaarRelighterLayout::block_vertices (the last block may be
//     shorter). Each block holds, for each wavelet index, its own slice of that index's list
//     with 16-bit block-relative vertex offsets (8 B per RGB 16-bit entry instead of 10).
//   * A slice holding at least dense_fraction of the block's vertices is stored as a dense
//     column (a value for every vertex of the block, zeros where the vertex has none; no
//     offsets) and is accumulated with a vectorised axpy. Real shadowed transfer makes the
//     coarse wavelets that a non-linear lighting picks dense: nearly every vertex stores them.
//   * shade() walks block by block, and within a block the K lighting terms in order, so the
//     block's accumulators (3 floats per vertex, 192 KiB for the default 16384 vertices) stay
//     in L2 across the K terms; the next term's slice is prefetched while one is summed.
// Accumulation is in float, L̂ · stored per term in the lighting's order (one float
// accumulator per vertex and channel; with K terms the rounding error is at most about K·2⁻²⁴
// of Σ|T̂·L̂|, in practice √K of that); the per-vertex dequantisation step is applied once at
// the end.
// Compiles as C++17.
// References: [4] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/haar/approximation.h"
#include "prt/haar/cube_map.h"
#include "prt/haar/transfer.h"

namespace prt {

// How the relighter lays out its copy of the transfer (see above). The defaults are tuned for
// N = 32, 16-bit RGB on a core with ≥ 512 KiB of L2: larger blocks give longer slices, which
// stream better (timings per block size: docs/BENCHMARKS.md, "Blocked relight layout").
struct HaarRelighterLayout {
  int block_vertices = 16384;   // vertices per block, clamped to [1, 65536]
  double dense_fraction = 0.5;  // dense column when a slice has ≥ this fraction of the block
};

class HaarRelighter {
 public:
  explicit HaarRelighter(HaarTransfer transfer, HaarRelighterLayout layout = {});

  const HaarTransfer& transfer() const { return transfer_; }
  int64_t vertex_count() const { return transfer_.vertex_count; }

  // Writes RGB exit radiance for every vertex: out_rgb[3v + c], 3 · vertex_count() floats.
  // Thread-safe (const, no shared scratch). Errors: the lighting's cube size differs from the
  // transfer's, or an index is out of range (out_rgb is then left zeroed).
  Status shade(const SparseLighting& lighting, float* out_rgb) const;

  // The layout actually used (block size after clamping).
  const HaarRelighterLayout& layout() const { return layout_; }
  // Bytes of the blocked copy that shade() reads (slot table, offsets, values, steps).
  uint64_t blocked_bytes() const;
  // Number of (block, wavelet index) slices stored as dense columns, and their value count.
  uint64_t dense_slice_count() const { return dense_slices_; }
  uint64_t dense_entry_count() const { return dense_entries_; }

 private:
  // Slice of block b, wavelet index i: slot b·(6N² + 1) + i. Its entries (channels values
  // each) are [entry, next slot's entry), its offsets [offset, next slot's offset); no offsets
  // but some entries marks a dense column. Slot b·(6N² + 1) + 6N² closes block b.
  struct Slot {
    uint64_t entry = 0;
    uint64_t offset = 0;
  };
  template <class T>
  void shade_blocks(const std::vector<T>& values, const SparseLighting& lighting,
                    float* out_rgb) const;

  HaarTransfer transfer_;
  HaarRelighterLayout layout_;
  int64_t block_count_ = 0;
  std::vector<Slot> slots_;
  std::vector<uint16_t> block_offsets_;  // vertex − first vertex of the block
  std::vector<float> values_f32_;
  std::vector<int16_t> values_i16_;
  std::vector<int8_t> values_i8_;
  uint64_t dense_slices_ = 0;
  uint64_t dense_entries_ = 0;
};

// The plain walk of prt/haar/transfer.h's per-index lists (Ng et al.'s layout, no blocking):
// for each kept term, every (vertex, value) of its list, accumulated into out_rgb in float,
// then the per-vertex step. The reference for shade()'s blocked layout, and the "before" of
// the benchmarks. Same errors as shade().
Status shade_index_lists(const HaarTransfer& transfer, const SparseLighting& lighting,
                         float* out_rgb);

// Brute-force reference in double: out_rgb[3v + c] = Σ_t T_v,t,c · L_t,c over all 6N² texels,
// with dense transfer laid out as in prt/haar/transfer.h (vertex-major, 6N²·channels floats per
// vertex). Slow; for tests. Errors: size or channel mismatch.
Status shade_dense_reference(const float* dense_transfer, int64_t vertex_count, int size,
                             int channels, const CubeMap& lighting, double* out_rgb);

}  // namespace prt
