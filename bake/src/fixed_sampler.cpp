// bake/src/fixed_sampler.cpp — the fixed recipe of the sampling pass: N Owen-scrambled Sobol'
// cosine-distributed rays at every vertex (transfer_pass.h).
#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

#include "bake/obscurance_falloff.h"
#include "bake/sampling.h"
#include "prt/core/memory_budget.h"
#include "sh/basis.h"
#include "transfer_pass.h"

namespace prt::bake::detail {
namespace {

// Rays of one batch traced together: at most this many (whole vertices; at least one vertex).
constexpr std::size_t kTraceBatchRays = 16384;

// The direction's cell: each component quantised to 16 levels over [−1, 1], interleaved
// (Morton, so octant first): 4096 cells, neighbouring cells for neighbouring directions.
constexpr uint32_t kDirectionCells = 4096;
uint32_t direction_cell(const glm::vec3& d) {
  uint32_t code = 0;
  for (int a = 0; a < 3; ++a) {
    const float t = std::clamp((d[a] + 1.f) * 8.f, 0.f, 15.f);
    const uint32_t q = static_cast<uint32_t>(t);
    for (int bit = 0; bit < 4; ++bit) code |= ((q >> bit) & 1u) << (3 * bit + (2 - a));
  }
  return code;
}

// One block: a batch of vertices' rays traced in coherent order (trace), then each vertex's
// direct transfer, AO, bent normal and (interreflected) its row of H, accumulated in sample order.
// Tracing order changes only which rays share a packet: each ray's hit is its own, and every sum
// runs over the rays of a vertex in the same order as casting them vertex by vertex would.
struct FixedVertexSampler {
  SamplingPass& pass;
  std::size_t block;
  int rays_per_vertex;                      // N rounded up to whole packets
  std::vector<glm::vec3> dirs, origins;     // the batch's rays (vertex-major), origins per vertex
  std::vector<scene::RayCaster::Hit> hits;  // per ray, when hits are wanted
  std::vector<bool> occluded;               // per ray
  std::vector<uint32_t> cells, order;       // each ray's direction cell; rays by cell
  std::vector<uint32_t> cell_start;
  std::vector<float> y, packet_sum;
  std::vector<double> acc;
  std::vector<std::pair<uint32_t, float>> gathered;
  CompactGather::Block compact;  // the block's rows of a compact gather

  FixedVertexSampler(SamplingPass& p, std::size_t blk)
      : pass(p),
        block(blk),
        rays_per_vertex((p.N + kPacketSize - 1) / kPacketSize * kPacketSize),
        y(static_cast<std::size_t>(p.K)),
        packet_sum(static_cast<std::size_t>(p.K)),
        acc(static_cast<std::size_t>(p.K)) {}

  bool want_hits() const { return pass.interreflect || pass.options.obscurance.enabled(); }

  // Vertices per batch.
  std::size_t batch_vertices() const {
    return std::max<std::size_t>(1, kTraceBatchRays / static_cast<std::size_t>(rays_per_vertex));
  }

