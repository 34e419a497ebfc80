// bake/src/transfer_baker.cpp — the per-vertex sampling pass, the gather matrix and the
// assembly of TransferData (see transfer_baker.h).
//
// Interreflection estimator (Sloan, Kautz & Snyder 2002, §6), derived:
//   the exit radiance of a diffuse vertex p with albedo ρ_p is
//     B_p = (ρ_p/π) ∫_{H(n)} L_in(ω) cos θ dω,
//   and L_in(ω) = V(ω)·L_env(ω) + B_q(ω), q(ω) the point the ray p→ω hits (exit radiance of a
//   diffuse surface is the same in every direction). With N directions of pdf cos θ/π,
//     ∫ f cos θ dω ≈ (1/N) Σ_s f(ω_s) · cos θ_s / (cos θ_s/π) = (π/N) Σ_s f(ω_s),
//   so B_p ≈ (ρ_p/π)(π/N) Σ_s [V L_env + B_q] = (ρ_p/N) Σ_s V(ω_s) L_env(ω_s)
//                                             + (ρ_p/N) Σ_{s hits} B_q(ω_s).
//   Writing L_env = Σ_k L_k Y_k and B_q = Σ_k T_q,k L_k, with T_q interpolated from the hit
//   triangle's vertices with barycentrics b_i (T_{v_i} already includes ρ_{v_i}/π):
//     T_p = D_p + ρ_p Σ_j H_pj T_j,  D_p,k = (ρ_p/N) Σ_s V(ω_s) Y_k(ω_s),
//     H_pj = (1/N) Σ_{s hits} Σ_{i : v_i = j} b_i(s).
//   The ρ_p/N weight is thus the receiver's albedo × the estimator weight π/N × the BRDF's 1/π.
// Back faces occlude but reflect nothing: the transfer stored for q describes only the side
// its vertex normals point to. The side is judged with the hit triangle's flat geometric
// normal, oriented by the sum of its vertex normals (front: dot(n_g, ω) < 0). Hits and occlusion
// come from the same ray (intersect instead of occluded), so D and H are consistent: every sample
// is visible, a front hit or a back hit. H memory: ≤ 3 (column, weight) pairs of 8 bytes per hit
// ray before merging; rows merge duplicate columns, so a row costs 8 bytes × distinct vertices hit
// (typically far fewer than 3·hits at high sample counts).
#include "bake/transfer_baker.h"
#include "bake/transfer_part.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "bake/adaptive/occluder_caps.h"
#include "bake/compact_gather.h"
#include "bake/interreflection_solver.h"
#include "bake/progress.h"
#include "bake/sampling.h"
#include "hit_records.h"
#include "prt/core/memory_budget.h"
#include "prt/formats/part_file.h"
#include "scene/ray_caster.h"
#include "scene/scene_label.h"
#include "sh/basis.h"
#include "transfer_geometry.h"
#include "transfer_pass.h"

namespace prt::bake {
namespace {

constexpr int kMaxAdaptiveBounces = 200;  // then BiCGSTAB finishes the solve
constexpr int kMaxCompactBounces = 200;   // the compact path's bounces before BiCGSTAB
constexpr int kDenseSolverBlocks = 10;    // direct, solved, BiCGSTAB's 7 and the best iterate

using Clock = std::chrono::steady_clock;
using detail::BlockRows;
using detail::DirectTransfer;
using detail::SamplingPass;
using detail::VertexSums;

int round_up(int n, int multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Process CPU seconds so far (every thread).
double cpu_now() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

std::string primitive_of(const scene::Scene& scene, std::size_t v) {
  for (const scene::ScenePrimitive& p : scene.primitives)
    if (v >= p.first_vertex && v < static_cast<std::size_t>(p.first_vertex) + p.vertex_count)
      return "primitive '" + p.name + "'";
  return "vertex " + std::to_string(v);
}

bool is_grey(const glm::vec3& a) {
  return a.x == a.y && a.y == a.z;
}

// Channels of the transfer (transfer_baker.h): 1 when it cannot depend on colour, else 3.
int channel_count(const scene::Scene& scene, const BakeOptions& options, bool apart) {
  if (options.direct_override) return 3;
  if (apart && options.kind != prt::TransferKind::Interreflected) return 1;  // T = S
  bool grey = std::all_of(scene.albedo.begin(), scene.albedo.end(), is_grey);
  for (const scene::ScenePrimitive& p : scene.primitives)
    if (p.base_color_texture)
      grey = grey && is_grey(p.base_color_texture->factor) && p.base_color_texture->image->grey();
  return grey ? 1 : 3;
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double e : x) m = std::max(m, std::fabs(e));
  return m;
}

// Adaptive interreflection (transfer_baker.h): T = Σ_i (ρH)^i D, stopped after the first bounce
// whose max-norm is ≤ tolerance × max|D|; BiCGSTAB (to relative residual `tolerance`) finishes
// when kMaxAdaptiveBounces were not enough (ρ → 1). Skipped when H is empty or ρ = 0: T = D.
void solve_adaptively(const SparseTransferMatrix& h, const std::vector<double>& rho,
                      const std::vector<double>& direct, int columns, double tolerance,
                      std::vector<double>& t, BakeStatistics& st, ProgressSink* progress) {
  t = direct;
  const bool any_albedo = std::any_of(rho.begin(), rho.end(), [](double r) { return r > 0.0; });
  const double d_max = max_abs(direct);
  if (h.entries() == 0 || !any_albedo || d_max == 0.0) return;
  st.interreflection_solved = true;
  std::vector<double> bounce = direct, next(direct.size());
  int bounces = 0;
  bool stopped = false;
  while (bounces < kMaxAdaptiveBounces && !stopped) {
    multiply_gather(h, rho, bounce.data(), columns, next.data());
    const double energy = max_abs(next);
    for (std::size_t j = 0; j < t.size(); ++j) t[j] += next[j];
    bounce.swap(next);
    if (st.bounce_energy.size() <= static_cast<std::size_t>(bounces))
      st.bounce_energy.push_back(0.0);
    st.bounce_energy[bounces] = std::max(st.bounce_energy[bounces], energy);
    ++bounces;
    stopped = energy <= tolerance * d_max;
  }
  st.jacobi_bounces = std::max(st.jacobi_bounces, bounces);
  if (stopped) return;
  SolveOptions so;
  so.bounces = -1;
  so.tolerance = tolerance;
  const SolveReport rep =
      solve_interreflection(h, rho, direct.data(), columns, t.data(), so, progress);
  st.solver_iterations += rep.krylov_iterations;
  st.solver_residual = std::max(st.solver_residual, rep.relative_residual);
  st.solver_converged = st.solver_converged && rep.converged;
}

// What one bake knows about itself: sizes, the kind of work, and what the phases fill in.
struct BakeJob {
  const scene::Scene& scene;
  const BakeOptions& options;
  ProgressSink* progress;
  std::size_t V;
  int order, K, C, N;
  bool need_sh_rays, interreflect, need_rays, adaptive;
  bool apart;    // the albedo is kept apart (transfer_baker.h)
  bool compact;  // interreflected through the compact gather (transfer_baker.h)
  BakeResult& result;
  MemoryBudget& budget;
  VertexSums sums;
  DirectTransfer direct;
  std::vector<uint8_t> modes;             // adaptive: per-vertex treatment
  OccluderCaps caps;                      // adaptive: where capped vertices draw their rays
  SparseTransferMatrix h;                 // interreflected: the gather matrix (reference path)
  std::unique_ptr<CompactGather> gather;  // interreflected: the compact gather
  double ray_offset_max = 0.0;

