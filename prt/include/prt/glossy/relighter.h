// prt/glossy/relighter.h — view-dependent shading of glossy transfer (prt/glossy/transfer.h):
// exit radiance of each vertex toward an eye point under SH lighting.
//
// Per vertex p with tangent frame (t, b = w·n × t, n) (orthonormalised once at creation):
//   ωo = normalize(eye − p) expressed in the frame: (t·ωo, b·ωo, n·ωo);
//   L'_c = M_p,c' · L_c  (c' = c for 3-channel transfer, 0 for grey transfer, which gives RGB
//                         under RGB lighting);
//   exit_c = Σ_i b_c,i(ωo) · L'_c,i,  b from the vertex's material (prt/glossy/brdf_projection.h).
// Orders as in prt/diffuse/relighter.h: K = min(order_file, order_light)² lighting coefficients are
// used (a higher-order lighting is truncated, a lower one zero-extended); b and L' have the file's
// n². View directions handled deliberately: the BRDFs are one-sided, so a vertex seen from below
// its tangent plane (n·(eye − p) ≤ 0, which happens near silhouettes where the interpolated normal
// turns away from the eye) has exit radiance 0, and so has a vertex at the eye point itself or
// an eye that is not finite. The renderer interpolates the vertex values (per-vertex ωo).
// Lighting is radiance in the units of the environment; exit is radiance in the same units.
// Arithmetic: shade() reads float matrices and accumulates in float — through the kernels of
// prt/glossy/kernel.h (GlossyShadingPath::kKernel, the default: AVX2 where the CPU has it,
// rounding like the portable kernel), through CpcaKernel for compressed transfer (create_cpca),
// or through the plain per-vertex loop (kPortable, kept as the simple path tests compare with);
// the reference (shade_glossy_reference) accumulates in double and takes b by direct quadrature
// of the BRDF. b always comes from BrdfProjection::evaluate (float), the same in every path.
// Threads: shade is const and uses only its own stack and heap scratch, so call it from any number
// of threads on disjoint ranges; the library starts none. Nothing throws; errors are
// prt::Status. Compiles as C++17. References: [2], [55] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/brdf_projection.h"
#include "prt/glossy/cpca_kernel.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/kernel.h"
#include "prt/glossy/transfer.h"
#include "prt/lighting/sh_lighting.h"

namespace prt {

// How GlossyRelighter::shade computes M·L and b·L' for uncompressed transfer.
enum class GlossyShadingPath {
  kKernel,    // GlossyKernel (blocks of 16 vertices; AVX2 or portable, identical bits)
  kPortable,  // one vertex at a time, skipping the rows of M whose b entry is 0
};

// The per-frame state of one lighting (GlossyRelighter::prepare): the lighting and, for
// compressed transfer, the per-cluster products of CpcaKernel::prepare.
struct GlossyFrame {
  ShLighting light;
  CpcaFrame cpca;
  const void* owner = nullptr;  // the relighter that prepared it
};

class GlossyRelighter {
 public:
  GlossyRelighter();
  GlossyRelighter(GlossyRelighter&&) noexcept;
  GlossyRelighter& operator=(GlossyRelighter&&) noexcept;
  ~GlossyRelighter();

  // Copies the transfer and frames and builds one BrdfProjection per material at the file's
  // order. Errors: inconsistent `data` (order outside [1, kMaxBrdfProjectionOrder], channels not
  // 1 or 3, array sizes, a material index out of range, a non-finite or degenerate frame), and
  // BrdfProjection::create's.
  static Result<GlossyRelighter> create(const GlossyTransferData& data,
                                        const BrdfProjectionOptions& options = {});
  // Same, taking over the matrices of `data` instead of copying them (a file's bulk).
  static Result<GlossyRelighter> create(GlossyTransferData&& data,
                                        const BrdfProjectionOptions& options = {});
  static Result<GlossyRelighter> create(GlossyTransferData&& data,
                                        const BrdfProjectionOptions& options,
                                        GlossyShadingPath path);
  // Compressed transfer: positions, frames and materials from `geometry` (its matrices are not
  // read and may be empty), the matrices from `cpca` (prt/glossy/cpca_transfer.h), shaded through
  // CpcaKernel. Errors: those above, and a CPCA whose vertex count, order or channels differ from
  // geometry's, or that cpca_validate refuses.
  static Result<GlossyRelighter> create_cpca(GlossyTransferData&& geometry,
                                             const CpcaTransfer& cpca,
                                             const BrdfProjectionOptions& options = {});

  std::size_t vertex_count() const;
  int order() const;
  int channels() const;
  const std::vector<BrdfProjection>& projections() const;  // one per material
  bool compressed() const;                                 // made by create_cpca
  GlossyShadingPath path() const;

  // Once per lighting: what shade(frame, ...) needs (for compressed transfer the per-cluster
  // products, (K + 1)·3 matrix–vector products per cluster). Errors: out of memory.
  Status prepare(const ShLighting& light, GlossyFrame* frame) const;

  // Exit radiance toward eye_xyz (scene frame, scene units) of vertices
  // [first_vertex, first_vertex + count) under the frame's lighting: 3 floats per vertex into
  // out_rgb[0 .. 3·count). Errors: range beyond vertex_count(), null eye or null out_rgb with
  // count > 0, a frame this relighter did not prepare.
  Status shade(const GlossyFrame& frame, const float eye_xyz[3], std::size_t first_vertex,
               std::size_t count, float* out_rgb) const;

  // The same preparing the frame on each call (for compressed transfer that repeats the
  // per-cluster products: prefer prepare() once and shade(frame, ...) per range).
  Status shade(const ShLighting& light, const float eye_xyz[3], std::size_t first_vertex,
               std::size_t count, float* out_rgb) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// The slow reference for vertex v: the same frame, order rule and view handling, b by
// project_brdf_slice() (direct quadrature of the material's BRDF), everything in double.
// Errors: v out of range, inconsistent `data`, make_brdf()'s.
Status shade_glossy_reference(const GlossyTransferData& data, const ShLighting& light,
                              const double eye_xyz[3], std::size_t v,
                              const SliceQuadrature& quadrature, double out_rgb[3]);

}  // namespace prt
