// prt/glossy_kernel.h — the glossy shading kernels: transferred radiance L'_v = M_v·L per
// vertex, from the uncompressed matrices (prt/glossy_transfer.h) or from their CPCA form
// (prt/cpca.h), and exit radiance e_v,c = Σ_i b_v,c,i · L'_v,c,i for a per-vertex vector b
// the caller supplies (b_i(ω_o) = ∫ y_i f cos⁺θ_i dω_i in the local frame: it depends on the
// BRDF and the eye, not on the lighting; Sloan, Kautz & Snyder 2002 and Sloan et al. 2003,
// [2] and [3] of docs/REFERENCES.md).
//
// Channels: L is RGB (prt/lighting.h). A grey matrix (channels = 1) gives L'_c = M·L_c for
// c = R, G, B; an RGB matrix gives L'_c = M_c·L_c. b has 1 (grey) or 3 (RGB) channels.
// Orders: j runs over min(order_file, order_light)² lighting coefficients (higher lighting
// bands are dropped, missing ones are zero); L' and b always have order_file² coefficients.
//
// Layouts (n = order_file, all float):
//   L' output:  out[(v_rel·3 + c)·n² + i]               v_rel = v − first
//   b input:    b[(v_rel·b_channels + c)·n² + i]
//   exit output: out_rgb[v_rel·3 + c]
//
// Arithmetic: every path accumulates in float with a separate multiply and add (never fused),
// in one fixed order, so the AVX2 path and the portable path (and, for CPCA, the AVX-512 path)
// give identical bits on any machine:
//   uncompressed  — 16 vertices side by side; L'_c,i = Σ_j M_i,j·L_c,j (j ascending), then
//                   e_c = Σ_i b_c,i·L'_c,i (i ascending), each lane on its own;
//   CPCA          — per vertex, the three channels packed: lane g = c·n² + i of ⌈3n²/8⌉
//                   vectors; L' = P_0 + Σ_k w_k·P_k (k ascending), with P_k,c = U_k·L_c (k = 0:
//                   the mean) computed once per frame in double and rounded to float; then per
//                   channel r = Σ_u (b masked to the channel's lanes)_u·L'_u (u ascending) and
//                   e_c = h(r) with the 8-lane horizontal sum
//                   h(r) = ((r0+r4)+(r2+r6)) + ((r1+r5)+(r3+r7)). Vertices are shaded in an
//                   order grouped by cluster (no result depends on it). The AVX-512 path
//                   (KernelPath::Avx512; Auto where the CPU has AVX-512F) accumulates 16 lanes
//                   a vector with the same per-lane operations, then forms r as above.
// Error: |e − e_exact| ≲ (n² + K + 3)·2⁻²⁴ · Σ |terms| (docs/GLOSSY_CPCA.md).
//
// Threads: the shading calls are const and use the stack only; call them from any number of
// threads on disjoint output ranges. CpcaKernel::prepare writes only its CpcaFrame. The
// library starts no threads. Nothing here throws; failures return prt::Status. C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "prt/cpca.h"
#include "prt/glossy_transfer.h"
#include "prt/lighting.h"
#include "prt/relighter.h"  // KernelPath
#include "prt/status.h"

namespace prt {

// Uncompressed matrices, copied into blocks of 16 vertices ([c][i][j][lane]).
class GlossyKernel {
 public:
  GlossyKernel();
  GlossyKernel(GlossyKernel&&) noexcept;
  GlossyKernel& operator=(GlossyKernel&&) noexcept;
  ~GlossyKernel();

  // Errors: order outside [1, 16], channels not 1 or 3, a size mismatch, a non-finite entry.
  static Result<GlossyKernel> create(const GlossyTransferData& data);

  std::size_t vertex_count() const;
  int order() const;
  int channels() const;

  // L' of vertices [first, first + count). Errors: range beyond vertex_count(), null output.
  Status transfer(const ShLighting& light, std::size_t first, std::size_t count, float* out) const;
  // Exit radiance (RGB) of the same vertices with the caller's b (b_channels 1 or 3).
  Status shade(const ShLighting& light, const float* b, int b_channels, std::size_t first,
               std::size_t count, float* out_rgb) const;

  // The same choosing the implementation (tests and benchmarks).
  Status transfer_using(KernelPath path, const ShLighting& light, std::size_t first,
                        std::size_t count, float* out) const;
  Status shade_using(KernelPath path, const ShLighting& light, const float* b, int b_channels,
                     std::size_t first, std::size_t count, float* out_rgb) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// The per-frame products of a CpcaKernel with one lighting (reuse it across frames: its
// storage is kept).
struct CpcaFrame {
  std::vector<float> projected;  // [cluster][k ≤ K][c·n² + i, padded to stride], k = 0 the mean
  std::size_t stride = 0;        // 3·n² rounded up to 8
  std::size_t cluster_count = 0;
  std::size_t vectors = 0;      // K
  const void* owner = nullptr;  // the CpcaKernel that prepared it
};

class CpcaKernel {
 public:
  CpcaKernel();
  CpcaKernel(CpcaKernel&&) noexcept;
  CpcaKernel& operator=(CpcaKernel&&) noexcept;
  ~CpcaKernel();

  // Errors: those of cpca_validate().
  static Result<CpcaKernel> create(const CpcaTransfer& cpca);

  std::size_t vertex_count() const;
  int order() const;
  int channels() const;
  int vectors() const;

  // Once per frame: P_q,k,c = U_q,k·L_c for every cluster (double sums, rounded to float).
  // Errors: out of memory.
  Status prepare(const ShLighting& light, CpcaFrame* frame) const;

  // As GlossyKernel's, from a frame this object prepared (else an error).
  Status transfer(const CpcaFrame& frame, std::size_t first, std::size_t count, float* out) const;
  Status shade(const CpcaFrame& frame, const float* b, int b_channels, std::size_t first,
               std::size_t count, float* out_rgb) const;
  Status transfer_using(KernelPath path, const CpcaFrame& frame, std::size_t first,
                        std::size_t count, float* out) const;
  Status shade_using(KernelPath path, const CpcaFrame& frame, const float* b, int b_channels,
                     std::size_t first, std::size_t count, float* out_rgb) const;

  // Whether this CPU runs KernelPath::Avx512 (and KernelPath::Auto picks it).
  static bool avx512_path_available();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// The slow references, in double, straight from the vertex-major floats:
// L' of vertex v (3·n² doubles, channel-major) and its exit radiance with b (b_channels·n²
// floats for this vertex). Errors: v out of range, inconsistent data, bad b_channels.
Status glossy_transfer_reference(const GlossyTransferData& data, const ShLighting& light,
                                 std::size_t v, double* out);
Status glossy_shade_reference(const GlossyTransferData& data, const ShLighting& light,
                              const float* b_of_v, int b_channels, std::size_t v,
                              double out_rgb[3]);
// The same from the CPCA form (the matrix reconstructed in double, then applied).
Status cpca_transfer_reference(const CpcaTransfer& cpca, const ShLighting& light, std::size_t v,
                               double* out);
Status cpca_shade_reference(const CpcaTransfer& cpca, const ShLighting& light, const float* b_of_v,
                            int b_channels, std::size_t v, double out_rgb[3]);

}  // namespace prt
