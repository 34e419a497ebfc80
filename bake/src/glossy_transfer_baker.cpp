// bake/src/glossy_transfer_baker.cpp — the glossy transfer-matrix bake (see
// bake/glossy_transfer_baker.h): a sampling pass (direct matrices S and the front-face hits of
// every vertex), then Jacobi bounces over the recorded hits.
#include "bake/glossy_transfer_baker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "bake/compact_gather.h"
#include "bake/cpca/compressor.h"
#include "bake/progress.h"
#include "bake/sampling.h"
#include "float_scratch_file.h"
#include "glossy_bake_stages.h"
#include "hit_side.h"
#include "prt/core/half.h"
#include "prt/core/memory_budget.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/glossy_transfer_writer.h"
#include "prt/glossy/brdf_projection.h"
#include "scene/ray_caster.h"
#include "scene/scene_label.h"
#include "scene/tangent_frames.h"
#include "scene/vertex_materials.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"
#include "transfer_pass.h"

namespace prt::bake {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kBlock = 64;  // vertices per parallel task (fixed: determinism)

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Frame {
  glm::vec3 t, b, n;
  glm::vec3 to_local(const glm::vec3& d) const {
    return {glm::dot(d, t), glm::dot(d, b), glm::dot(d, n)};
  }
};

// The front-face hits of a block of vertices, in vertex order and, per vertex, in sample order:
// 8 bytes a hit (bake/compact_gather.h's CompactHit: the scene's triangle and the barycentrics
// quantised to 16 bits) and a bit per sample and vertex saying which samples are those hits, so
// that the sample (and with it the direction) of each hit is implied by its rank.
struct BlockHits {
  std::vector<CompactHit> hits;
  std::vector<uint64_t> mask;  // mask_words per vertex of the block; bit s: sample s is a hit
  std::vector<float> exact;    // GlossyBakeOptions::exact_hits: u, v of each hit in float
  uint64_t bytes() const {
    return hits.size() * sizeof(CompactHit) + mask.size() * 8 + exact.size() * 4;
  }
};

// A hit as the bounces read it: the triangle and its three barycentric weights.
struct HitPoint {
  uint32_t triangle;
  float beta[3];
};

HitPoint decode_hit(const BlockHits& b, std::size_t i) {
  const CompactHit& h = b.hits[i];
  if (!b.exact.empty()) {
    const float u = b.exact[2 * i], v = b.exact[2 * i + 1];
    return {h.triangle, {1.f - u - v, u, v}};
  }
  constexpr float kStep = 1.f / 65535.f;
  return {h.triangle, {float(65535 - h.u - h.v) * kStep, float(h.u) * kStep, float(h.v) * kStep}};
}

bool grey(const brdf::Rgb& c) {
  return c.r == c.g && c.g == c.b;
}

// The bounces' b(ω_o) of a material: the runtime's projection (prt/glossy/brdf_projection.h), so
// the bake and the shading use one implementation. Its float evaluate() takes a scratch buffer;
// kProjectionScratch floats cover every order and view order it accepts (n² + m² + E ≤ 1652).
constexpr std::size_t kProjectionScratch = 2048;

prt::BrdfProjection make_projection(const brdf::Material& material, int order,
                                    const prt::BrdfProjectionOptions& options,
                                    const std::string& name) {
  Result<prt::BrdfProjection> made = prt::BrdfProjection::create(material, order, options);
  if (!made.ok()) throw BakeError(name + ": " + made.status().message());
  if (made.value().scratch_floats() > kProjectionScratch)
    throw BakeError(name + ": BRDF projection view order too large for the bake");
  return std::move(made).value();
}

const char* method_name(prt::BrdfProjectionMethod m) {
  switch (m) {
    case prt::BrdfProjectionMethod::kZonal:
      return "zonal";
    case prt::BrdfProjectionMethod::kIsotropicTable:
      return "isotropic table";
    case prt::BrdfProjectionMethod::kMatrix:
      return "matrix";
    default:
      return "auto";
  }
}

struct GlossyJob {
  const scene::Scene& scene;
  const GlossyBakeOptions& o;
  ProgressSink* progress;
  std::size_t V;
  int order, K, N, C;
  bool interreflect;
  std::vector<Frame> frames;
  std::vector<brdf::Material> materials;
  std::vector<uint32_t> material_of_vertex;
  std::vector<prt::BrdfProjection> projections;  // per material (bounces only)
  // Interreflected: every vertex's matrices, V · C · K², filled by the pass. Shadowed: null, and
  // each block of vertices goes to `sink` as it is finished.
  std::vector<float>* matrices = nullptr;
  std::function<void(std::size_t first, std::size_t count, const float* m)> sink;
  prt::MemoryBudget* budget = nullptr;
  std::vector<float> S;               // V · K², grey direct transfer (bounces only)
  std::vector<BlockHits> block_hits;  // per block of kBlock vertices (bounces only)
  std::size_t mask_words = 0;         // ⌈N / 64⌉
  std::vector<float> zonal_over_pi;   // z_l / π
  GlossyBakeStatistics& st;

  std::size_t KK() const { return std::size_t(K) * K; }
  std::size_t blocks() const { return (V + kBlock - 1) / kBlock; }
};

void sample_direction(const GlossyJob& job, std::size_t v, uint64_t vertex_seed, uint32_t i,
                      glm::vec3& local, glm::vec3& world) {
  // Uniform on the upper hemisphere of the local frame, pdf 1/2π.
  local = to_glm(numerics::sample_uniform_hemisphere(to_numerics(sample_sobol_2d(i, vertex_seed))));
  const Frame& f = job.frames[v];
  world = glm::normalize(local.x * f.t + local.y * f.b + local.z * f.n);
}

// Rows of the per-packet float blocks are padded to a multiple of 8 floats so the rank update
// runs on whole vectors.
constexpr int kLane = 8;
int padded(int K) {
  return (K + kLane - 1) / kLane * kLane;
}

// out[i·Kp + j] = Σ_s a[s·Kp + i] · c[s·Kp + j] for s < count, j < Kp (a rank-`count` product in
// float; Kp = padded(K), c's padding zero; out is overwritten, so it needs no clearing). Each
// 8-wide piece of a row is summed over the samples in registers and stored once (summing into
// memory sample by sample stalls on store forwarding: 37% of the pass in a profile). Cloned for
// AVX2 without FMA, so both clones round identically (no fused multiply-add).
__attribute__((target_clones("avx2", "default"))) void rank_update(int K, int count, const float* a,
                                                                   const float* c, float* out) {
  typedef float F8 __attribute__((vector_size(4 * kLane)));  // GCC vector: one ymm or two xmm
  const int Kp = padded(K);
  for (int i = 0; i < K; ++i) {
    float* row = out + std::size_t(i) * Kp;
    for (int jb = 0; jb < Kp; jb += kLane) {
      F8 t = {};
      for (int s = 0; s < count; ++s) {
        F8 cs;
        std::memcpy(&cs, c + s * Kp + jb, sizeof cs);
        t += a[s * Kp + i] * cs;
      }
      std::memcpy(row + jb, &t, sizeof t);
    }
  }
}

// acc[i·K + j] += scale · block[i·Kp + j] (double accumulator, unpadded).
__attribute__((target_clones("avx2", "default"))) void add_block(int K, const float* block,
                                                                 double scale, double* acc) {
  const int Kp = padded(K);
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < K; ++j) acc[i * K + j] += scale * block[i * Kp + j];
}