  BakeJob(const scene::Scene& s, const BakeOptions& o, ProgressSink* p, BakeResult& r, int channels,
          bool albedo_apart, MemoryBudget& b, bool shard_part = false)
      : scene(s),
        options(o),
        progress(p),
        V(s.positions.size()),
        order(o.order),
        K(o.order * o.order),
        C(channels),
        N(round_up_to_packet(o.samples)),
        need_sh_rays(o.kind != prt::TransferKind::Unshadowed),
        interreflect(o.kind == prt::TransferKind::Interreflected),
        need_rays(need_sh_rays || o.ao || o.bent_normals),
        adaptive(o.adaptive.enabled && need_rays),
        apart(albedo_apart),
        compact(interreflect && !adaptive && !apart && !o.dense_gather),
        result(r),
        budget(b),
        direct(s, o, channels, albedo_apart, r.data, sums, shard_part) {}

  BakeStatistics& st() { return result.stats; }
  uint8_t mode_of(std::size_t v) const { return modes.empty() ? kSampleVertex : modes[v]; }
};

// Adaptive: the caller's vertex modes, with vertices whose occluder caps all lie below the
// horizon made analytic (they are provably open too).
void choose_vertex_modes(BakeJob& job) {
  const AdaptiveSampling& ad = job.options.adaptive;
  const std::size_t V = job.V;
  job.modes = ad.vertex_mode.empty() ? std::vector<uint8_t>(V, kSampleVertex) : ad.vertex_mode;
  if (ad.cap_sampling) {
    std::vector<uint8_t> wanted(V, 0);
    for (std::size_t v = 0; v < V; ++v) wanted[v] = job.modes[v] == kSampleVertex;
    // The caller's ray caster already holds the starts of this geometry.
    std::optional<scene::VertexRayStarts> own;
    const scene::VertexRayStarts& starts =
        ad.caster ? ad.caster->vertex_ray_starts()
                  : own.emplace(scene::compute_vertex_ray_starts(job.scene));
    job.caps = find_occluder_caps(job.scene, starts, wanted, ad.max_caps, ad.max_cap_solid_angle,
                                  ad.hierarchy.get());
    job.st().seconds_caps = job.caps.seconds;
    for (std::size_t v = 0; v < V; ++v) {
      if (!wanted[v] || !job.caps.covered[v]) continue;
      if (job.caps.count(v) == 0) {
        job.modes[v] = kAnalyticVertex;
        ++job.st().cap_open_vertices;
      } else {
        ++job.st().cap_vertices;
      }
    }
  }
  job.st().vertex_samples.assign(V, 0);
  job.st().vertex_standard_error.assign(V, 0.f);
  for (std::size_t v = 0; v < V; ++v)
    if (job.mode_of(v) == kAnalyticVertex) ++job.st().analytic_vertices;
}

// Adaptive with no vertex to sample: no BVH is built. AO = 1 and bent normal = n are exact for
// an open hemisphere; skipped vertices keep zeros.
void store_without_rays(BakeJob& job) {
  std::vector<double> out(static_cast<std::size_t>(job.K));
  for (std::size_t v = 0; v < job.V; ++v) {
    const glm::vec3 n = glm::normalize(job.scene.normals[v]);
    for (int a = 0; a < 3; ++a) job.sums.bent[3 * v + a] = n[a];
    if (job.mode_of(v) != kAnalyticVertex) continue;
    job.direct.unshadowed(v, out.data());
    job.direct.store(v, out.data());
    job.sums.ao[v] = 1.f;
  }
  if (job.interreflect) job.h.row_offsets.assign(job.V + 1, 0);
}

// A shard's rows (bake/transfer_part.h): which rows of which order, and where its gather blocks go.
struct ShardRows {
  const std::vector<uint32_t>* order;
  RowRange range;
  std::vector<CompactGather::Block>* blocks;
};

// Casts the rays: builds (or borrows) the BVH, runs the fixed or the adaptive sampler, and
// assembles H from the blocks' rows; with `shard`, the fixed sampler over the shard's rows only.
void run_sampling_pass(BakeJob& job, const ShardRows* shard = nullptr) {
  BakeStatistics& st = job.st();
  const AdaptiveSampling& ad = job.options.adaptive;
  const Clock::time_point t_rays = Clock::now();
  const double cpu_rays = cpu_now();
  std::unique_ptr<scene::RayCaster> own_caster;
  if (shard && !job.adaptive)  // the ray starts of the shard's rows only
    own_caster = std::make_unique<scene::RayCaster>(
        job.scene, shard->order->data() + shard->range.first, shard->range.size());
  else if (!(job.adaptive && ad.caster))
    own_caster = std::make_unique<scene::RayCaster>(job.scene);
  const scene::RayCaster& caster = own_caster ? *own_caster : *ad.caster;
  st.seconds_bvh = seconds_since(t_rays);
  st.cpu_seconds_bvh = cpu_now() - cpu_rays;
  job.ray_offset_max = std::max(job.ray_offset_max, caster.max_ray_offset());
  const int gather_channels = job.apart && job.interreflect ? job.C : 0;
  const double cpu_setup = cpu_now();
  if (job.compact)
    job.gather = std::make_unique<CompactGather>(
        shard ? *shard->order : make_morton_order(job.scene.positions), job.scene.triangles,
        detail::kVertexBlock, 1.0 / job.N, /*for_solve=*/shard == nullptr);
  st.cpu_seconds_gather_setup = cpu_now() - cpu_setup;
  SamplingPass pass{job.scene,
                    job.options,
                    caster,
                    job.progress,
                    job.V,
                    job.order,
                    job.K,
                    job.N,
                    job.need_sh_rays,
                    job.interreflect,
                    gather_channels,
                    job.direct,
                    job.sums,
                    st,
                    job.modes,
                    job.caps,
                    {},
                    {},
                    {}};
  pass.compact = job.gather.get();
  pass.budget = &job.budget;
  // The hit test's per-triangle records (fixed recipe): charged now, freed after the pass.
  std::vector<detail::HitRecord> hit_records;
  const uint64_t record_bytes =
      job.compact && !job.adaptive ? job.scene.triangles.size() * sizeof(detail::HitRecord) : 0;
  if (record_bytes > 0) {
    job.budget.charge(record_bytes, "the hit test's triangle records");
    const double cpu_records = cpu_now();
    hit_records = detail::make_hit_records(job.scene, *job.gather);
    st.cpu_seconds_gather_setup += cpu_now() - cpu_records;
    pass.hit_records = hit_records.data();
  }
  if (shard) {
    pass.row_order = shard->order;
    pass.first_row = shard->range.first;
    pass.end_row = shard->range.end;
    pass.part_blocks = shard->blocks;
    pass.sums_by_row = true;
    shard->blocks->resize(job.compact ? pass.blocks() : 0);
  }
  const std::size_t blocks = pass.blocks();
  pass.rows.resize(job.interreflect && !job.compact ? blocks : 0);
  pass.block_rays.assign(blocks, 0);
  pass.block_back_hits.assign(blocks, 0);
  if (job.progress) job.progress->start("bake", shard ? shard->range.size() : job.V);
  if (job.adaptive)
    detail::sample_adaptive(pass);
  else
    detail::sample_fixed(pass);
  if (job.progress) job.progress->finish();
  for (uint64_t r : pass.block_rays) st.rays += r;
  for (uint64_t b : pass.block_back_hits) st.back_face_hits += b;
  st.seconds_rays = seconds_since(t_rays);
  st.cpu_seconds_rays = cpu_now() - cpu_rays;
  st.bvh_bytes = caster.embree_peak_bytes();
  std::vector<detail::HitRecord>().swap(hit_records);
  job.budget.release(record_bytes);
  if (shard) return;  // the part holds the rows; the merge assembles H
  if (job.interreflect && job.compact) {
    st.matrix_entries = job.gather->hits();
    st.matrix_bytes = job.gather->bytes();
  } else if (job.interreflect) {
    // The blocks' rows and the assembled matrix coexist while it is assembled.
    uint64_t entries = 0;
    for (const BlockRows& br : pass.rows) entries += br.columns.size();
    job.budget.charge(2 * entries * (sizeof(uint32_t) + sizeof(float)) + 12 * (job.V + 1),
                      "the gather matrix");
    detail::assemble_gather_matrix(pass.rows, job.V, job.h);
    job.budget.release(entries * (sizeof(uint32_t) + sizeof(float)) + 4 * (job.V + 1));
    st.matrix_entries = job.h.entries();
    st.matrix_bytes = job.h.bytes();
  }
}

// A merge of shards' parts (bake/transfer_part.h) in place of the sampling pass: each row's
// direct transfer, AO and bent normal stored as the fixed sampler stores them, and the gather's
// rows cut into the blocks of 64 rows the sampler would have made, charged as it charges them.
void fill_from_parts(BakeJob& job, const std::vector<const TransferPart*>& parts) {
  BakeStatistics& st = job.st();
  const std::size_t K = static_cast<std::size_t>(job.K);
  std::vector<uint32_t> order = make_morton_order(job.scene.positions);
  if (job.compact)
    job.gather = std::make_unique<CompactGather>(order, job.scene.triangles, detail::kVertexBlock,
                                                 1.0 / job.N);
  CompactGather::Block block;
  std::size_t next_block = 0;
  const auto store_block = [&] {
    job.budget.charge(CompactGather::block_bytes(block.lengths.size(), block.hits.size()),
                      "the gather matrix");
    job.gather->set_block(next_block++, std::move(block));
    block = CompactGather::Block{};
  };
  for (const TransferPart* part : parts) {
    const double* direct = part->direct_values();
    const std::vector<TransferPart::HitRun> runs = part->hit_runs();
    std::size_t run = 0, hit = 0;  // the next row's hits: runs[run].data + hit
    for (std::size_t i = 0; i < part->rows.size(); ++i) {
      const std::size_t r = part->rows.first + i, v = order[r];
      if (job.need_sh_rays) job.direct.store(v, direct + i * K);
      if (job.options.ao) job.sums.ao[v] = part->ao[i];
      if (job.options.bent_normals)
        for (std::size_t a = 0; a < 3; ++a) job.sums.bent[3 * v + a] = part->bent[3 * i + a];
      if (!job.compact) continue;
      const uint32_t len = part->gather_rows[i];
      if (block.lengths.empty()) {  // sized once: no regrowth while the block's rows come in
        const std::size_t end = std::min<std::size_t>(i + detail::kVertexBlock, part->rows.size());
        std::size_t block_hits = 0;
        for (std::size_t j = i; j < end; ++j) block_hits += part->gather_rows[j];
        block.lengths.reserve(detail::kVertexBlock);
        block.hits.reserve(block_hits);
      }
      block.lengths.push_back(len);
      while (len > 0 && run < runs.size() && hit == runs[run].size) ++run, hit = 0;
      if (len > 0 && (run == runs.size() || runs[run].size - hit < len))
        throw BakeError(scene::scene_label(job.scene) +
                        ": a part's gather rows and hits do not agree");
      if (len > 0) {
        const CompactHit* const first = runs[run].data + hit;
        for (uint32_t k = 0; k < len; ++k)  // as the glossy and Haar merges check their hits
          if (first[k].triangle >= job.scene.triangles.size())
            throw BakeError(scene::scene_label(job.scene) +
                            ": a part's gather hit names no triangle of the scene");
        block.hits.insert(block.hits.end(), first, first + len);
      }
      hit += len;
      if (block.lengths.size() == detail::kVertexBlock || r + 1 == job.V) store_block();
    }
    st.rays += part->rays;
    st.back_face_hits += part->back_face_hits;
    job.ray_offset_max = std::max(job.ray_offset_max, part->ray_offset_max);
    // A part read from a file: its rows are copied, so its pages go now, not with the file
    // (the merge's peak is the single bake's stores plus one part, not plus every part).
    if (part->direct_view)
      prt::release_part_pages(part->direct_view, part->direct_count * sizeof(double));
    if (part->hits_view)
      prt::release_part_pages(part->hits_view, part->hit_count * sizeof(CompactHit));
  }
  if (job.compact) {
    st.matrix_entries = job.gather->hits();
    st.matrix_bytes = job.gather->bytes();
  }
}

// The buffers every bake holds, charged before BakeJob allocates them (transfer_baker.h): the
// coefficients, the sampling pass's sums, the solver's blocks and the compact gather's tables.
// The gather's rows are charged as the sampling pass fills them.
void charge_bake_buffers(const scene::Scene& scene, const BakeOptions& o, int channels,
                         bool compact, MemoryBudget& budget) {
  const uint64_t V = scene.positions.size(), T = scene.triangles.size();
  const uint64_t K = static_cast<uint64_t>(o.order) * o.order;
  const bool interreflect = o.kind == prt::TransferKind::Interreflected;
  const bool need_rays = o.kind != prt::TransferKind::Unshadowed || o.ao || o.bent_normals;
  uint64_t rows_out = V;
  if (o.adaptive.enabled && o.adaptive.compact_output && !o.adaptive.vertex_mode.empty())
    rows_out = static_cast<uint64_t>(std::count_if(o.adaptive.vertex_mode.begin(),
                                                   o.adaptive.vertex_mode.end(),
                                                   [](uint8_t m) { return m != kSkipVertex; }));
  budget.charge(rows_out * static_cast<uint64_t>(channels) * K * sizeof(float),
                "the transfer coefficients");
  if (need_rays)
    budget.charge(V * (interreflect ? K * sizeof(double) : 0) + V * 4 * sizeof(float),
                  "the visibility sums");
  if (!interreflect) return;
  // Compact: every channel at once, T in double, two bounces in float or binary16 with rows
  // padded (padded_row_elements) and ρ per row and channel; dense: per channel,
  // kDenseSolverBlocks V × K blocks.
  const uint64_t C = static_cast<uint64_t>(channels);
  const uint64_t bounce_row =
      padded_row_elements(static_cast<int>(C * K)) *
      (o.bounce_precision == prt::Precision::F16 ? sizeof(uint16_t) : sizeof(float));
  budget.charge(compact ? V * (C * K * sizeof(double) + 2 * bounce_row + C * sizeof(double))
                        : kDenseSolverBlocks * V * K * sizeof(double) + V * sizeof(double),
                "the interreflection solver's blocks");
  if (compact)
    budget.charge(V * 2 * sizeof(uint32_t) + T * (sizeof(uint32_t) + sizeof(glm::uvec3)),
                  "the gather matrix's tables");
}

// T_c = D_c + diag(ρ_c) H T_c per colour channel, into the output's float coefficients. With the
// albedo kept apart: G_c = S + H_c G_c, H_c the channel's block (the hit albedo inside, no
// receiver albedo: ρ = 1 in the solver).
// Folds one channel's solver report into the statistics.
void add_solve_report(const SolveReport& rep, BakeStatistics& st) {
  st.jacobi_bounces = std::max(st.jacobi_bounces, rep.jacobi_bounces);
  st.solver_iterations += rep.krylov_iterations;
  st.solver_residual = std::max(st.solver_residual, rep.relative_residual);
  st.solver_converged = st.solver_converged && rep.converged;
  if (st.bounce_energy.size() < rep.bounce_energy.size())
    st.bounce_energy.resize(rep.bounce_energy.size(), 0.0);
  for (std::size_t i = 0; i < rep.bounce_energy.size(); ++i)
    st.bounce_energy[i] = std::max(st.bounce_energy[i], rep.bounce_energy[i]);
}

// The compact path: every channel in one solve (C × K columns, one pass over the hits per
// bounce), rows in the gather's (Morton) order, D_r,c = ρ_c(v)·S_v for v = the vertex of row r.
// A row's C × K columns are the output's layout, so the solution is copied back row by row.
void solve_compact_channels(BakeJob& job) {
  BakeStatistics& st = job.st();
  const CompactGather& g = *job.gather;
  const std::size_t V = job.V, K = static_cast<std::size_t>(job.K);
  const std::size_t C = static_cast<std::size_t>(job.C), CK = C * K;
  std::vector<double> solved(V * CK), rho(V * C);
  for (std::size_t r = 0; r < V; ++r)
    for (std::size_t c = 0; c < C; ++c)
      rho[r * C + c] = job.scene.albedo[g.vertex_of_row(r)][static_cast<int>(c)];
  std::vector<double> override_d;
  if (job.options.direct_override) override_d = job.options.direct_override(job.sums.visibility_sh);
  const auto fill_direct = [&](double* d) {
    tbb::parallel_for(std::size_t(0), V, [&](std::size_t r) {
      if (!override_d.empty()) {
        std::copy_n(&override_d[g.vertex_of_row(r) * CK], CK, &d[r * CK]);
        return;
      }
      const double* s = &job.sums.visibility_sh[g.vertex_of_row(r) * K];
      for (std::size_t c = 0; c < C; ++c)
        for (std::size_t k = 0; k < K; ++k) d[r * CK + c * K + k] = rho[r * C + c] * s[k];
    });
  };
  SolveOptions so;
  so.bounces = job.options.bounces;
  so.tolerance = job.options.bounce_tolerance;
  so.max_iterations = job.options.max_solver_iterations;
  so.half_bounces = job.options.bounce_precision == prt::Precision::F16;
  const CompactGatherOperator a(g, rho, job.C);
  SolveReport rep;
  try {
    rep = solve_by_bounces(a, g.max_weighted_row_sum(rho, job.C), fill_direct, static_cast<int>(CK),
                           solved.data(), so, kMaxCompactBounces, &job.budget, job.progress);
  } catch (const std::domain_error& e) {
    throw BakeError(scene::scene_label(job.scene) + ": " + e.what());
  }
  add_solve_report(rep, st);
  prt::TransferData& data = job.result.data;
  tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
    const double* t = &solved[g.row_of_vertex(v) * CK];
    for (std::size_t i = 0; i < CK; ++i) data.coefficients[v * CK + i] = static_cast<float>(t[i]);
  });
}