  // Generates the rays of vertices vs[0, m) and traces them in packets of 16 sorted by direction.
  void trace(const std::size_t* vs, std::size_t m) {
    const std::size_t R = static_cast<std::size_t>(rays_per_vertex), total = m * R;
    dirs.resize(total);
    origins.resize(m);
    occluded.assign(total, false);
    const bool with_hits = want_hits();
    if (with_hits) hits.assign(total, scene::RayCaster::Hit{});
    cells.resize(total);
    order.resize(total);
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t v = vs[j];
      const glm::vec3 n = glm::normalize(pass.scene.normals[v]);
      origins[j] = pass.caster.vertex_origin(static_cast<uint32_t>(v));
      for (std::size_t first = 0; first < R; first += kPacketSize)
        generate_cosine_directions(n, pass.options.seed, v, static_cast<uint32_t>(first),
                                   kPacketSize, &dirs[j * R + first]);
    }
    // Rays by direction cell, then by index (a counting sort: a fixed order).
    cell_start.assign(kDirectionCells + 1, 0);
    for (std::size_t i = 0; i < total; ++i) ++cell_start[(cells[i] = direction_cell(dirs[i])) + 1];
    for (uint32_t c = 0; c < kDirectionCells; ++c) cell_start[c + 1] += cell_start[c];
    for (std::size_t i = 0; i < total; ++i)
      order[cell_start[cells[i]]++] = static_cast<uint32_t>(i);
    const float tfar = std::numeric_limits<float>::infinity();
    glm::vec3 lane_o[kPacketSize], lane_d[kPacketSize];
    scene::RayCaster::Hit lane_hits[kPacketSize];
    bool lane_occ[kPacketSize];
    uint32_t lane_ray[kPacketSize];
    for (std::size_t p = 0; p < total; p += kPacketSize) {
      const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, total - p));
      for (int l = 0; l < count; ++l) {
        lane_ray[l] = order[p + static_cast<std::size_t>(l)];
        lane_o[l] = origins[lane_ray[l] / R];
        lane_d[l] = dirs[lane_ray[l]];
      }
      if (with_hits) {
        pass.caster.intersect_packet(lane_o, lane_d, count, tfar, lane_hits);
        for (int l = 0; l < count; ++l) {
          hits[lane_ray[l]] = lane_hits[l];
          occluded[lane_ray[l]] = lane_hits[l].hit;
        }
      } else {
        pass.caster.occluded_packet(lane_o, lane_d, count, tfar, lane_occ);
        for (int l = 0; l < count; ++l) occluded[lane_ray[l]] = lane_occ[l];
      }
    }
  }

  // Vertex v, the slot-th of the last traced batch. Returns the rays cast.
  uint64_t sample(std::size_t v, std::size_t slot) {
    const int K = pass.K, N = pass.N;
    const std::size_t R = static_cast<std::size_t>(rays_per_vertex);
    const bool need_sh = pass.need_sh_rays, interreflect = pass.interreflect;
    const double inv_n = 1.0 / N;
    const glm::vec3 n = glm::normalize(pass.scene.normals[v]);
    std::fill(acc.begin(), acc.end(), 0.0);
    gathered.clear();
    const std::size_t hits_before = compact.hits.size();
    // Obscurance (obscurance_falloff.h) needs every hit's distance; plain AO weighs by visibility.
    const ObscuranceOptions& obscurance = pass.options.obscurance;
    double open_sum = 0.0;  // Σ ρ(d_s), ρ = V(ω_s) for plain AO
    glm::dvec3 bent(0.0);
    uint64_t rays = 0;
    for (std::size_t first = 0; first < R; first += kPacketSize) {
      const std::size_t at = slot * R + first;
      const glm::vec3* d = &dirs[at];
      const scene::RayCaster::Hit* h = want_hits() ? &hits[at] : nullptr;
      rays += kPacketSize;
      // SH of the visible directions: summed in float over the 16 rays of a packet (at most 16
      // terms of magnitude ≤ ~3.5), then added to the double accumulator.
      bool any = false;
      if (need_sh) std::fill(packet_sum.begin(), packet_sum.end(), 0.f);
      for (int i = 0; i < kPacketSize; ++i) {
        const bool occ = occluded[at + static_cast<std::size_t>(i)];
        const double open = !obscurance.enabled() ? (occ ? 0.0 : 1.0)
                            : h[i].hit
                                ? obscurance_weight(obscurance.falloff, h[i].t, obscurance.distance)
                                : 1.0;
        open_sum += open;
        bent += open * glm::dvec3(d[i]);
        if (occ || !need_sh) continue;
        any = true;
        sh::evaluate(pass.order, d[i].x, d[i].y, d[i].z, y.data());
        for (int k = 0; k < K; ++k) packet_sum[k] += y[k];
      }
      if (any)
        for (int k = 0; k < K; ++k) acc[k] += static_cast<double>(packet_sum[k]);
      if (interreflect)
        for (int i = 0; i < kPacketSize; ++i)
          if (h[i].hit && !(pass.compact ? gather_front_hit_compact(pass.scene, h[i], d[i],
                                                                    *pass.compact, compact.hits)
                                         : gather_front_hit(pass.scene, h[i], d[i], 1.f,
                                                            pass.gather_channels, gathered)))
            ++pass.block_back_hits[block];
    }
    if (need_sh)
      for (int k = 0; k < K; ++k) acc[k] *= inv_n;
    if (need_sh) pass.direct.store(v, acc.data());
    pass.sums.ao[v] = static_cast<float>(open_sum * inv_n);
    const double bl = glm::length(bent);
    const glm::vec3 bn = bl > 0 ? glm::vec3(bent / bl) : n;
    pass.sums.bent[3 * v + 0] = bn.x;
    pass.sums.bent[3 * v + 1] = bn.y;
    pass.sums.bent[3 * v + 2] = bn.z;
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
    std::size_t vs[kVertexBlock];
    for (std::size_t r = r_begin; r < r_end; ++r)
      vs[r - r_begin] = pass.row_order ? (*pass.row_order)[r]
                        : pass.compact ? pass.compact->vertex_of_row(r)
                                       : r;
    const std::size_t batch = sampler.batch_vertices();
    for (std::size_t j = 0; j < r_end - r_begin; j += batch) {
      const std::size_t m = std::min(batch, r_end - r_begin - j);
      sampler.trace(vs + j, m);
      for (std::size_t s = 0; s < m; ++s) rays += sampler.sample(vs[j + s], s);
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