// The sampling pass over one vertex: S_v and its hits. Returns the rays cast.
struct VertexSampler {
  GlossyJob& job;
  const scene::RayCaster& caster;
  std::vector<float> yl, yg, packet;
  std::vector<double> acc;
  glm::vec3 local[kPacketSize], dirs[kPacketSize];
  bool occluded[kPacketSize];
  scene::RayCaster::Hit hit[kPacketSize];
  bool exact;  // also keep each hit's barycentrics in float (exact_hits; a farm part's records)

  VertexSampler(GlossyJob& j, const scene::RayCaster& c)
      : job(j),
        caster(c),
        yl(kPacketSize * std::size_t(padded(j.K)), 0.f),
        yg(kPacketSize * std::size_t(padded(j.K)), 0.f),
        packet(std::size_t(j.K) * padded(j.K)),
        acc(j.KK()),
        exact(j.o.exact_hits) {}

  // S_v (C · K², the channels equal) into `s`.
  uint64_t sample(std::size_t v, float* s, BlockHits& out, uint64_t* mask, uint64_t& back_hits) {
    const int K = job.K, Kp = padded(K);
    const uint64_t seed = hash_seed(job.o.seed, v);
    const glm::vec3 origin = caster.vertex_origin(static_cast<uint32_t>(v));
    std::fill(acc.begin(), acc.end(), 0.0);
    for (int first = 0; first < job.N; first += kPacketSize) {
      for (int i = 0; i < kPacketSize; ++i)
        sample_direction(job, v, seed, static_cast<uint32_t>(first + i), local[i], dirs[i]);
      detail::cast_packet(caster, origin, dirs, kPacketSize, std::numeric_limits<float>::infinity(),
                          job.interreflect ? hit : nullptr, occluded);
      int visible = 0;
      for (int i = 0; i < kPacketSize; ++i) {
        if (!occluded[i]) {
          sh::evaluate(job.order, local[i].x, local[i].y, local[i].z, &yl[visible * Kp]);
          sh::evaluate(job.order, dirs[i].x, dirs[i].y, dirs[i].z, &yg[visible * Kp]);
          ++visible;
        } else if (job.interreflect && hit[i].hit) {
          if (detail::ray_hits_front_side(job.scene, hit[i].triangle, dirs[i])) {
            out.hits.push_back(quantise_hit(hit[i].triangle, hit[i].u, hit[i].v));
            if (exact) {
              out.exact.push_back(hit[i].u);
              out.exact.push_back(hit[i].v);
            }
            const unsigned sample = unsigned(first + i);
            mask[sample / 64] |= uint64_t(1) << (sample % 64);
          } else {
            ++back_hits;
          }
        }
      }
      if (visible == 0) continue;
      rank_update(K, visible, yl.data(), yg.data(), packet.data());
      add_block(K, packet.data(), 1.0, acc.data());
    }
    const double w = 2.0 * sh::kPi / job.N;
    const std::size_t KK = job.KK();
    for (std::size_t e = 0; e < KK; ++e) s[e] = static_cast<float>(acc[e] * w);
    for (int c = 1; c < job.C; ++c) std::copy_n(s, KK, s + c * KK);
    return static_cast<uint64_t>(job.N);
  }
};

void run_sampling_pass(GlossyJob& job) {
  const Clock::time_point t0 = Clock::now();
  const scene::RayCaster caster(job.scene);
  job.block_hits.assign(job.blocks(), BlockHits{});
  std::vector<uint64_t> rays(job.blocks(), 0), back(job.blocks(), 0);
  if (job.progress) job.progress->start("glossy bake", job.V);
  const std::size_t per_vertex = std::size_t(job.C) * job.KK();
  tbb::parallel_for(std::size_t(0), job.blocks(), [&](std::size_t blk) {
    VertexSampler sampler(job, caster);
    const std::size_t first = blk * kBlock, end = std::min(job.V, (blk + 1) * kBlock);
    std::vector<float> block(job.matrices ? 0 : (end - first) * per_vertex);
    BlockHits& hits = job.block_hits[blk];
    if (job.interreflect) hits.mask.assign((end - first) * job.mask_words, 0);
    for (std::size_t v = first; v < end; ++v) {
      float* s = job.matrices ? &(*job.matrices)[v * per_vertex] : &block[(v - first) * per_vertex];
      uint64_t* mask = job.interreflect ? &hits.mask[(v - first) * job.mask_words] : nullptr;
      rays[blk] += sampler.sample(v, s, hits, mask, back[blk]);
    }
    if (job.interreflect) {  // kept for the bounces: exactly their size, charged
      hits.hits.shrink_to_fit();
      hits.exact.shrink_to_fit();
      if (job.budget) job.budget->charge(hits.bytes(), "the glossy bounces' ray hits");
    }
    if (!job.matrices) job.sink(first, end - first, block.data());
    if (job.progress) job.progress->advance(end - first, rays[blk]);
  });
  if (job.progress) job.progress->finish();
  for (std::size_t blk = 0; blk < job.blocks(); ++blk) {
    job.st.rays += rays[blk];
    job.st.back_face_hits += back[blk];
    job.st.hits += job.block_hits[blk].hits.size();
    job.st.gather_bytes += job.block_hits[blk].bytes();
  }
  job.st.seconds_rays = seconds_since(t0);
}

// One bounce at vertex p: out (C · K²) = S_p + (2π/N) Σ_hits y_local ⊗ r, r the radiance row
// the hit point sends back (M from `prev`).
// The bounce the gather reads: V · C · K² floats, or (GlossyBakeOptions::bounce_precision F16)
// as many binary16 values.
struct BounceRead {
  const float* f32 = nullptr;
  const uint16_t* f16 = nullptr;
};

struct BounceGatherer {
  const GlossyJob& job;
  const BounceRead prev;
  const std::vector<float>& exit;  // V · C · K: Σ_l z_l/π · row (l, 0) of prev (Lambert exit)
  std::vector<float> yl, r, rc, block;
  std::vector<double> acc;
  mutable std::vector<float> expanded;  // one matrix of a binary16 bounce, in float