void solve_interreflection_channels(BakeJob& job) {
  if (job.compact) {
    solve_compact_channels(job);
    return;
  }
  BakeStatistics& st = job.st();
  const std::size_t V = job.V, K = static_cast<std::size_t>(job.K);
  const std::size_t C = static_cast<std::size_t>(job.C);
  std::vector<double> direct(V * K), solved(V * K), rho(V, 1.0);
  std::vector<double> override_d;
  if (job.options.direct_override) override_d = job.options.direct_override(job.sums.visibility_sh);
  prt::TransferData& data = job.result.data;
  for (std::size_t c = 0; c < C; ++c) {
    const SparseTransferMatrix block =
        job.apart ? column_block(job.h, c * V, V) : SparseTransferMatrix{};
    const SparseTransferMatrix& h = job.apart ? block : job.h;
    if (!job.apart)
      for (std::size_t v = 0; v < V; ++v) rho[v] = job.scene.albedo[v][static_cast<int>(c)];
    for (std::size_t v = 0; v < V; ++v)
      for (std::size_t k = 0; k < K; ++k)
        direct[v * K + k] = override_d.empty() ? rho[v] * job.sums.visibility_sh[v * K + k]
                                               : override_d[(v * C + c) * K + k];
    if (job.adaptive) {
      solve_adaptively(h, rho, direct, job.K, job.options.adaptive.bounce_tolerance, solved, st,
                       job.progress);
    } else {
      SolveOptions so;
      so.bounces = job.options.bounces;
      so.tolerance = job.options.bounce_tolerance;
      so.max_iterations = job.options.max_solver_iterations;
      const SolveReport rep =
          solve_interreflection(h, rho, direct.data(), job.K, solved.data(), so, job.progress);
      add_solve_report(rep, st);
    }
    for (std::size_t v = 0; v < V; ++v)
      for (std::size_t k = 0; k < K; ++k)
        data.coefficients[(v * C + c) * K + k] = static_cast<float>(solved[v * K + k]);
  }
}

