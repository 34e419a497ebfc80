// bake/src/transfer_pass.h (private) — what the phases of bake_transfer share: the direct
// transfer being stored, the rows of the gather matrix H being built, and the sampling pass that
// the two samplers (fixed_sampler.cpp: the same N rays at every vertex; adaptive_sampler.cpp:
// rays allocated to where the error is) both fill in. transfer_baker.cpp runs the phases.
//
// Conventions: SH of bake/transfer_baker.h (order n, K = n² coefficients, real orthonormal, polar
// axis +z); the direct transfer S_v,k = (1/N) Σ V(ω_s) Y_k(ω_s), grey, and T = ρ_c·S once stored
// (T = S when the albedo is kept apart); rows of H as derived at the top of transfer_baker.cpp.
// With the albedo kept apart, H carries the albedo of each hit point, per channel: a hit on
// vertex j's triangle adds b_j·ρ_c(hit) to column c·V + j of its row (C channel blocks of V
// columns; transfer_baker.cpp splits them into one matrix per channel before the solve).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bake/adaptive/occluder_caps.h"
#include "bake/compact_gather.h"
#include "bake/interreflection_solver.h"
#include "bake/progress.h"
#include "bake/transfer_baker.h"
#include "scene/ray_caster.h"

namespace prt {
class MemoryBudget;
}  // namespace prt

namespace prt::bake::detail {

struct HitRecord;  // hit_records.h

inline constexpr std::size_t kVertexBlock = 64;  // vertices per parallel task (fixed: determinism)
inline constexpr std::size_t kAuditStride = 8;   // adaptive: every 8th sampled vertex audits

// The rows of H produced by one block of vertices.
struct BlockRows {
  std::vector<uint32_t> lengths;
  std::vector<uint32_t> columns;
  std::vector<float> weights;
};

// Per-vertex results of the sampling pass besides the transfer.
struct VertexSums {
  std::vector<double> visibility_sh;  // V × K: (1/N) Σ V Y_k (grey; albedo applied later)
  std::vector<float> ao;              // V
  std::vector<float> bent;            // 3V
};

// Where a vertex's direct transfer goes: straight into the float output as ρ_c·S for shadowed
// and unshadowed bakes, kept in double (sums.visibility_sh) for the interreflection solve.
// Compact output (AdaptiveSampling::compact_output) stores rows for the vertices that are not
// kSkipVertex only, in vertex order.
class DirectTransfer {
 public:
  // `shard_part`: a shard of a farm bake (bake/transfer_part.h) keeps every sampled S_v in
  // sums.visibility_sh (double, for its part file) and allocates no output coefficients; the
  // caller sizes the sums for the shard's rows (SamplingPass::sums_by_row).
  DirectTransfer(const scene::Scene& scene, const BakeOptions& options, int channels,
                 bool albedo_apart, prt::TransferData& data, VertexSums& sums,
                 bool shard_part = false);
  // The analytic unshadowed transfer of vertex v, grey: (1/π) · rotate_zonal(clamped cosine, n).
  void unshadowed(std::size_t v, double* out) const;
  // Stores S_v (K values) as described above; kept sums go to row `slot` of
  // sums.visibility_sh (the vertex itself unless a shard's pass says otherwise).
  void store(std::size_t v, const double* s_k) { store(v, s_k, v); }
  void store(std::size_t v, const double* s_k, std::size_t slot);