  BounceGatherer(const GlossyJob& j, BounceRead p, const std::vector<float>& e)
      : job(j),
        prev(p),
        exit(e),
        yl(kPacketSize * std::size_t(padded(j.K)), 0.f),
        r(kPacketSize * std::size_t(j.C) * j.K),
        rc(kPacketSize * std::size_t(padded(j.K)), 0.f),
        block(std::size_t(j.C) * j.K * padded(j.K)),
        acc(std::size_t(j.C) * j.KK()),
        expanded(p.f16 ? j.KK() : 0) {}

  const float* matrix(std::size_t q, int c) const {
    const std::size_t at = (q * job.C + std::size_t(c)) * job.KK();
    if (prev.f32) return prev.f32 + at;
    prt::convert_halves_to_floats(prev.f16 + at, job.KK(), expanded.data());
    return expanded.data();
  }

  // r (C × K) for one hit seen along world direction d from the receiving vertex.
  void radiance_row(const HitPoint& h, const glm::vec3& d, float* row) const;

  // out (C · K²) = direct (K², the grey direct transfer of p) + the gather over p's hits, which are
  // the hits of `hits` from index *next on, their samples the set bits of `mask`; advances *next.
  void gather(std::size_t p, const float* direct, const BlockHits& hits, const uint64_t* mask,
              std::size_t* next, float* out) {
    const int K = job.K, C = job.C, Kp = padded(K);
    const std::size_t KK = job.KK();
    for (int c = 0; c < C; ++c)
      for (std::size_t e = 0; e < KK; ++e) acc[c * KK + e] = direct[e];
    const uint64_t seed = hash_seed(job.o.seed, p);
    const double w = 2.0 * sh::kPi / job.N;
    std::size_t word = 0;
    uint64_t bits = job.mask_words > 0 ? mask[0] : 0;
    for (;;) {
      int count = 0;
      while (count < kPacketSize) {
        while (bits == 0 && ++word < job.mask_words) bits = mask[word];
        if (bits == 0) break;
        const uint32_t sample = uint32_t(word * 64 + unsigned(__builtin_ctzll(bits)));
        bits &= bits - 1;
        glm::vec3 local, world;
        sample_direction(job, p, seed, sample, local, world);
        sh::evaluate(job.order, local.x, local.y, local.z, &yl[count * Kp]);
        radiance_row(decode_hit(hits, (*next)++), world, &r[std::size_t(count) * C * K]);
        ++count;
      }
      if (count == 0) break;
      for (int c = 0; c < C; ++c) {
        // Channel c of the rows: stride C·K between hits; gather them contiguous first.
        for (int s = 0; s < count; ++s)
          std::copy_n(&r[(std::size_t(s) * C + c) * K], K, &rc[std::size_t(s) * Kp]);
        rank_update(K, count, yl.data(), rc.data(), &block[std::size_t(c) * K * Kp]);
      }
      for (int c = 0; c < C; ++c) add_block(K, &block[std::size_t(c) * K * Kp], w, &acc[c * KK]);
      if (count < kPacketSize) break;
    }
    for (std::size_t e = 0; e < acc.size(); ++e) out[e] = static_cast<float>(acc[e]);
  }
};

void BounceGatherer::radiance_row(const HitPoint& h, const glm::vec3& d, float* row) const {
  const int K = job.K, C = job.C;
  std::fill(row, row + std::size_t(C) * K, 0.f);
  const glm::uvec3 tri = job.scene.triangles[h.triangle];
  const float* beta = h.beta;
  const uint32_t material = job.material_of_vertex[tri.x];
  if (job.materials[material].lambertian()) {
    // ρ(hit) · Σ_a β_a · (Σ_l z_l/π · row (l, 0) of M_qa): the interpolated Lambert exit.
    const glm::vec3 rho = job.scene.albedo_at(h.triangle, beta[1], beta[2]);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < C; ++c) {
        const float k = beta[a] * rho[c];
        const float* e = &exit[(std::size_t(tri[a]) * C + c) * K];
        for (int j = 0; j < K; ++j) row[c * K + j] += k * e[j];
      }
    return;
  }
  const prt::BrdfProjection& proj = job.projections[material];
  float bq[3 * kMaxGlossyBakeOrder * kMaxGlossyBakeOrder], scratch[kProjectionScratch];
  for (int a = 0; a < 3; ++a) {
    const glm::vec3 wo = job.frames[tri[a]].to_local(-d);
    const float wo_local[3] = {wo.x, wo.y, wo.z};
    proj.evaluate(wo_local, bq, scratch);
    for (int c = 0; c < C; ++c) {
      const float* m = matrix(tri[a], c);
      const float* bc = bq + c * K;
      for (int i = 0; i < K; ++i) {
        const float k = beta[a] * bc[i];
        if (k == 0.f) continue;
        const float* mrow = m + std::size_t(i) * K;
        for (int j = 0; j < K; ++j) row[c * K + j] += k * mrow[j];
      }
    }
  }
}

// exit[(q·C + c)·K + j] = Σ_l z_l/π · M_q,c[(l, 0), j]: the Lambert exit transfer of every vertex
// (before its albedo), read contiguously by the gather instead of n scattered rows of M_q.
void lambert_exit(const GlossyJob& job, BounceRead M, std::vector<float>& exit) {
  const int K = job.K;
  tbb::parallel_for(std::size_t(0), job.V * job.C, [&](std::size_t qc) {
    float* e = &exit[qc * K];
    std::fill(e, e + K, 0.f);
    float row[kMaxGlossyBakeOrder * kMaxGlossyBakeOrder];
    for (int l = 0; l < job.order; ++l) {
      const float z = job.zonal_over_pi[l];
      const std::size_t at = qc * job.KK() + std::size_t(sh::index(l, 0)) * K;
      const float* mrow = M.f32 ? M.f32 + at : row;
      if (!M.f32) prt::convert_halves_to_floats(M.f16 + at, std::size_t(K), row);
      for (int j = 0; j < K; ++j) e[j] += z * mrow[j];
    }
  });
}

// Throws BakeError when the bounces diverge: a change that is not finite, or one that exceeds
// twice the whole direct transfer (2 max |S|) and the bounce before it. With albedos ≤ 1 the
// largest radiance of each bounce is at most that of the bounce before, so the changes shrink
// but for the spread of a bounce's light over more of the hemisphere, which can raise an SH
// coefficient of it above the direct one; the factor 2 leaves room for that.
void check_divergence(const GlossyJob& job) {
  const std::vector<double>& c = job.st.bounce_change;
  const std::size_t k = c.size();
  const bool nonfinite = !std::isfinite(c.back());
  const bool growing = k >= 2 && c[k - 1] > 2.0 && c[k - 1] > c[k - 2];
  if (!nonfinite && !growing) return;
  char text[200];
  std::snprintf(text, sizeof text,
                ": glossy interreflection diverges: bounce %zu changed the transfer by %.3g of its "
                "direct part (bounce %zu: %.3g); a material reflects more light than arrives",
                k, c[k - 1], k - 1, k >= 2 ? c[k - 2] : 0.0);
  throw BakeError(scene::scene_label(job.scene) + text);
}

