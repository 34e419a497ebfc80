// cpca_transfer.cpp — the CPCA glossy transfer: validation, reconstruction, truncation;
// see prt/glossy/cpca_transfer.h.
#include "prt/glossy/cpca_transfer.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace prt {

uint64_t CpcaTransfer::payload_bytes() const {
  const uint64_t d = dimension();
  const uint64_t ids = (2 * vertex_count + 3) / 4 * 4;  // uint16 ids padded to 4 bytes
  return 64 + 4 * uint64_t(cluster_count) * (vector_count + 1) * d + ids +
         4 * vertex_count * vector_count;
}

Status cpca_validate(const CpcaTransfer& t) {
  if (t.order < 1 || t.order > kMaxCpcaOrder || (t.channels != 1 && t.channels != 3)) {
    return Status::Error("cpca: bad order or channel count");
  }
  if (t.cluster_count == 0 || t.cluster_count > kMaxCpcaClusters) {
    return Status::Error("cpca: cluster count outside [1, 65535]");
  }
  const std::size_t d = t.dimension(), n = static_cast<std::size_t>(t.vertex_count);
  if (t.means.size() != t.cluster_count * d ||
      t.basis.size() != std::size_t(t.cluster_count) * t.vector_count * d ||
      t.cluster_of_vertex.size() != n || t.weights.size() != n * t.vector_count) {
    return Status::Error("cpca: array sizes do not match the header counts");
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (t.cluster_of_vertex[v] >= t.cluster_count) {
      return Status::Error("cpca: vertex " + std::to_string(v) + " has cluster id " +
                           std::to_string(t.cluster_of_vertex[v]) + " beyond the " +
                           std::to_string(t.cluster_count) + " clusters");
    }
  }
  for (const auto* a : {&t.means, &t.basis, &t.weights}) {
    for (float x : *a) {
      if (!std::isfinite(x)) return Status::Error("cpca: a non-finite value");
    }
  }
  return Status::Ok();
}

void cpca_reconstruct(const CpcaTransfer& t, std::size_t v, double* out) {
  const std::size_t d = t.dimension(), k = t.vector_count, q = t.cluster_of_vertex[v];
  for (std::size_t e = 0; e < d; ++e) out[e] = t.means[q * d + e];
  for (std::size_t j = 0; j < k; ++j) {
    const double w = t.weights[v * k + j];
    const float* u = t.basis.data() + (q * k + j) * d;
    for (std::size_t e = 0; e < d; ++e) out[e] += w * u[e];
  }
}

CpcaTransfer cpca_truncate(const CpcaTransfer& t, uint32_t k) {
  k = std::min(k, t.vector_count);
  CpcaTransfer c = t;
  c.vector_count = k;
  const std::size_t d = t.dimension(), kk = t.vector_count,
                    n = static_cast<std::size_t>(t.vertex_count);
  c.basis.resize(std::size_t(t.cluster_count) * k * d);
  for (std::size_t q = 0; q < t.cluster_count; ++q) {
    std::copy_n(t.basis.data() + q * kk * d, k * d, c.basis.data() + q * k * d);
  }
  c.weights.resize(n * k);
  for (std::size_t v = 0; v < n; ++v) {
    std::copy_n(t.weights.data() + v * kk, k, c.weights.data() + v * k);
  }
  return c;
}

}  // namespace prt