// The adaptive part of the metadata.
nlohmann::json adaptive_metadata(const BakeJob& job) {
  const AdaptiveSampling& ad = job.options.adaptive;
  const BakeStatistics& st = job.result.stats;
  nlohmann::json a;
  a["transfer_requested"] = transfer_kind_name(job.options.kind);
  a["min_samples"] = round_up(std::max(ad.min_samples, 2 * kPacketSize), 2 * kPacketSize);
  a["max_samples"] = round_up(std::max(ad.min_samples, ad.max_samples), 2 * kPacketSize);
  a["min_cap_samples"] = round_up(std::max(ad.min_cap_samples, 1), kPacketSize);
  a["audit_stride"] = detail::kAuditStride;
  a["allocation_rounds"] = st.allocation_rounds;
  a["qmc_calibration"] = st.qmc_calibration;
  a["qmc_calibration_caps"] = st.qmc_calibration_caps;
  a["cap_sampling"] = ad.cap_sampling;
  a["cap_vertices"] = st.cap_vertices;
  a["cap_open_vertices"] = st.cap_open_vertices;
  a["rms_sampling_error_target"] = ad.rms_error;
  a["allocation_budget_met"] = st.allocation_budget_met;
  a["lighting_weighted"] = ad.lighting_order > 0;
  a["analytic_vertices"] = st.analytic_vertices;
  uint64_t sampled = 0, sum = 0;
  for (uint32_t n_v : st.vertex_samples) sampled += n_v > 0, sum += n_v;
  a["sampled_vertices"] = sampled;
  a["mean_samples_of_sampled_vertices"] =
      sampled ? static_cast<double>(sum) / static_cast<double>(sampled) : 0.0;
  if (job.interreflect) {
    a["empty_gather_rows"] = st.empty_gather_rows;
    a["interreflection_solved"] = st.interreflection_solved;
    a["bounce_tolerance"] = ad.bounce_tolerance;
  }
  return a;
}