// out = the CPCA reconstruction of M (GlossyBakeOptions::bounce_cpca_clusters): what a bounce
// that reads compressed transfer sees.
void compressed_transfer(GlossyJob& job, const std::vector<float>& M, std::vector<float>& out) {
  prt::CpcaOptions co;
  co.clusters = job.o.bounce_cpca_clusters;
  co.vectors = job.o.bounce_cpca_vectors;
  co.threads = job.o.threads > 0 ? unsigned(job.o.threads)
                                 : unsigned(tbb::this_task_arena::max_concurrency());
  prt::Result<prt::CpcaTransfer> t =
      prt::cpca_compress(uint32_t(job.order), uint32_t(job.C), job.V, M.data(), co);
  if (!t.ok()) throw BakeError(scene::scene_label(job.scene) + ": " + t.status().message());
  job.st.bounce_cpca_bytes = t->payload_bytes();
  out.resize(M.size());
  const std::size_t per_vertex = std::size_t(job.C) * job.KK();
  tbb::parallel_for(std::size_t(0), job.V, [&](std::size_t v) {
    std::vector<double> r(per_vertex);
    prt::cpca_reconstruct(*t, v, r.data());
    for (std::size_t e = 0; e < per_vertex; ++e) out[v * per_vertex + e] = float(r[e]);
  });
}

// Where the bounces keep the direct transfer S and the bounce they write: in memory (S and a
// second whole bounce) or, streamed, in scratch files, so that memory holds only the bounce that
// is read at random (M, or its binary16 copy H) and the blocks in flight. Same arithmetic either
// way. With a binary16 bounce the float bounces live on two files used in turn (the previous one,
// for the change and the output, and the one being written); the pass writes M⁽⁰⁾ there too.
struct BounceStore {
  bool streamed = false;
  bool half = false;
  std::vector<float> next;             // in memory: V · C · K²
  std::vector<uint16_t> H;             // half: the bounce read, V · C · K² binary16
  detail::FloatScratchFile s_file;     // streamed: V · K²
  detail::FloatScratchFile bounce[2];  // streamed: V · C · K² each
  int written = 0;                     // the file the next bounce writes
  float s_max = 0.f;                   // max |S|
  std::mutex lock;                     // s_max, from the pass's blocks
  BounceRead read(const std::vector<float>& M) const {
    return half ? BounceRead{nullptr, H.data()} : BounceRead{M.data(), nullptr};
  }
};

void check_scratch(const GlossyJob& job, bool ok, const std::string& error) {
  if (!ok) throw BakeError(scene::scene_label(job.scene) + ": " + error);
}

void open_scratch(GlossyJob& job, BounceStore& store, const std::string& directory) {
  const std::size_t KK = job.KK(), per_vertex = std::size_t(job.C) * KK;
  std::string error;
  check_scratch(job, store.s_file.open(directory, job.V * KK, "the direct transfer", &error),
                error);
  for (int f = 0; f < (store.half ? 2 : 1); ++f)
    check_scratch(
        job, store.bounce[f].open(directory, job.V * per_vertex, "a glossy bounce", &error), error);
  if (store.half) store.written = 1;  // bounce[0] holds M⁽⁰⁾
}

// A block of the pass's matrices M⁽⁰⁾ (binary16 bounce): S to its file, M⁽⁰⁾ to bounce[0] and H.
void keep_pass_block(GlossyJob& job, BounceStore& store, std::size_t first, std::size_t count,
                     const float* m) {
  const std::size_t KK = job.KK(), per_vertex = std::size_t(job.C) * KK;
  std::vector<float> s(count * KK);
  float s_max = 0.f;
  for (std::size_t i = 0; i < count; ++i) std::copy_n(m + i * per_vertex, KK, &s[i * KK]);
  for (float x : s) s_max = std::max(s_max, std::fabs(x));
  std::string error;
  check_scratch(job, store.s_file.write(first * KK, count * KK, s.data(), &error), error);
  check_scratch(job, store.bounce[0].write(first * per_vertex, count * per_vertex, m, &error),
                error);
  prt::convert_floats_to_halves(m, count * per_vertex, &store.H[first * per_vertex]);
  std::lock_guard<std::mutex> guard(store.lock);
  store.s_max = std::max(store.s_max, s_max);
}

// S from the pass's matrices (channel 0 of M⁽⁰⁾, float bounce) into job.S or its file, max |S|.
void keep_direct(GlossyJob& job, const std::vector<float>& M, BounceStore& store) {
  const std::size_t KK = job.KK(), per_vertex = std::size_t(job.C) * KK;
  std::string error;
  if (!store.streamed) job.S.resize(job.V * KK);
  std::vector<float> chunk(store.streamed ? kBlock * KK : 0);
  for (std::size_t first = 0; first < job.V; first += kBlock) {
    const std::size_t n = std::min(kBlock, job.V - first);
    float* s = store.streamed ? chunk.data() : &job.S[first * KK];
    for (std::size_t i = 0; i < n; ++i) std::copy_n(&M[(first + i) * per_vertex], KK, &s[i * KK]);
    for (std::size_t e = 0; e < n * KK; ++e) store.s_max = std::max(store.s_max, std::fabs(s[e]));
    if (store.streamed)
      check_scratch(job, store.s_file.write(first * KK, n * KK, s, &error), error);
  }
  if (!store.streamed) store.next.resize(M.size());
}