 private:
  const scene::Scene& scene_;
  int order_, K_, C_;
  bool albedo_apart_;
  bool keep_sums_;  // S_v goes to sums.visibility_sh (interreflected, or a shard's part)
  bool compact_;
  std::vector<std::size_t> row_of_;
  std::vector<double> zonal_;
  prt::TransferData& data_;
  VertexSums& sums_;
};

// The sampling pass: one of the samplers fills sums, the transfer (through `direct`), the rows
// of H per block and the ray counts.
struct SamplingPass {
  const scene::Scene& scene;
  const BakeOptions& options;
  const scene::RayCaster& caster;
  ProgressSink* progress;
  std::size_t V;
  int order, K;
  int N;  // the fixed recipe's samples per vertex
  bool need_sh_rays, interreflect;
  int gather_channels;  // 0: H of geometric weights; C: H with the hit's albedo, C blocks
  DirectTransfer& direct;
  VertexSums& sums;
  BakeStatistics& st;
  // Adaptive only: per-vertex modes and occluder caps.
  const std::vector<uint8_t>& modes;
  const OccluderCaps& caps;
  // Outputs per block of kVertexBlock vertices.
  std::vector<BlockRows> rows;  // interreflected only
  std::vector<uint64_t> block_rays, block_back_hits;
  // Interreflected with the compact gather (fixed recipe only): block b of the pass is block b of
  // the gather, rows in its (Morton) order; each block's bytes are charged to `budget` (when not
  // null) before the block is stored.
  CompactGather* compact = nullptr;
  MemoryBudget* budget = nullptr;
  // With compact: the per-triangle records of the hit test (hit_records.h), when made; the fixed
  // sampler then judges sides and renumbers triangles through them.
  const HitRecord* hit_records = nullptr;
  // A shard of a farm bake (bake/transfer_part.h, fixed recipe only): the rows [first_row,
  // end_row) of `row_order` (the Morton order of compact_gather.h) instead of every vertex; block
  // b covers rows first_row + 64b onwards, and a compact gather's blocks go to part_blocks[b]
  // instead of the gather (which then only renumbers the hit triangles).
  const std::vector<uint32_t>* row_order = nullptr;
  std::size_t first_row = 0, end_row = ~std::size_t{0};
  std::vector<CompactGather::Block>* part_blocks = nullptr;
  // With row_order: sums (visibility_sh, ao, bent) hold the shard's rows only, row r at
  // r − first_row, instead of every vertex (a shard then touches none of the others' sums).
  bool sums_by_row = false;

  std::size_t row_end() const { return end_row < V ? end_row : V; }
  std::size_t blocks() const { return (row_end() - first_row + kVertexBlock - 1) / kVertexBlock; }
  uint8_t mode_of(std::size_t v) const { return modes.empty() ? kSampleVertex : modes[v]; }
  bool capped(std::size_t v) const {
    return !caps.covered.empty() && caps.covered[v] && caps.count(v) > 0;
  }
};

// The fixed recipe: N cosine-distributed rays at every vertex.
void sample_fixed(SamplingPass& pass);
// Adaptive sampling (transfer_baker.h, AdaptiveSampling): min_samples everywhere, then rounds of
// Neyman allocation until the calibrated error model meets the budget.
void sample_adaptive(SamplingPass& pass);

// Casts `count` ≤ kPacketSize rays from `origin`: closest hits into `hits` (occluded[i] = a hit)
// when `hits` is not null, occlusion only otherwise. Hit::front_face is not filled in (the
// samplers judge the side with hit_side.h).
void cast_packet(const scene::RayCaster& caster, const glm::vec3& origin, const glm::vec3* dirs,
                 int count, float tfar, scene::RayCaster::Hit* hits, bool* occluded);

// Appends the hit triangle's vertices, weighted by barycentrics × the sample's weight (1 under
// cosine-weighted sampling, bake/adaptive/cap_sampling.h's w in caps), to a row being gathered;
// with gather_channels = C > 0, one entry per channel c at column c·V + j, also weighted by the
// albedo at the hit point (Scene::albedo_at: the texture, bilinear). False (nothing added) when
// the ray sees the back side: the flat facet's geometric normal, oriented by the triangle's
// vertex normals (hit_side.h). A back face occludes only.
bool gather_front_hit(const scene::Scene& scene, const scene::RayCaster::Hit& hit,
                      const glm::vec3& dir, float weight, int gather_channels,
                      std::vector<std::pair<uint32_t, float>>& gathered);

// The compact gather's form of gather_front_hit (geometric weights only): appends the hit as a
// CompactHit (renumbered triangle, quantised barycentrics); false for a back face.
bool gather_front_hit_compact(const scene::Scene& scene, const scene::RayCaster::Hit& hit,
                              const glm::vec3& dir, const CompactGather& gather,
                              std::vector<CompactHit>& hits);

// Merges duplicate columns of the gathered entries into one row of H, scaled by row_scale.
void append_row(std::vector<std::pair<uint32_t, float>>& gathered, double row_scale,
                BlockRows& rows);

// Concatenates the blocks' rows into H (the blocks are emptied).
void assemble_gather_matrix(std::vector<BlockRows>& rows, std::size_t V, SparseTransferMatrix& h);

}  // namespace prt::bake::detail