// The file's metadata: what was baked and how. Nothing that changes from run to run (wall
// times, the thread count): the CLI records those beside the file (OUT.run.json).
std::string bake_metadata(const BakeJob& job) {
  const BakeOptions& options = job.options;
  const BakeStatistics& st = job.result.stats;
  nlohmann::json meta;
  meta["generator"] = "prt bake";
  meta["scene"] = job.scene.source_path;
  meta["sh_basis"] = sh::kBasisConvention;
  meta["transfer"] = transfer_kind_name(st.stored_kind);
  meta["order"] = job.order;
  meta["channels"] = job.C;
  meta["albedo_folded"] = !job.apart;
  if (job.apart)
    meta["albedo_kept_apart"] = job.scene.textured()
                                    ? "textured scene: multiply by the surface's (texture) albedo"
                                    : "requested: multiply by the surface's albedo";
  meta["samples_requested"] = options.samples;
  meta["samples_per_vertex"] = st.samples_per_vertex;
  meta["sampling"] = "Owen-scrambled Sobol (0,2)-sequence, cosine-weighted (concentric)";
  meta["seed"] = options.seed;
  meta["precision"] = options.precision == prt::Precision::F16 ? "f16" : "f32";
  meta["ao"] = options.ao;
  meta["bent_normals"] = options.bent_normals;
  if (options.obscurance.enabled()) {
    nlohmann::json ob;
    ob["distance"] = options.obscurance.distance;
    ob["falloff"] = obscurance_falloff_name(options.obscurance.falloff);
    ob["definition"] =
        "ao holds W = (1/pi) int rho(d) cos dw (obscurance), bent normals weighted "
        "by rho(d); d the hit distance in scene units, rho(d >= distance) = 1";
    meta["obscurance"] = ob;
  }
  meta["vertices"] = job.V;
  meta["triangles"] = st.triangles;
  meta["skipped_triangles"] = st.skipped_triangles;
  meta["rays"] = st.rays;
  meta["ray_offset_max"] = job.ray_offset_max;  // largest ε_v (scene/ray_offset.h)
  if (job.adaptive) meta["adaptive"] = adaptive_metadata(job);
  if (job.interreflect && (!job.adaptive || st.interreflection_solved)) {
    nlohmann::json s;
    s["bounces_requested"] = options.bounces;
    s["tolerance"] = options.bounce_tolerance;
    s["jacobi_bounces"] = st.jacobi_bounces;
    s["krylov_iterations"] = st.solver_iterations;
    s["relative_residual"] = st.solver_residual;
    s["converged"] = st.solver_converged;
    s["bounce_energy"] = st.bounce_energy;
    s["matrix_entries"] = st.matrix_entries;
    s["gather"] = st.compact_gather ? "compact: 8 bytes per hit, Morton order, Neumann bounces"
                                    : "dense: merged CSR entries, BiCGSTAB";
    s["gather_bytes"] = st.matrix_bytes;
    if (options.bounce_precision == prt::Precision::F16) s["bounce_precision"] = "f16";
    s["back_face_hits"] = st.back_face_hits;
    meta["interreflection"] = s;
  }
  return meta.dump();
}

}  // namespace

