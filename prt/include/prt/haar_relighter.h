// prt/haar_relighter.h — relighting with sparse Haar lighting × sparse Haar transfer.
//
// Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003, Sec. 6: exit radiance is the product of a
// sparse lighting vector (prt/haar_approximation.h) and the sparse transport matrix stored
// per lighting coefficient (prt/haar_transfer.h):
//     B_v,c = Σ_{kept i} T̂_v,i,c · L̂_i,c
// (grey transfer, channels = 1, uses the same T̂ for R, G and B). With every term kept and no
// quantisation it equals the brute-force texel sum Σ_t T_v,t,c · L_t,c, because the Haar
// transform is orthonormal.
//
// The fast path walks, for each kept lighting coefficient, its list of (vertex, stored value)
// and accumulates L̂ · stored into out_rgb in float (one float accumulator per vertex and
// channel; with K terms the rounding error is at most about K·2⁻²⁴ of Σ|T̂·L̂|, and in
// practice √K of that); the per-vertex dequantisation step is applied once at the end.
// Compiles as C++17.
#pragma once

#include <cstdint>

#include "prt/haar_approximation.h"
#include "prt/haar_cube_map.h"
#include "prt/haar_transfer.h"
#include "prt/status.h"

namespace prt {

class HaarRelighter {
 public:
  explicit HaarRelighter(HaarTransfer transfer) : transfer_(std::move(transfer)) {}

  const HaarTransfer& transfer() const { return transfer_; }
  int64_t vertex_count() const { return transfer_.vertex_count; }

  // Writes RGB exit radiance for every vertex: out_rgb[3v + c], 3 · vertex_count() floats.
  // Thread-safe (const, no shared scratch). Errors: the lighting's cube size differs from the
  // transfer's, or an index is out of range (out_rgb is then left zeroed).
  Status shade(const SparseLighting& lighting, float* out_rgb) const;

 private:
  HaarTransfer transfer_;
};

// Brute-force reference in double: out_rgb[3v + c] = Σ_t T_v,t,c · L_t,c over all 6N² texels,
// with dense transfer laid out as in prt/haar_transfer.h (vertex-major, 6N²·channels floats per
// vertex). Slow; for tests. Errors: size or channel mismatch.
Status shade_dense_reference(const float* dense_transfer, int64_t vertex_count, int size,
                             int channels, const CubeMap& lighting, double* out_rgb);

}  // namespace prt