// One bounce over the vertices of block blk: next = S + G(read); returns max |next − previous|.
float bounce_block(const GlossyJob& job, BounceRead read, const std::vector<float>& exit,
                   const std::vector<float>& M, BounceStore& store, std::size_t blk) {
  const std::size_t KK = job.KK(), per_vertex = std::size_t(job.C) * KK;
  const std::size_t first = blk * kBlock, n = std::min(job.V, first + kBlock) - first;
  std::vector<float> s_buffer, out_buffer, prev_buffer;
  const float* s = store.streamed ? nullptr : &job.S[first * KK];
  float* out = store.streamed ? nullptr : &store.next[first * per_vertex];
  const float* prev = store.half ? nullptr : &M[first * per_vertex];
  std::string error;
  if (store.streamed) {
    s_buffer.resize(n * KK);
    out_buffer.resize(n * per_vertex);
    check_scratch(job, store.s_file.read(first * KK, n * KK, s_buffer.data(), &error), error);
    s = s_buffer.data();
    out = out_buffer.data();
  }
  if (store.half) {  // the previous bounce in float, for the change
    prev_buffer.resize(n * per_vertex);
    check_scratch(job,
                  store.bounce[1 - store.written].read(first * per_vertex, n * per_vertex,
                                                       prev_buffer.data(), &error),
                  error);
    prev = prev_buffer.data();
  }
  BounceGatherer g(job, read, exit);
  const BlockHits& hits = job.block_hits[blk];
  std::size_t at = 0;
  float change = 0.f;
  for (std::size_t i = 0; i < n; ++i) {
    float* o = out + i * per_vertex;
    g.gather(first + i, s + i * KK, hits, &hits.mask[i * job.mask_words], &at, o);
    const float* m = prev + i * per_vertex;
    for (std::size_t e = 0; e < per_vertex; ++e) {
      const float d = std::fabs(o[e] - m[e]);
      // NaN compares false: keep it, so that a non-finite bounce is seen.
      if (!(d <= change)) change = d;
    }
  }
  if (store.streamed)
    check_scratch(
        job, store.bounce[store.written].write(first * per_vertex, n * per_vertex, out, &error),
        error);
  return change;
}

// After a streamed bounce: the bounce written becomes the one read (M, or H in binary16).
void load_written_bounce(const GlossyJob& job, std::vector<float>& M, BounceStore& store) {
  std::string error;
  const std::size_t total = job.V * job.C * job.KK(), chunk = std::size_t(1) << 22;
  std::vector<float> buffer(store.half ? std::min(chunk, total) : 0);
  for (std::size_t at = 0; at < total; at += chunk) {
    const std::size_t n = std::min(chunk, total - at);
    float* to = store.half ? buffer.data() : &M[at];
    check_scratch(job, store.bounce[store.written].read(at, n, to, &error), error);
    if (store.half) prt::convert_floats_to_halves(to, n, &store.H[at]);
  }
  if (store.half) store.written = 1 - store.written;
}

// Jacobi bounces: M (or H) holds M⁽ᵏ⁾; returns when done. Converged means the last bounce
// changed no entry by more than bounce_tolerance × max|S|, whether the bounces were counted or
// solved for.
void run_bounces(GlossyJob& job, std::vector<float>& M, BounceStore& store) {
  const Clock::time_point t0 = Clock::now();
  const float s_max = store.s_max;
  const int max_bounces = job.o.bounces < 0 ? kMaxGlossyBounces : job.o.bounces;
  if (job.progress) job.progress->start("glossy bounces", job.o.bounces < 0 ? 0 : max_bounces);
  job.st.converged = false;
  std::vector<float> exit(job.V * job.C * std::size_t(job.K));
  std::vector<float> compressed;  // bounce_cpca_clusters > 0: what the gather reads
  if (job.o.bounce_cpca_clusters > 0 && job.budget)
    job.budget->charge(M.size() * 4, "the compressed bounce's reconstruction");
  for (int k = 0; k < max_bounces; ++k) {
    if (job.o.bounce_cpca_clusters > 0) compressed_transfer(job, M, compressed);
    const BounceRead read =
        job.o.bounce_cpca_clusters > 0 ? BounceRead{compressed.data(), nullptr} : store.read(M);
    lambert_exit(job, read, exit);
    std::vector<float> block_change(job.blocks(), 0.f);
    tbb::parallel_for(std::size_t(0), job.blocks(), [&](std::size_t blk) {
      block_change[blk] = bounce_block(job, read, exit, M, store, blk);
    });
    if (store.streamed)
      load_written_bounce(job, M, store);
    else
      M.swap(store.next);
    float change = 0.f;
    for (float c : block_change)
      if (!(c <= change)) change = c;
    const double relative = s_max > 0.f ? double(change) / s_max : 0.0;
    job.st.bounce_change.push_back(relative);
    job.st.bounces = k + 1;
    if (job.progress) job.progress->advance(1, 0);
    check_divergence(job);
    job.st.converged = relative <= job.o.bounce_tolerance;
    if (job.o.bounces < 0 && job.st.converged) break;
  }
  if (job.progress) job.progress->finish();
  job.st.seconds_bounces = seconds_since(t0);
}

int glossy_channels(const scene::Scene& scene, const std::vector<brdf::Material>& materials,
                    bool interreflect) {
  if (!interreflect) return 1;
  for (const glm::vec3& a : scene.albedo)
    if (a.x != a.y || a.y != a.z) return 3;
  for (const brdf::Material& m : materials)
    if (m.model == brdf::MaterialModel::kMerl || !grey(m.diffuse) || !grey(m.specular)) return 3;
  return 1;
}

void validate_glossy_options(const scene::Scene& scene, const GlossyBakeOptions& o) {
  const std::string name = scene::scene_label(scene);
  for (const scene::ScenePrimitive& p : scene.primitives)
    if (!p.brdf_texture_problem.empty()) throw BakeError(name + ": " + p.brdf_texture_problem);
  if (o.order < 1 || o.order > kMaxGlossyBakeOrder)
    throw BakeError(name + ": glossy SH order " + std::to_string(o.order) + " is outside [1, " +
                    std::to_string(kMaxGlossyBakeOrder) + "]");
  BakeOptions b;  // the scene checks and the options the diffuse bake shares
  b.kind = o.bounces == 0 ? prt::TransferKind::Shadowed : prt::TransferKind::Interreflected;
  b.order = o.order;
  b.samples = o.samples;
  b.bounces = o.bounces;
  b.bounce_tolerance = o.bounce_tolerance;
  b.threads = o.threads;
  validate_bake_inputs(scene, b);
}

std::string glossy_metadata(const GlossyJob& job, const prt::GlossyTransferData& d) {
  const GlossyBakeStatistics& st = job.st;
  nlohmann::json meta;
  meta["generator"] = "prt bake --glossy";
  meta["scene"] = job.scene.source_path;
  meta["sh_basis"] = sh::kBasisConvention;
  meta["transfer"] = job.interreflect ? "glossy interreflected" : "glossy shadowed";
  meta["rows"] = "SH of the vertex's local tangent frame (+z normal, +x tangent)";
  meta["columns"] = "SH of the global scene frame (+Y up)";
  meta["domain"] = "upper hemisphere, no cosine (cos is in the BRDF projection b)";
  meta["order"] = job.order;
  meta["channels"] = job.C;
  meta["samples_requested"] = job.o.samples;
  meta["samples_per_vertex"] = job.N;
  meta["sampling"] = "Owen-scrambled Sobol (0,2)-sequence, uniform on the hemisphere";
  meta["seed"] = job.o.seed;
  meta["precision"] = d.storage == prt::Precision::F16 ? "f16" : "f32";
  nlohmann::json mats = nlohmann::json::array();
  for (const brdf::Material& m : job.materials) mats.push_back(brdf::describe(m));
  meta["materials"] = mats;
  meta["vertices"] = job.V;
  meta["triangles"] = st.triangles;
  meta["rays"] = st.rays;
  if (job.interreflect) {
    nlohmann::json b;
    b["bounces_requested"] = job.o.bounces;
    b["bounces"] = st.bounces;
    b["tolerance"] = job.o.bounce_tolerance;
    b["converged"] = st.converged;
    b["bounce_change"] = st.bounce_change;
    b["hits"] = st.hits;
    b["back_face_hits"] = st.back_face_hits;
    nlohmann::json methods = nlohmann::json::array();
    for (const prt::BrdfProjection& p : job.projections) methods.push_back(method_name(p.method()));
    b["brdf_projection"] = methods;
    meta["interreflection"] = b;
  }
  return meta.dump();
}