void validate_bake_inputs(const scene::Scene& scene, const BakeOptions& o) {
  const std::string name = scene::scene_label(scene);
  if (o.kind != prt::TransferKind::Unshadowed && o.kind != prt::TransferKind::Shadowed &&
      o.kind != prt::TransferKind::Interreflected)
    throw BakeError(name + ": transfer kind '" + transfer_kind_name(o.kind) +
                    "' is not supported by the SH baker");
  if (o.order < 1 || o.order > kMaxBakeOrder)
    throw BakeError(name + ": SH order " + std::to_string(o.order) + " is outside [1, " +
                    std::to_string(kMaxBakeOrder) + "]");
  if (o.samples < 1 || o.samples > kMaxBakeSamples)
    throw BakeError(name + ": " + std::to_string(o.samples) +
                    " samples per vertex is outside [1, " + std::to_string(kMaxBakeSamples) + "]");
  if (o.bounces < -1) throw BakeError(name + ": bounces must be >= 0, or -1 (until converged)");
  if (!(o.bounce_tolerance > 0.0) || !std::isfinite(o.bounce_tolerance) || o.bounce_tolerance >= 1)
    throw BakeError(name + ": bounce tolerance must be in (0, 1)");
  if (o.max_solver_iterations < 1) throw BakeError(name + ": solver iteration cap must be >= 1");
  if (o.threads < 0) throw BakeError(name + ": thread count must be >= 0");
  if (o.direct_override && (o.kind != prt::TransferKind::Interreflected || o.adaptive.enabled ||
                            o.keep_albedo_apart || scene.textured()))
    throw BakeError(name +
                    ": a direct term of the caller's is for interreflected, fixed-recipe "
                    "bakes with the albedo folded");
  if (o.obscurance.distance != 0.0 &&
      !(o.obscurance.distance > 0.0 && std::isfinite(o.obscurance.distance)))
    throw BakeError(name + ": obscurance distance must be a finite length > 0");
  if (o.obscurance.enabled() && o.adaptive.enabled)
    throw BakeError(name + ": obscurance is baked by the fixed recipe only, not adaptive sampling");
  if (o.adaptive.enabled) {
    const AdaptiveSampling& a = o.adaptive;
    if (a.min_samples < 1 || a.max_samples < a.min_samples || a.max_samples > kMaxBakeSamples)
      throw BakeError(name + ": adaptive sample range [" + std::to_string(a.min_samples) + ", " +
                      std::to_string(a.max_samples) + "] is invalid");
    if (!(a.rms_error > 0.0) || !std::isfinite(a.rms_error))
      throw BakeError(name + ": adaptive RMS error target must be > 0");
    if (!(a.bounce_tolerance > 0.0) || !(a.bounce_tolerance < 1.0))
      throw BakeError(name + ": adaptive bounce tolerance must be in (0, 1)");
    if (a.compact_output && o.kind == prt::TransferKind::Interreflected)
      throw BakeError(name + ": compact output is for shadowed and unshadowed bakes");
    if (a.cap_sampling && (a.max_caps < 1 || a.max_caps > 256 || !(a.max_cap_solid_angle > 0.0) ||
                           !std::isfinite(a.max_cap_solid_angle) || a.min_cap_samples < 1))
      throw BakeError(name + ": cap sampling needs 1..256 caps, a solid angle > 0 and >= 1 sample");
    if (!a.vertex_mode.empty() && a.vertex_mode.size() != scene.positions.size())
      throw BakeError(name + ": adaptive vertex modes do not match the vertex count");
    if (a.lighting_order < 0 ||
        a.lighting.size() < static_cast<std::size_t>(a.lighting_order) * a.lighting_order)
      throw BakeError(name + ": adaptive lighting has fewer than order² coefficients");
  }
  if (o.bounce_precision == prt::Precision::F16 &&
      (o.kind != prt::TransferKind::Interreflected || o.adaptive.enabled || o.keep_albedo_apart ||
       o.dense_gather || scene.textured()))
    throw BakeError(name +
                    ": bounce precision f16 is for interreflected bakes through the compact "
                    "gather (not adaptive, textured, albedo apart or dense)");
  if (scene.positions.empty()) throw BakeError(name + ": the scene has no vertices");
  if (scene.normals.size() != scene.positions.size())
    throw BakeError(name + ": " + std::to_string(scene.normals.size()) + " normals for " +
                    std::to_string(scene.positions.size()) + " vertices");
  if (scene.albedo.size() != scene.positions.size())
    throw BakeError(name + ": " + std::to_string(scene.albedo.size()) + " albedo values for " +
                    std::to_string(scene.positions.size()) + " vertices");
  if (scene.positions.size() > 0xffffffffull) throw BakeError(name + ": too many vertices");
  for (std::size_t v = 0; v < scene.positions.size(); ++v) {
    const glm::vec3 p = scene.positions[v], n = scene.normals[v], a = scene.albedo[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw BakeError(name + ": vertex " + std::to_string(v) + " has a non-finite position");
    const float len = glm::length(n);
    if (!std::isfinite(len) || std::fabs(len - 1.f) > 1e-3f)
      throw BakeError(name + ": vertex " + std::to_string(v) + " of " + primitive_of(scene, v) +
                      " has a normal that is not unit length");
    for (int c = 0; c < 3; ++c) {
      if (!(a[c] >= 0.f && a[c] < 1.f)) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "albedo (%g, %g, %g) of %s is outside [0, 1)",
                      static_cast<double>(a.x), static_cast<double>(a.y), static_cast<double>(a.z),
                      primitive_of(scene, v).c_str());
        throw BakeError(name + ": " + buf + " (energy would not be conserved)");
      }
    }
  }
  for (const glm::uvec3& t : scene.triangles)
    if (t.x >= scene.positions.size() || t.y >= scene.positions.size() ||
        t.z >= scene.positions.size())
      throw BakeError(name + ": a triangle index is out of range");
}

