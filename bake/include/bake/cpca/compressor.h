// bake/cpca/compressor.h — the CPCA compressor of glossy transfer matrices (Sloan, Hall, Hart &
// Snyder 2003; [3] of docs/REFERENCES.md): makes the prt::CpcaTransfer an engine relights
// (prt/glossy/cpca_transfer.h, which explains the representation), and measures its error.
// A tool (`prt compress`, `prt report --glossy`): it may start threads, so it is not part of
// the engine runtime. Declared in namespace prt beside the data it makes.
//
// Algorithm (docs/GLOSSY_CPCA.md): k-means++ seeding with a fixed-seed generator; then
// `iterations` rounds of [per-cluster PCA; reassignment of every vertex to the cluster that
// reconstructs it with the least squared error, among its `candidates` nearest cluster means].
// PCA: randomized subspace iteration on the centred members (never forming the D×D
// covariance), warm-started from the previous round's vectors, then Rayleigh–Ritz with a
// Jacobi eigensolver, all in double. When K ≥ min(members, D) the vectors span the members
// exactly. The weights are computed against the float-rounded mean and vectors, so
// reconstruction is exact to float rounding at full rank.
//
// Memory: `matrices` is only read (it may be a mapping of the file, bake/cpca/matrix_source.h);
// the run's own buffers — per-vertex state and weights, the cluster models, each thread's
// block of 256 centred members — are charged to a MemoryBudget of options.memory_limit first,
// and a metric's scaled copy is held in memory when it fits the limit, else in a mapped
// temporary file. A limit below the run's own buffers is refused with one line (a Status).
// Determinism: the result depends only on the data and the options, not on `threads`
// (threads work on disjoint vertices or clusters; every sum runs in a fixed order).
// Nothing here throws; failures return prt::Status.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/transfer.h"

namespace prt {

struct CpcaOptions {
  uint32_t clusters = 64;  // clamped to the vertex count
  uint32_t vectors = 8;    // K ≤ 4096 (ignored when target_relative_rms > 0)
  // > 0: choose the smallest K ≤ max_vectors whose relative RMS matrix error
  // sqrt(Σ_v |x_v − x̃_v|² / Σ_v |x_v|²) is at most this (an error when none is).
  double target_relative_rms = 0;
  uint32_t max_vectors = 32;
  uint32_t iterations = 6;        // rounds of PCA + reassignment (stops early when stable)
  uint32_t candidates = 8;        // clusters tried per vertex at reassignment (nearest means)
  uint32_t power_iterations = 2;  // subspace iterations per round (4 more in the first)
  uint64_t seed = 1;
  unsigned threads = 1;       // worker threads (std::thread); 0 or 1 = the calling thread only
  uint64_t memory_limit = 0;  // bytes it may hold (prt/core/memory_budget.h); 0: none
  // The metric, optional (empty: the plain squared error): per channel c a symmetric positive
  // definite n²×n² matrix G_c on the ROWS of the transfer matrices, channels · n⁴ values,
  // row_metric[(c·n² + i)·n² + k] = G_c,ik. The compressor then minimises the squared error
  //     Σ_v Σ_c tr(δ_v,cᵀ G_c δ_v,c),   δ_v,c = M_v,c − M̃_v,c,
  // by running on W_c M (W_c = G_c^{1/2}) and mapping the means and vectors back by W_c⁻¹. The
  // stored vectors are then orthonormal under that inner product (not the plain one); the file
  // format and the kernels are unchanged. target_relative_rms is then measured in the metric.
  // bake/cpca/relit_metric.h builds the metric under which this error is the expected relit error.
  std::vector<double> row_metric;
};

// Compresses `vertex_count` vectors of `channels`·order⁴ floats, vertex-major (the layout of
// GlossyTransferData::matrices). Errors: order 0 or > 16, channels not 1 or 3, a size
// mismatch, a non-finite value, K or clusters 0 (K = 0 is allowed: means only), no vertices,
// a row metric of the wrong size, not finite, not symmetric or not positive definite.
Result<CpcaTransfer> cpca_compress(uint32_t order, uint32_t channels, uint64_t vertex_count,
                                   const float* matrices, const CpcaOptions& options);
Result<CpcaTransfer> cpca_compress(const GlossyTransferData& data, const CpcaOptions& options);

// sqrt(Σ_v |x_v − x̃_v|² / Σ_v |x_v|²) in double (0 when every x_v is 0).
double cpca_relative_rms_error(const CpcaTransfer& cpca, const float* matrices);

// The same in a row metric (CpcaOptions::row_metric; empty: the plain error):
// sqrt(Σ_v Σ_c tr(δ_v,cᵀ G_c δ_v,c) / Σ_v Σ_c tr(M_v,cᵀ G_c M_v,c)); -1 when the metric is
// malformed.
double cpca_metric_relative_rms_error(const CpcaTransfer& cpca, const float* matrices,
                                      const std::vector<double>& row_metric);

// The same error when only the first k ≤ K vectors are used (a nested truncation).
double cpca_relative_rms_error_truncated(const CpcaTransfer& cpca, const float* matrices,
                                         uint32_t k);

}  // namespace prt