void store_geometry(const scene::Scene& scene, const GlossyJob& job, prt::GlossyTransferData& d) {
  const std::size_t V = job.V;
  d.vertex_count = V;
  d.positions.resize(3 * V);
  d.normals.resize(3 * V);
  d.tangents.resize(4 * V);
  for (std::size_t v = 0; v < V; ++v) {
    const Frame& f = job.frames[v];
    const float w = glm::dot(glm::cross(f.n, f.t), f.b) < 0.f ? -1.f : 1.f;
    for (int a = 0; a < 3; ++a) {
      d.positions[3 * v + a] = scene.positions[v][a];
      d.normals[3 * v + a] = f.n[a];
      d.tangents[4 * v + a] = f.t[a];
    }
    d.tangents[4 * v + 3] = w;
  }
  for (const scene::ScenePrimitive& p : scene.primitives)
    d.primitives.push_back({p.first_vertex, p.vertex_count, p.name});
  d.fingerprint = prt::geometry_fingerprint(d.positions.data(), V);
}

}  // namespace

void glossy_scene_materials(const scene::Scene& scene, std::vector<brdf::Material>& materials,
                            std::vector<uint32_t>& material_of_vertex) {
  scene::vertex_materials(scene, materials, material_of_vertex);
}

namespace {

// Where the bake's matrices go: into result.data.matrices, or (writer set) into a file.
struct GlossyOutput {
  GlossyBakeResult& result;
  prt::GlossyTransferFileWriter* writer = nullptr;
  std::string path;            // the writer's, for messages
  std::mutex* lock = nullptr;  // the writer is called from the blocks' tasks one at a time
};

void put_matrices(const GlossyOutput& out, const GlossyJob& job, std::size_t first,
                  std::size_t count, const float* m) {
  const std::size_t per_vertex = std::size_t(job.C) * job.KK();
  if (out.writer == nullptr) {
    std::copy_n(m, count * per_vertex, &out.result.data.matrices[first * per_vertex]);
    return;
  }
  prt::Status s = prt::Status::Ok();
  {
    std::lock_guard<std::mutex> guard(*out.lock);
    s = out.writer->write(first, count, m);
  }
  if (!s.ok()) throw BakeError(s.message());
}

// The scratch files of streamed bounces go beside the output.
std::string scratch_directory(const std::string& output_path) {
  const std::string parent = std::filesystem::path(output_path).parent_path().string();
  return parent.empty() ? std::string(".") : parent;
}

unsigned worker_threads(const GlossyBakeOptions& o) {
  return o.threads > 0
             ? unsigned(o.threads)
             : std::max(1u, static_cast<unsigned>(tbb::this_task_arena::max_concurrency()));
}

// Charges what the bake will hold before it holds it: frames and the file's geometry sections;
// shadowed, the matrices of the blocks in flight (streamed) or of every vertex (in memory);
// interreflected, M and the Lambert exit rows, and the next bounce and S (in memory) or the
// blocks in flight of both (streamed: the rest is in scratch files). The hits are charged block
// by block as the ray pass keeps them.
void charge_bake(prt::MemoryBudget& budget, const GlossyJob& job, const GlossyBakeOptions& o,
                 bool streamed) {
  const uint64_t V = job.V, KK = job.KK(), C = job.C;
  budget.charge(V * (sizeof(Frame) + 16 + 44 + 4), "the vertex frames and geometry");
  const uint64_t all = V * C * KK * 4;
  const uint64_t in_flight = uint64_t(worker_threads(o)) * kBlock * 4;
  if (!job.interreflect) {
    if (streamed)
      budget.charge(in_flight * KK * 2, "the glossy matrices of the vertex blocks in flight");
    else
      budget.charge(all, "the glossy transfer matrices");
    return;
  }
  if (streamed && o.bounce_precision == prt::Precision::F16) {
    budget.charge(all / 2, "the binary16 glossy matrices of the bounce read");
    budget.charge(in_flight * (2 * C + 1) * KK,
                  "the glossy matrices of the vertex blocks in flight");
  } else if (streamed) {
    budget.charge(all, "the glossy matrices of the bounce read");
    budget.charge(in_flight * (C + 1) * KK, "the glossy matrices of the vertex blocks in flight");
  } else {
    budget.charge(2 * all, "the glossy matrices of two bounces");
    budget.charge(V * KK * 4, "the direct transfer");
  }
  budget.charge(V * C * job.K * 4, "the Lambert exit rows");
}

GlossyJob make_job(const scene::Scene& scene, const GlossyBakeOptions& o, ProgressSink* progress,
                   GlossyBakeStatistics& st) {
  return GlossyJob{scene,
                   o,
                   progress,
                   scene.vertex_count(),
                   o.order,
                   o.order * o.order,
                   round_up_to_packet(o.samples),
                   1,
                   o.bounces != 0,
                   {},
                   {},
                   {},
                   {},
                   nullptr,
                   {},
                   nullptr,
                   {},
                   {},
                   (std::size_t(round_up_to_packet(o.samples)) + 63) / 64,
                   {},
                   st};
}

// The frames, materials and zonal factors of `inputs` (glossy_inputs of the scene).
void set_inputs(GlossyJob& job, const GlossyInputs& in) {
  job.materials = in.materials;
  job.material_of_vertex = in.material_of_vertex;
  job.frames.resize(job.V);
  for (std::size_t v = 0; v < job.V; ++v) {
    const glm::vec3 n = glm::normalize(job.scene.normals[v]), t = glm::vec3(in.tangents[v]);
    job.frames[v] = {t, in.tangents[v].w * glm::cross(n, t), n};
  }
  for (int l = 0; l < job.order; ++l)
    job.zonal_over_pi.push_back(
        static_cast<float>(sh::clamped_cosine_zonal_coefficient(l) / sh::kPi));
}

// The sampling pass's results of every vertex (`pre`, taken) where run_sampling_pass puts its own:
// the hits, block by block, quantised as the pass quantises them (quantise_hit of the same float
// barycentrics, the same sample bits), so that the bounces read the same BlockHits.
void use_sampled(GlossyJob& job, detail::GlossySampled& pre) {
  const std::size_t KK = job.KK(), per_vertex = std::size_t(job.C) * KK;
  if (job.matrices) {
    for (std::size_t v = 0; v < job.V; ++v)
      for (int c = 0; c < job.C; ++c)
        std::copy_n(&pre.direct[v * KK], KK, &(*job.matrices)[v * per_vertex + c * KK]);
  } else if (job.C == 1) {  // shadowed (one channel), or a binary16 bounce of one channel
    for (std::size_t first = 0; first < job.V; first += kBlock)
      job.sink(first, std::min(kBlock, job.V - first), &pre.direct[first * KK]);
  } else {  // a binary16 bounce: blocks of C · K² a vertex, as the pass gives its sink
    std::vector<float> block(kBlock * per_vertex);
    for (std::size_t first = 0; first < job.V; first += kBlock) {
      const std::size_t count = std::min(kBlock, job.V - first);
      for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < job.C; ++c)
          std::copy_n(&pre.direct[(first + i) * KK], KK, &block[i * per_vertex + c * KK]);
      job.sink(first, count, block.data());
    }
  }
  job.st.rays = pre.rays;
  job.st.back_face_hits = pre.back_face_hits;
  if (!job.interreflect) return;
  // The parts' records are held until every block is made (charged for that time).
  const uint64_t records = pre.hits.size() * sizeof(GlossyHitRecord) + 8 * (job.V + 1);
  if (job.budget) job.budget->charge(records, "the glossy parts' ray hits");
  job.block_hits.assign(job.blocks(), BlockHits{});
  for (std::size_t blk = 0; blk < job.blocks(); ++blk) {
    const std::size_t first = blk * kBlock, end = std::min(job.V, (blk + 1) * kBlock);
    BlockHits& b = job.block_hits[blk];
    b.mask.assign((end - first) * job.mask_words, 0);
    const uint64_t begin = pre.hit_offset[first], stop = pre.hit_offset[end];
    b.hits.reserve(stop - begin);
    if (job.o.exact_hits) b.exact.reserve(2 * (stop - begin));
    for (std::size_t v = first; v < end; ++v) {
      uint64_t* mask = &b.mask[(v - first) * job.mask_words];
      for (uint64_t i = pre.hit_offset[v]; i < pre.hit_offset[v + 1]; ++i) {
        const GlossyHitRecord& h = pre.hits[i];
        b.hits.push_back(quantise_hit(h.triangle, h.u, h.v));
        if (job.o.exact_hits) {
          b.exact.push_back(h.u);
          b.exact.push_back(h.v);
        }
        mask[h.sample / 64] |= uint64_t(1) << (h.sample % 64);
      }
    }
    if (job.budget) job.budget->charge(b.bytes(), "the glossy bounces' ray hits");
    job.st.hits += b.hits.size();
    job.st.gather_bytes += b.bytes();
  }
  std::vector<GlossyHitRecord>().swap(pre.hits);
  std::vector<uint64_t>().swap(pre.hit_offset);
  if (job.budget) job.budget->release(records);
}

