// prt/glossy/cpca_kernel.h — the glossy shading kernel of CPCA-compressed transfer
// (prt/glossy/cpca_transfer.h; Sloan et al. 2003, [3] of docs/REFERENCES.md): transferred
// radiance L'_v = μ_q·L + Σ_k w_v,k (U_q,k·L) and exit radiance e_v,c = Σ_i b_v,c,i · L'_v,c,i.
// Channels, orders, the layouts of L', b and the exit radiance, and the thread rules are those
// of prt/glossy/kernel.h; CpcaKernel::prepare writes only its CpcaFrame.
//
// Arithmetic: every path accumulates in float with a separate multiply and add (never fused),
// in one fixed order, so the AVX2, AVX-512 and portable paths give identical bits:
//   per vertex, the three channels packed: lane g = c·n² + i of ⌈3n²/8⌉ vectors;
//   L' = P_0 + Σ_k w_k·P_k (k ascending), with P_k,c = U_k·L_c (k = 0: the mean) computed once
//   per frame in double and rounded to float; then per channel r = Σ_u (b masked to the
//   channel's lanes)_u·L'_u (u ascending) and e_c = h(r) with the 8-lane horizontal sum
//   h(r) = ((r0+r4)+(r2+r6)) + ((r1+r5)+(r3+r7)). Vertices are shaded in an order grouped by
//   cluster (no result depends on it). The AVX-512 path (KernelPath::Avx512; Auto where the
//   CPU has AVX-512F) accumulates 16 lanes a vector with the same per-lane operations, then
//   forms r as above.
// Error: |e − e_exact| ≲ (n² + K + 3)·2⁻²⁴ · Σ |terms| (docs/GLOSSY_CPCA.md).
// Nothing here throws; failures return prt::Status. C++17.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "prt/core/kernel_path.h"
#include "prt/core/status.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/lighting/sh_lighting.h"

namespace prt {

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

}  // namespace prt
