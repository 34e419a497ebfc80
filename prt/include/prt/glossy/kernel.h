// prt/glossy/kernel.h — the glossy shading kernel of uncompressed transfer: transferred
// radiance L'_v = M_v·L per vertex from the matrices (prt/glossy/transfer.h), and exit radiance
// e_v,c = Σ_i b_v,c,i · L'_v,c,i for a per-vertex vector b the caller supplies (b_i(ω_o) = ∫ y_i f
// cos⁺θ_i dω_i in the local frame: it depends on the BRDF and the eye, not on the lighting; Sloan,
// Kautz & Snyder 2002 and Sloan et al. 2003, [2] and [3] of docs/REFERENCES.md).
//
// Channels: L is RGB (prt/lighting/sh_lighting.h). A grey matrix (channels = 1) gives L'_c = M·L_c
// for c = R, G, B; an RGB matrix gives L'_c = M_c·L_c. b has 1 (grey) or 3 (RGB) channels. Orders:
// j runs over min(order_file, order_light)² lighting coefficients (higher lighting bands are
// dropped, missing ones are zero); L' and b always have order_file² coefficients.
//
// Layouts (n = order_file, all float):
//   L' output:  out[(v_rel·3 + c)·n² + i]               v_rel = v − first
//   b input:    b[(v_rel·b_channels + c)·n² + i]
//   exit output: out_rgb[v_rel·3 + c]
//
// The CPCA form has its own kernel with the same conventions (prt/glossy/cpca_kernel.h); the
// slow references in double are in prt/glossy/reference.h.
//
// Arithmetic: every path accumulates in float with a separate multiply and add (never fused),
// in one fixed order, so the AVX2 path and the portable path give identical bits on any
// machine:
//   uncompressed  — 16 vertices side by side; L'_c,i = Σ_j M_i,j·L_c,j (j ascending), then
//                   e_c = Σ_i b_c,i·L'_c,i (i ascending), each lane on its own;
// Error: |e − e_exact| ≲ (n² + K + 3)·2⁻²⁴ · Σ |terms| (docs/GLOSSY_CPCA.md).
//
// Threads: the shading calls are const and use the stack only; call them from any number of
// threads on disjoint output ranges. The library starts no
// threads. Nothing here throws; failures return prt::Status. C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "prt/core/kernel_path.h"
#include "prt/core/status.h"
#include "prt/glossy/transfer.h"
#include "prt/lighting/sh_lighting.h"

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

}  // namespace prt
