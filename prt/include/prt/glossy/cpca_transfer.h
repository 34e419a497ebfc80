// prt/glossy/cpca_transfer.h — glossy transfer compressed by clustered principal component
// analysis (CPCA; Sloan, Hall, Hart & Snyder 2003; [3] of docs/REFERENCES.md): the data an
// engine relights from, its validation and its reconstruction. The compressor that makes it is
// a tool, not part of the runtime: bake/cpca/compressor.h.
//
// Each vertex's transfer (prt/glossy/transfer.h: `channels` matrices of n²×n², row-major) is a
// vector x_v of D = channels·n⁴ floats. CPCA partitions the vertices into clusters q and keeps,
// per cluster, a mean μ_q and K orthonormal principal vectors U_q,1..K; a vertex keeps its
// cluster id and K weights w_v,k = U_q,k · (x_v − μ_q), and is reconstructed as
//     x̃_v = μ_q + Σ_k w_v,k U_q,k .
// Under lighting L the transferred radiance is then L'_v = μ_q·L + Σ_k w_v,k (U_q,k·L): the
// matrix–vector products are done once per cluster and frame (prt/glossy/cpca_kernel.h).
// Nothing here throws; failures return prt::Status. Compiles as C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/transfer.h"

namespace prt {

inline constexpr uint32_t kMaxCpcaOrder = 16;
inline constexpr uint32_t kMaxCpcaClusters = 65535;  // ids are stored as uint16 (docs/FORMAT.md)

struct CpcaTransfer {
  uint32_t order = 5;     // SH order n of the matrices
  uint32_t channels = 1;  // 1 (grey) or 3 (RGB) matrices per vertex
  uint32_t cluster_count = 0;
  uint32_t vector_count = 0;  // K, the same for every cluster
  uint64_t vertex_count = 0;
  uint64_t fingerprint = 0;  // geometry fingerprint of the source GlossyTransferData (0: none)
  // cluster_count · D: means[q·D + d], d = (c·n² + i)·n² + j as in GlossyTransferData.
  std::vector<float> means;
  // cluster_count · K · D: basis[(q·K + k)·D + d]; per cluster orthonormal (a vector may be
  // zero when the cluster has fewer independent members than K).
  std::vector<float> basis;
  std::vector<uint32_t> cluster_of_vertex;  // vertex_count, each < cluster_count
  std::vector<float> weights;               // vertex_count · K: weights[v·K + k]

  std::size_t dimension() const { return std::size_t(channels) * order * order * order * order; }
  // Bytes of the compressed form as stored (prt/formats/cpca_file.h; docs/GLOSSY_CPCA.md): header
  // and arrays, without the geometry and materials of the uncompressed file.
  uint64_t payload_bytes() const;
};

// Checks sizes, ids and finiteness (a one-line error naming the problem).
Status cpca_validate(const CpcaTransfer& cpca);

// x̃_v in double (D values). Precondition: cpca_validate(cpca).ok(), v < vertex_count.
void cpca_reconstruct(const CpcaTransfer& cpca, std::size_t v, double* out);

// Keeps only the first k ≤ K vectors of every cluster (the weights of the rest are dropped).
CpcaTransfer cpca_truncate(const CpcaTransfer& cpca, uint32_t k);

}  // namespace prt