namespace {

// bake_transfer, or (with `parts`) the merge of a sharded bake's parts.
BakeResult bake_transfer_with(const scene::Scene& scene, const BakeOptions& options,
                              ProgressSink* progress,
                              const std::vector<const TransferPart*>* parts) {
  const Clock::time_point t_start = Clock::now();
  const double cpu_start = cpu_now();
  validate_bake_inputs(scene, options);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));
  BakeResult result;
  const bool apart = options.keep_albedo_apart || scene.textured();
  if (apart && options.kind == prt::TransferKind::Interreflected &&
      3 * scene.positions.size() > 0xffffffffull)
    throw BakeError(scene::scene_label(scene) +
                    ": too many vertices for interreflection with the albedo kept apart");
  const int channels = channel_count(scene, options, apart);
  MemoryBudget budget(options.memory_limit, scene::scene_label(scene));
  const bool compact = options.kind == prt::TransferKind::Interreflected &&
                       !(options.adaptive.enabled) && !apart && !options.dense_gather;
  charge_bake_buffers(scene, options, channels, compact, budget);
  BakeJob job(scene, options, progress, result, channels, apart, budget);
  result.stats.compact_gather = job.compact;
  const std::size_t V = job.V;
  BakeStatistics& st = result.stats;
  st.vertices = V;
  st.triangles = scene.triangles.size();
  st.samples_per_vertex = job.need_rays ? job.N : 0;
  st.skipped_triangles = scene.skipped_degenerate_triangles;
  if (job.need_rays) {
    job.sums.ao.assign(V, 0.f);
    job.sums.bent.assign(3 * V, 0.f);
  }

  // 1. Unshadowed transfer is analytic; albedo is applied by the store.
  if (!job.need_sh_rays)
    tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
      std::vector<double> out(static_cast<std::size_t>(job.K));
      job.direct.unshadowed(v, out.data());
      job.direct.store(v, out.data());
    });
  // 2. Which vertices cast rays (adaptive), then the rays.
  bool any_sampled = !job.adaptive;
  if (job.adaptive) {
    choose_vertex_modes(job);
    for (std::size_t v = 0; v < V; ++v)
      any_sampled = any_sampled || job.mode_of(v) == kSampleVertex;
    if (!any_sampled) store_without_rays(job);
  }
  if (parts)
    fill_from_parts(job, *parts);
  else if (job.need_rays && any_sampled)
    run_sampling_pass(job);

  // 3. The header arrays, then the interreflection solve per channel.
  prt::TransferData& data = result.data;
  data.order = static_cast<uint32_t>(job.order);
  data.channels = static_cast<uint32_t>(job.C);
  data.storage = options.precision;
  data.albedo_folded = !apart;
  detail::store_scene_geometry(scene, data);
  const Clock::time_point t_solve = Clock::now();
  const double cpu_solve = cpu_now();
  if (job.adaptive) {
    for (std::size_t v = 0; v < V && job.interreflect; ++v)
      if (job.mode_of(v) == kSampleVertex && job.h.row_offsets[v + 1] == job.h.row_offsets[v])
        ++st.empty_gather_rows;
    st.samples_per_vertex = 0;
    for (uint32_t n_v : st.vertex_samples)
      st.samples_per_vertex = std::max(st.samples_per_vertex, static_cast<int>(n_v));
  }
  if (job.interreflect) solve_interreflection_channels(job);
  st.seconds_solve = job.interreflect ? seconds_since(t_solve) : 0.0;
  st.cpu_seconds_solve = job.interreflect ? cpu_now() - cpu_solve : 0.0;

  // 4. What the file says it holds: an adaptive bake that needed no rays, or no solve, stores
  // the simpler kind.
  st.stored_kind = options.kind;
  if (job.adaptive) {
    if (st.analytic_vertices == V)
      st.stored_kind = prt::TransferKind::Unshadowed;
    else if (!job.interreflect || !st.interreflection_solved)
      st.stored_kind = prt::TransferKind::Shadowed;
  }
  data.kind = st.stored_kind;
  if (options.ao) data.ao = std::move(job.sums.ao);
  if (options.bent_normals) data.bent_normals = std::move(job.sums.bent);
  st.budget_peak_bytes = budget.peak();
  st.seconds_total = seconds_since(t_start);
  st.cpu_seconds_total = cpu_now() - cpu_start;
  data.metadata_json = bake_metadata(job);
  return result;
}

}  // namespace

BakeResult bake_transfer(const scene::Scene& scene, const BakeOptions& options,
                         ProgressSink* progress) {
  return bake_transfer_with(scene, options, progress, nullptr);
}

RowRange shard_rows(uint64_t rows, ShardSpec shard) {
  // ⌊i·rows/N⌋ without overflow: rows = q·N + m, i·rows/N = i·q + ⌊i·m/N⌋ (i, m < N < 2³²).
  const auto bound = [&](uint64_t i) {
    const uint64_t q = rows / shard.count, m = rows % shard.count;
    return i * q + i * m / shard.count;
  };
  return {bound(shard.index), bound(uint64_t{shard.index} + 1)};
}

