// bake/src/transfer_pass.cpp — the direct-transfer store and the gather-matrix rows shared by the
// samplers (transfer_pass.h).
#include "transfer_pass.h"

#include <algorithm>

#include "hit_side.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"

namespace prt::bake::detail {
namespace {

using sh::kPi;

}  // namespace

DirectTransfer::DirectTransfer(const scene::Scene& scene, const BakeOptions& options, int channels,
                               bool albedo_apart, prt::TransferData& data, VertexSums& sums,
                               bool shard_part)
    : scene_(scene),
      order_(options.order),
      K_(options.order * options.order),
      C_(channels),
      albedo_apart_(albedo_apart),
      keep_sums_(options.kind == prt::TransferKind::Interreflected || shard_part),
      compact_(options.adaptive.enabled && options.adaptive.compact_output),
      data_(data),
      sums_(sums) {
  const std::size_t V = scene.positions.size();
  std::size_t rows_out = V;
  if (compact_) {
    // A pilot of 256 vertices of a large scene at order 16 would otherwise allocate V × 256.
    row_of_.assign(V, 0);
    rows_out = 0;
    for (std::size_t v = 0; v < V; ++v)
      if (options.adaptive.vertex_mode.empty() || options.adaptive.vertex_mode[v] != kSkipVertex)
        row_of_[v] = rows_out++;
  }
  if (shard_part) rows_out = 0;
  data_.coefficients.assign(rows_out * static_cast<std::size_t>(C_ * K_), 0.f);
  if (keep_sums_ && !shard_part) sums_.visibility_sh.assign(V * static_cast<std::size_t>(K_), 0.0);
  zonal_.resize(static_cast<std::size_t>(order_));
  for (int l = 0; l < order_; ++l)
    zonal_[static_cast<std::size_t>(l)] = sh::clamped_cosine_zonal_coefficient(l);
}

void DirectTransfer::unshadowed(std::size_t v, double* out) const {
  const glm::dvec3 n = glm::normalize(glm::dvec3(scene_.normals[v]));
  sh::rotate_zonal(order_, zonal_.data(), n.x, n.y, n.z, out);
  for (int k = 0; k < K_; ++k) out[k] /= kPi;
}

void DirectTransfer::store(std::size_t v, const double* s_k, std::size_t slot) {
  const std::size_t K = static_cast<std::size_t>(K_);
  if (keep_sums_) {
    std::copy(s_k, s_k + K, &sums_.visibility_sh[slot * K]);
    return;
  }
  const std::size_t row = compact_ ? row_of_[v] : v;
  const std::size_t C = static_cast<std::size_t>(C_);
  for (std::size_t c = 0; c < C; ++c) {
    const double rho_c = albedo_apart_ ? 1.0 : scene_.albedo[v][static_cast<int>(c)];
    float* t = &data_.coefficients[(row * C + c) * K];
    for (std::size_t k = 0; k < K; ++k) t[k] = static_cast<float>(rho_c * s_k[k]);
  }
}

void cast_packet(const scene::RayCaster& caster, const glm::vec3& origin, const glm::vec3* dirs,
                 int count, float tfar, scene::RayCaster::Hit* hits, bool* occluded) {
  if (hits != nullptr) {
    caster.intersect_packet(origin, dirs, count, tfar, hits, /*face_side=*/false);
    for (int i = 0; i < count; ++i) occluded[i] = hits[i].hit;
  } else {
    caster.occluded_packet(origin, dirs, count, tfar, occluded);
  }
}

bool gather_front_hit(const scene::Scene& scene, const scene::RayCaster::Hit& hit,
                      const glm::vec3& dir, float weight, int gather_channels,
                      std::vector<std::pair<uint32_t, float>>& gathered) {
  if (!ray_hits_front_side(scene, hit.triangle, dir)) return false;
  const glm::uvec3 tri = scene.triangles[hit.triangle];
  const float b0 = (1.f - hit.u - hit.v) * weight, b1 = hit.u * weight, b2 = hit.v * weight;
  if (gather_channels == 0) {
    gathered.emplace_back(tri.x, b0);
    gathered.emplace_back(tri.y, b1);
    gathered.emplace_back(tri.z, b2);
    return true;
  }
  const glm::vec3 rho = scene.albedo_at(hit.triangle, hit.u, hit.v);
  const auto V = static_cast<uint32_t>(scene.positions.size());
  for (int c = 0; c < gather_channels; ++c) {
    const uint32_t block = static_cast<uint32_t>(c) * V;
    gathered.emplace_back(block + tri.x, b0 * rho[c]);
    gathered.emplace_back(block + tri.y, b1 * rho[c]);
    gathered.emplace_back(block + tri.z, b2 * rho[c]);
  }
  return true;
}

bool gather_front_hit_compact(const scene::Scene& scene, const scene::RayCaster::Hit& hit,
                              const glm::vec3& dir, const CompactGather& gather,
                              std::vector<CompactHit>& hits) {
  if (!ray_hits_front_side(scene, hit.triangle, dir)) return false;
  hits.push_back(quantise_hit(gather.triangle_index(hit.triangle), hit.u, hit.v));
  return true;
}

void append_row(std::vector<std::pair<uint32_t, float>>& gathered, double row_scale,
                BlockRows& br) {
  std::sort(gathered.begin(), gathered.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  uint32_t len = 0;
  for (std::size_t i = 0; i < gathered.size();) {
    const uint32_t col = gathered[i].first;
    double w = 0.0;
    for (; i < gathered.size() && gathered[i].first == col; ++i) w += gathered[i].second;
    if (w <= 0.0) continue;
    br.columns.push_back(col);
    br.weights.push_back(static_cast<float>(w * row_scale));
    ++len;
  }
  br.lengths.push_back(len);
}

void assemble_gather_matrix(std::vector<BlockRows>& rows, std::size_t V, SparseTransferMatrix& h) {
  h.row_offsets.assign(1, 0);
  h.row_offsets.reserve(V + 1);
  std::size_t total = 0;
  for (const BlockRows& br : rows) total += br.columns.size();
  h.columns.reserve(total);
  h.weights.reserve(total);
  for (BlockRows& br : rows) {
    for (uint32_t len : br.lengths) h.row_offsets.push_back(h.row_offsets.back() + len);
    h.columns.insert(h.columns.end(), br.columns.begin(), br.columns.end());
    h.weights.insert(h.weights.end(), br.weights.begin(), br.weights.end());
    br = BlockRows{};
  }
}

}  // namespace prt::bake::detail