// The whole bake; with `pre`, its sampling pass is replaced by those results (a farm merge).
void bake_glossy(const scene::Scene& scene, const GlossyBakeOptions& o, ProgressSink* progress,
                 GlossyOutput& out, const GlossyInputs* inputs = nullptr,
                 detail::GlossySampled* pre = nullptr) {
  const Clock::time_point t_start = Clock::now();
  validate_glossy_options(scene, o);
  std::optional<tbb::global_control> thread_limit;
  if (o.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(o.threads));
  GlossyBakeResult& result = out.result;
  GlossyBakeStatistics& st = result.stats;
  GlossyJob job = make_job(scene, o, progress, st);
  prt::MemoryBudget budget(o.memory_limit, scene::scene_label(scene));
  job.budget = &budget;
  GlossyInputs derived;  // the single bake derives them; a merge has them from its parts
  if (!inputs) derived = glossy_inputs(scene);
  const GlossyInputs& in = inputs ? *inputs : derived;
  job.C = glossy_channels(scene, in.materials, job.interreflect);
  const bool streamed = out.writer != nullptr || !out.path.empty();
  if (job.interreflect && o.bounce_precision == prt::Precision::F16 &&
      (!streamed || o.bounce_cpca_clusters > 0))
    throw BakeError(scene::scene_label(scene) +
                    ": a binary16 bounce needs a bake streamed to a file, without bounce CPCA");
  charge_bake(budget, job, o, streamed);
  set_inputs(job, in);
  st.vertices = job.V;
  st.triangles = scene.triangles.size();
  st.samples_per_vertex = job.N;
  if (job.interreflect) {
    const Clock::time_point t0 = Clock::now();
    for (std::size_t m = 0; m < job.materials.size(); ++m)
      job.projections.push_back(
          make_projection(job.materials[m], job.order, o.projection,
                          scene::scene_label(scene) + ": material " + std::to_string(m)));
    st.seconds_projection = seconds_since(t0);
  }
  prt::GlossyTransferData& d = result.data;
  d.order = static_cast<uint32_t>(job.order);
  d.channels = static_cast<uint32_t>(job.C);
  d.storage = o.precision;
  d.interreflected = job.interreflect;
  store_geometry(scene, job, d);
  d.materials = job.materials;
  d.material_of_vertex = job.material_of_vertex;
  std::unique_ptr<prt::GlossyTransferFileWriter> writer;
  if (!out.path.empty()) {  // opened before the work: an unwritable path fails at once
    auto made = prt::GlossyTransferFileWriter::create(out.path, d);
    if (!made.ok()) throw BakeError(made.status().message());
    writer = std::move(made).value();
    out.writer = writer.get();
  }
  std::vector<float> M;  // interreflected, float bounce: every vertex's matrices
  BounceStore store;
  if (job.interreflect) {
    store.streamed = out.writer != nullptr;
    store.half = o.bounce_precision == prt::Precision::F16;
    if (store.streamed) open_scratch(job, store, scratch_directory(out.path));
    if (store.half) {
      store.H.resize(job.V * job.C * job.KK());
      job.sink = [&](std::size_t first, std::size_t count, const float* m) {
        keep_pass_block(job, store, first, count, m);
      };
    } else {
      M.resize(job.V * job.C * job.KK());
      job.matrices = &M;
    }
  } else {
    if (!out.writer) d.matrices.resize(job.V * job.C * job.KK());
    job.sink = [&](std::size_t first, std::size_t count, const float* m) {
      put_matrices(out, job, first, count, m);
    };
  }
  if (pre)
    use_sampled(job, *pre);
  else
    run_sampling_pass(job);
  if (job.interreflect) {
    if (st.hits > 0) {
      if (!store.half) keep_direct(job, M, store);
      run_bounces(job, M, store);
    }
    if (!out.writer) {
      d.matrices.swap(M);
    } else if (store.half) {  // the last float bounce, from its file, in blocks
      const std::size_t per_vertex = std::size_t(job.C) * job.KK();
      std::vector<float> block(16 * kBlock * per_vertex);
      std::string error;
      for (std::size_t first = 0; first < job.V; first += 16 * kBlock) {
        const std::size_t count = std::min(job.V - first, 16 * kBlock);
        check_scratch(job,
                      store.bounce[1 - store.written].read(first * per_vertex, count * per_vertex,
                                                           block.data(), &error),
                      error);
        put_matrices(out, job, first, count, block.data());
      }
    } else {  // in blocks, so that binary16 conversion holds one block
      for (std::size_t first = 0; first < job.V; first += 16 * kBlock) {
        const std::size_t count = std::min(job.V - first, 16 * kBlock);
        put_matrices(out, job, first, count, &M[first * job.C * job.KK()]);
      }
    }
  }
  st.seconds_total = seconds_since(t_start);
  d.metadata_json = glossy_metadata(job, d);
  if (out.writer) {
    const prt::Status s = out.writer->finish(d.metadata_json);
    if (!s.ok()) throw BakeError(s.message());
  }
  st.peak_charged_bytes = budget.peak();
}

}  // namespace