void check_shardable(const scene::Scene& scene, const BakeOptions& options) {
  const std::string name = scene::scene_label(scene);
  if (options.adaptive.enabled)
    throw BakeError(name + ": a sharded bake needs the fixed recipe, not adaptive sampling");
  if (options.keep_albedo_apart || scene.textured())
    throw BakeError(name +
                    ": a sharded bake needs the albedo folded into the transfer (the scene "
                    "is textured or the albedo is kept apart)");
  if (options.kind == prt::TransferKind::Interreflected && options.dense_gather)
    throw BakeError(name + ": a sharded interreflected bake needs the compact gather");
}

std::vector<TransferPart::HitRun> TransferPart::hit_runs() const {
  if (hits_view) return {{hits_view, static_cast<std::size_t>(hit_count)}};
  std::vector<HitRun> runs;
  for (const CompactGather::Block& b : gather_blocks)
    if (!b.hits.empty()) runs.push_back({b.hits.data(), b.hits.size()});
  return runs;
}

uint64_t TransferPart::hit_size() const {
  if (hits_view) return hit_count;
  uint64_t n = 0;
  for (const CompactGather::Block& b : gather_blocks) n += b.hits.size();
  return n;
}

TransferPart bake_transfer_part(const scene::Scene& scene, const BakeOptions& options,
                                ShardSpec shard, ProgressSink* progress) {
  const Clock::time_point t_start = Clock::now();
  validate_bake_inputs(scene, options);
  check_shardable(scene, options);
  if (shard.count == 0 || shard.index >= shard.count)
    throw BakeError(scene::scene_label(scene) + ": shard " + std::to_string(shard.index) + "/" +
                    std::to_string(shard.count) + " is not a shard");
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));
  BakeResult result;
  MemoryBudget budget(options.memory_limit, scene::scene_label(scene));
  const uint64_t V = scene.positions.size(), K = uint64_t(options.order) * options.order;
  const bool need_sh = options.kind != prt::TransferKind::Unshadowed;
  const bool need_rays = need_sh || options.ao || options.bent_normals;
  const uint64_t n = shard_rows(V, shard).size();  // the sums hold the shard's rows only
  budget.charge(n * (need_sh ? K * sizeof(double) : 0) + (need_rays ? n * 16 : 0),
                "the visibility sums");
  BakeJob job(scene, options, progress, result, channel_count(scene, options, false), false, budget,
              true);
  TransferPart part;
  part.shard = shard;
  part.vertices = V;
  part.rows = shard_rows(V, shard);
  part.coefficients = job.K;
  if (need_rays) {
    job.sums.visibility_sh.assign(need_sh ? n * K : 0, 0.0);
    job.sums.ao.assign(n, 0.f);
    job.sums.bent.assign(3 * n, 0.f);
    const std::vector<uint32_t> order = make_morton_order(scene.positions);
    std::vector<CompactGather::Block> blocks;
    const ShardRows rows{&order, part.rows, &blocks};
    run_sampling_pass(job, &rows);
    // The sums are in row order already (SamplingPass::sums_by_row): moved, not copied.
    if (need_sh) part.direct = std::move(job.sums.visibility_sh);
    if (options.ao) part.ao = std::move(job.sums.ao);
    if (options.bent_normals) part.bent = std::move(job.sums.bent);
    // The blocks are kept as they are (the part file writes their hits one after another: no
    // copy into one array, whose fresh pages cost more than the copy); only the row lengths
    // are gathered into one array.
    part.gather_rows.reserve(job.compact ? n : 0);
    for (const CompactGather::Block& b : blocks)
      part.gather_rows.insert(part.gather_rows.end(), b.lengths.begin(), b.lengths.end());
    part.gather_blocks = std::move(blocks);
  }
  part.rays = result.stats.rays;
  part.back_face_hits = result.stats.back_face_hits;
  part.ray_offset_max = job.ray_offset_max;
  result.stats.vertices = part.rows.size();
  result.stats.triangles = scene.triangles.size();
  result.stats.samples_per_vertex = need_rays ? job.N : 0;
  result.stats.matrix_entries = part.hit_size();
  result.stats.budget_peak_bytes = budget.peak();
  result.stats.seconds_total = seconds_since(t_start);
  part.stats = result.stats;
  return part;
}

BakeResult merge_transfer_parts(const scene::Scene& scene, const BakeOptions& options,
                                const std::vector<const TransferPart*>& parts,
                                ProgressSink* progress) {
  // A shadowed or unshadowed part holds S alone: the merge may keep the albedo apart.
  BakeOptions checked = options;
  if (options.kind != prt::TransferKind::Interreflected) checked.keep_albedo_apart = false;
  check_shardable(scene, checked);
  const std::string name = scene::scene_label(scene);
  const uint64_t V = scene.positions.size(), K = uint64_t(options.order) * options.order;
  const bool need_sh = options.kind != prt::TransferKind::Unshadowed;
  const bool interreflect = options.kind == prt::TransferKind::Interreflected;
  uint64_t next = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const TransferPart& p = *parts[i];
    const RowRange want =
        shard_rows(V, {static_cast<uint32_t>(i), static_cast<uint32_t>(parts.size())});
    const uint64_t n = p.rows.size();
    uint64_t hits = 0;
    for (uint32_t len : p.gather_rows) hits += len;
    if (p.vertices != V || p.shard.index != i || p.shard.count != parts.size() ||
        p.rows.first != want.first || p.rows.end != want.end || p.rows.first != next ||
        p.direct_size() != (need_sh ? n * K : 0) || p.ao.size() != (options.ao ? n : 0) ||
        p.bent.size() != (options.bent_normals ? 3 * n : 0) ||
        p.gather_rows.size() != (interreflect ? n : 0) || hits != p.hit_size())
      throw BakeError(name + ": part " + std::to_string(i) + " of " + std::to_string(parts.size()) +
                      " does not fit the scene or the split");
    next = p.rows.end;
  }
  if (next != V) throw BakeError(name + ": the parts do not cover every vertex");
  return bake_transfer_with(scene, options, progress, &parts);
}

}  // namespace prt::bake
