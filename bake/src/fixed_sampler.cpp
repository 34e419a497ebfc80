// bake/src/fixed_sampler.cpp — the fixed recipe of the sampling pass: N Owen-scrambled Sobol'
// cosine-distributed rays at every vertex (transfer_pass.h).
#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

#include "bake/obscurance_falloff.h"
#include "bake/sampling.h"
#include "hit_records.h"
#include "prt/core/memory_budget.h"
#include "sh/basis.h"
#include "transfer_pass.h"

namespace prt::bake::detail {
namespace {

// One vertex: its direct transfer, AO, bent normal and (interreflected) its row of H.
struct FixedVertexSampler {
  SamplingPass& pass;
  std::size_t block;
  glm::vec3 dirs[kPacketSize];
  bool occluded[kPacketSize];
  scene::RayCaster::Hit hits[kPacketSize];
  std::vector<float> y, packet_sum;
  std::vector<double> acc;
  std::vector<std::pair<uint32_t, float>> gathered;
  CompactGather::Block compact;  // the block's rows of a compact gather

  FixedVertexSampler(SamplingPass& p, std::size_t blk)
      : pass(p),
        block(blk),
        y(static_cast<std::size_t>(p.K)),
        packet_sum(static_cast<std::size_t>(p.K)),
        acc(static_cast<std::size_t>(p.K)) {}

  // The packet's hits into the vertex's row of H; back faces are counted only.
  void gather_hits() {
    for (int i = 0; i < kPacketSize; ++i) {
      if (!hits[i].hit) continue;
      const bool front =
          pass.hit_records ? gather_front_hit_record(pass.hit_records, hits[i].triangle, hits[i].u,
                                                     hits[i].v, dirs[i], compact.hits)
          : pass.compact
              ? gather_front_hit_compact(pass.scene, hits[i], dirs[i], *pass.compact, compact.hits)
              : gather_front_hit(pass.scene, hits[i], dirs[i], 1.f, pass.gather_channels, gathered);
      if (!front) ++pass.block_back_hits[block];
    }
  }

  // Returns the rays cast; the sums go to row `slot` (SamplingPass::sums_by_row).
  uint64_t sample(std::size_t v, std::size_t slot) {
    const int K = pass.K, N = pass.N;
    const bool need_sh = pass.need_sh_rays, interreflect = pass.interreflect;
    const float tfar = std::numeric_limits<float>::infinity();
    const double inv_n = 1.0 / N;
    const glm::vec3 n = glm::normalize(pass.scene.normals[v]);
    const glm::vec3 origin = pass.caster.vertex_origin(static_cast<uint32_t>(v));
    std::fill(acc.begin(), acc.end(), 0.0);
    gathered.clear();
    const std::size_t hits_before = compact.hits.size();
    // Obscurance (obscurance_falloff.h) needs every hit's distance; plain AO weighs by visibility.
    const ObscuranceOptions& obscurance = pass.options.obscurance;
    const bool want_hits = interreflect || obscurance.enabled();
    double open_sum = 0.0;  // Σ ρ(d_s), ρ = V(ω_s) for plain AO
    glm::dvec3 bent(0.0);
    uint64_t rays = 0;
    for (int first = 0; first < N; first += kPacketSize) {
      generate_cosine_directions(n, pass.options.seed, v, static_cast<uint32_t>(first), kPacketSize,
                                 dirs);
      cast_packet(pass.caster, origin, dirs, kPacketSize, tfar, want_hits ? hits : nullptr,
                  occluded);
      rays += kPacketSize;
      // SH of the visible directions: summed in float over the 16 rays of a packet (at most 16
      // terms of magnitude ≤ ~3.5), then added to the double accumulator.
      bool any = false;
      if (need_sh) std::fill(packet_sum.begin(), packet_sum.end(), 0.f);
      for (int i = 0; i < kPacketSize; ++i) {
        const double open =
            !obscurance.enabled() ? (occluded[i] ? 0.0 : 1.0)
            : hits[i].hit ? obscurance_weight(obscurance.falloff, hits[i].t, obscurance.distance)
                          : 1.0;
        open_sum += open;
        bent += open * glm::dvec3(dirs[i]);
        if (occluded[i] || !need_sh) continue;
        any = true;
        sh::evaluate(pass.order, dirs[i].x, dirs[i].y, dirs[i].z, y.data());
        for (int k = 0; k < K; ++k) packet_sum[k] += y[k];
      }
      if (any)
        for (int k = 0; k < K; ++k) acc[k] += static_cast<double>(packet_sum[k]);
      if (interreflect) gather_hits();
    }
    if (need_sh)
      for (int k = 0; k < K; ++k) acc[k] *= inv_n;
    if (need_sh) pass.direct.store(v, acc.data(), slot);
    pass.sums.ao[slot] = static_cast<float>(open_sum * inv_n);
    const double bl = glm::length(bent);
    const glm::vec3 bn = bl > 0 ? glm::vec3(bent / bl) : n;
    pass.sums.bent[3 * slot + 0] = bn.x;
    pass.sums.bent[3 * slot + 1] = bn.y;
    pass.sums.bent[3 * slot + 2] = bn.z;
    if (interreflect && !pass.compact) append_row(gathered, inv_n, pass.rows[block]);
    if (interreflect && pass.compact)
      compact.lengths.push_back(static_cast<uint32_t>(compact.hits.size() - hits_before));
    return rays;
  }
};

}  // namespace

// Block blk covers rows [first_row + blk·64, ...): the vertices themselves, the compact gather's
// rows (its Morton order) or a shard's rows of row_order; a compact block is charged and stored
// at the end (in the gather, or in the shard's part_blocks).
void sample_fixed(SamplingPass& pass) {
  const std::size_t first = pass.first_row, end = pass.row_end();
  tbb::parallel_for(std::size_t(0), pass.blocks(), [&](std::size_t blk) {
    FixedVertexSampler sampler(pass, blk);
    const std::size_t r_begin = first + blk * kVertexBlock;
    const std::size_t r_end = std::min(end, r_begin + kVertexBlock);
    uint64_t rays = 0;
    for (std::size_t r = r_begin; r < r_end; ++r) {
      const std::size_t v = pass.row_order ? (*pass.row_order)[r]
                            : pass.compact ? pass.compact->vertex_of_row(r)
                                           : r;
      rays += sampler.sample(v, pass.sums_by_row ? r - first : v);
    }
    if (pass.compact) {
      CompactGather::Block& b = sampler.compact;
      if (pass.budget)
        pass.budget->charge(CompactGather::block_bytes(b.lengths.size(), b.hits.size()),
                            "the gather matrix");
      b.hits.shrink_to_fit();
      if (pass.part_blocks)
        (*pass.part_blocks)[blk] = std::move(b);
      else
        pass.compact->set_block(blk, std::move(b));
    }
    pass.block_rays[blk] = rays;
    if (pass.progress) pass.progress->advance(r_end - r_begin, rays);
  });
}

}  // namespace prt::bake::detail