GlossyBakeResult bake_glossy_transfer(const scene::Scene& scene, const GlossyBakeOptions& o,
                                      ProgressSink* progress) {
  GlossyBakeResult result;
  GlossyOutput out{result, nullptr, {}, nullptr};
  bake_glossy(scene, o, progress, out);
  return result;
}

GlossyBakeResult bake_glossy_transfer_to_file(const scene::Scene& scene, const GlossyBakeOptions& o,
                                              const std::string& path, ProgressSink* progress) {
  if (path.empty()) throw BakeError(scene::scene_label(scene) + ": no output path");
  GlossyBakeResult result;
  std::mutex lock;
  GlossyOutput out{result, nullptr, path, &lock};
  bake_glossy(scene, o, progress, out);
  return result;
}

namespace detail {

GlossySampled sample_glossy_vertices(const scene::Scene& scene, const GlossyBakeOptions& o,
                                     const GlossyInputs& inputs,
                                     const std::vector<uint32_t>& vertices, ProgressSink* progress,
                                     GlossyBakeStatistics& st) {
  const Clock::time_point t0 = Clock::now();
  validate_glossy_options(scene, o);
  std::optional<tbb::global_control> thread_limit;
  if (o.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(o.threads));
  GlossyJob job = make_job(scene, o, progress, st);
  set_inputs(job, inputs);  // one channel: S_v as the single bake's first channel
  prt::MemoryBudget budget(o.memory_limit, scene::scene_label(scene));
  const std::size_t R = vertices.size(), KK = job.KK(), blocks = (R + kBlock - 1) / kBlock;
  budget.charge(job.V * (sizeof(Frame) + 8) + R * KK * 4, "the shard's frames and matrices");
  const scene::RayCaster caster(scene);
  GlossySampled out;
  out.direct.resize(R * KK);
  // Each block's hits as records (sample, triangle, float barycentrics), in vertex and sample
  // order: what the merge quantises as the single bake's pass does (use_sampled).
  std::vector<std::vector<GlossyHitRecord>> block_records(blocks);
  std::vector<std::vector<uint32_t>> block_counts(blocks);
  std::vector<uint64_t> rays(blocks, 0), back(blocks, 0);
  if (progress) progress->start("glossy bake", R);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
    VertexSampler sampler(job, caster);
    sampler.exact = true;
    const std::size_t first = blk * kBlock, end = std::min(R, first + kBlock);
    BlockHits hits;
    std::vector<uint64_t> mask(job.interreflect ? job.mask_words : 0);
    for (std::size_t r = first; r < end; ++r) {
      std::fill(mask.begin(), mask.end(), 0);
      const std::size_t before = hits.hits.size();
      rays[blk] += sampler.sample(vertices[r], &out.direct[r * KK], hits, mask.data(), back[blk]);
      if (!job.interreflect) continue;
      std::size_t i = before;
      for (std::size_t w = 0; w < job.mask_words; ++w)
        for (uint64_t bits = mask[w]; bits != 0; bits &= bits - 1, ++i)
          block_records[blk].push_back({uint32_t(w * 64 + __builtin_ctzll(bits)),
                                        hits.hits[i].triangle, hits.exact[2 * i],
                                        hits.exact[2 * i + 1]});
      block_counts[blk].push_back(static_cast<uint32_t>(hits.hits.size() - before));
    }
    if (progress) progress->advance(end - first, rays[blk]);
  });
  if (progress) progress->finish();
  out.hit_offset.assign(1, 0);
  uint64_t hit_count = 0;
  for (const std::vector<GlossyHitRecord>& b : block_records) hit_count += b.size();
  budget.charge(hit_count * sizeof(GlossyHitRecord) + 8 * (R + 1), "the shard's ray hits");
  out.hits.reserve(hit_count);
  for (std::size_t blk = 0; blk < blocks; ++blk) {
    out.rays += rays[blk];
    out.back_face_hits += back[blk];
    for (uint32_t c : block_counts[blk]) out.hit_offset.push_back(out.hit_offset.back() + c);
    out.hits.insert(out.hits.end(), block_records[blk].begin(), block_records[blk].end());
    std::vector<GlossyHitRecord>().swap(block_records[blk]);
  }
  st.vertices = job.V;
  st.triangles = scene.triangles.size();
  st.samples_per_vertex = job.N;
  st.rays = out.rays;
  st.back_face_hits = out.back_face_hits;
  st.hits = out.hits.size();
  st.seconds_rays = st.seconds_total = seconds_since(t0);
  st.peak_charged_bytes = budget.peak();
  return out;
}

GlossyBakeResult finish_glossy_bake_to_file(const scene::Scene& scene, const GlossyBakeOptions& o,
                                            const GlossyInputs& inputs, GlossySampled& all,
                                            const std::string& path, ProgressSink* progress) {
  if (path.empty()) throw BakeError(scene::scene_label(scene) + ": no output path");
  GlossyBakeResult result;
  std::mutex lock;
  GlossyOutput out{result, nullptr, path, &lock};
  bake_glossy(scene, o, progress, out, &inputs, &all);
  return result;
}

}  // namespace detail

}  // namespace prt::bake
