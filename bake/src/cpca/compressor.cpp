// compressor.cpp — clustered PCA of per-vertex transfer matrices; see bake/cpca/compressor.h.
#include "bake/cpca/compressor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <new>
#include <sstream>
#include <thread>

#include "bake/cpca/matrix_source.h"
#include "numerics/rng.h"
#include "pca.h"
#include "prt/core/memory_budget.h"
#include "row_metric.h"

namespace prt {
namespace {

using detail::dot;

// Runs fn(i) for i < n on up to `threads` threads (indices interleaved in chunks of 16).
// Every fn(i) must write only its own outputs: the result then does not depend on threads.
// Throws std::bad_alloc when a worker ran out of memory.
void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& fn) {
  constexpr std::size_t kChunk = 16;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const unsigned t_count = static_cast<unsigned>(
      std::min<std::size_t>(std::max(1u, threads), std::max<std::size_t>(chunks, 1)));
  std::atomic<bool> failed{false};
  auto work = [&](unsigned t) {
    try {
      for (std::size_t c = t; c < chunks; c += t_count) {
        for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) fn(i);
      }
    } catch (...) {
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < t_count; ++t) {
    try {
      pool.emplace_back(work, t);
    } catch (...) {  // no thread: the calling thread does that share
      for (std::size_t c = t; c < chunks; c += t_count) {
        for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) fn(i);
      }
    }
  }
  work(0);
  for (auto& th : pool) th.join();
  if (failed) throw std::bad_alloc();
}

double squared_distance(const float* x, const double* mu, std::size_t d) {
  double s0 = 0, s1 = 0;
  std::size_t e = 0;
  for (; e + 2 <= d; e += 2) {
    const double a = x[e] - mu[e], b = x[e + 1] - mu[e + 1];
    s0 += a * a;
    s1 += b * b;
  }
  for (; e < d; ++e) s0 += (x[e] - mu[e]) * (x[e] - mu[e]);
  return s0 + s1;
}

// The state of one CPCA run.
struct Model {
  std::size_t d = 0, k = 0, clusters = 0;
  std::vector<std::vector<double>> mean, basis;  // per cluster: d, k·d
  std::vector<uint32_t> assignment;
  std::vector<double> error;  // per vertex: squared reconstruction error under `assignment`
};

struct Problem {
  const float* x;  // the vectors the clusters are fitted to: W x under a row metric
  std::size_t n, d;
  const CpcaOptions* options;
  const float* original = nullptr;            // x itself (== x without a metric)
  const detail::RowMetric* metric = nullptr;  // null: the plain metric
};

// Squared error of reconstructing x from cluster q: |x − μ|² − Σ_k (U_k·(x − μ))².
double reconstruction_error(const Model& m, std::size_t q, const float* x, double* scratch) {
  const std::size_t d = m.d;
  const double* mu = m.mean[q].data();
  for (std::size_t e = 0; e < d; ++e) scratch[e] = x[e] - mu[e];
  double err = dot(scratch, scratch, d);
  for (std::size_t k = 0; k < m.k; ++k) {
    const double w = dot(scratch, &m.basis[q][k * d], d);
    err -= w * w;
  }
  return std::max(err, 0.0);
}

// k-means++ seeding (Arthur & Vassilvitskii 2007) with a fixed-seed generator, then every
// vertex joins its nearest seed.
void seed_clusters(const Problem& pb, Model* m) {
  const std::size_t n = pb.n, d = pb.d;
  numerics::SplitMix64 rng{pb.options->seed};
  auto next_uniform = [&rng]() { return rng.uniform(); };
  std::vector<std::size_t> seeds;
  seeds.push_back(
      std::min(n - 1, static_cast<std::size_t>(next_uniform() * static_cast<double>(n))));
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  std::vector<uint32_t> owner(n, 0);
  std::vector<double> centre(d);
  for (std::size_t s = 0; s < m->clusters; ++s) {
    if (s > 0) {
      double total = 0.0;
      for (double x : nearest) total += x;
      std::size_t pick = n;
      if (total > 0.0) {
        const double r = next_uniform() * total;
        double acc = 0.0;
        for (std::size_t v = 0; v < n && pick == n; ++v) {
          acc += nearest[v];
          if (nearest[v] > 0.0 && acc >= r) pick = v;
        }
        for (std::size_t v = n; v-- > 0 && pick == n;) {
          if (nearest[v] > 0.0) pick = v;  // rounding left r beyond the last sum
        }
      }
      if (pick == n) pick = s % n;  // every vertex coincides with a seed
      seeds.push_back(pick);
    }
    const float* c = pb.x + seeds[s] * d;
    for (std::size_t e = 0; e < d; ++e) centre[e] = c[e];
    parallel_for(n, pb.options->threads, [&](std::size_t v) {
      const double dist = squared_distance(pb.x + v * d, centre.data(), d);
      if (dist < nearest[v]) {
        nearest[v] = dist;
        owner[v] = static_cast<uint32_t>(s);
      }
    });
  }
  m->assignment = owner;
}

// PCA of every cluster on the current assignment (warm-started from the current vectors).
void fit_clusters(const Problem& pb, Model* m, bool warm) {
  std::vector<std::vector<uint32_t>> members(m->clusters);
  for (std::size_t v = 0; v < pb.n; ++v)
    members[m->assignment[v]].push_back(static_cast<uint32_t>(v));
  std::vector<std::vector<double>> old_basis;
  if (warm) old_basis = m->basis;
  m->mean.assign(m->clusters, {});
  m->basis.assign(m->clusters, {});
  parallel_for(m->clusters, pb.options->threads, [&](std::size_t q) {
    detail::PcaInput in;
    in.x = pb.x;
    in.d = pb.d;
    in.members = members[q].data();
    in.member_count = members[q].size();
    in.k = m->k;
    in.warm = warm ? &old_basis[q] : nullptr;
    in.power_iterations = pb.options->power_iterations;
    in.seed = pb.options->seed * 0x100000001b3ull + q;
    detail::cluster_pca(in, &m->mean[q], &m->basis[q]);
  });
}

// Moves every vertex to the candidate cluster with the least reconstruction error; returns
// the number of vertices that moved. Empty clusters then take the worst-reconstructed vertices.
std::size_t reassign(const Problem& pb, Model* m) {
  const std::size_t n = pb.n, d = pb.d, cand = std::max<uint32_t>(1, pb.options->candidates);
  std::vector<uint32_t> next(n);
  m->error.assign(n, 0.0);
  parallel_for(n, pb.options->threads, [&](std::size_t v) {
    const float* x = pb.x + v * d;
    std::vector<std::pair<double, uint32_t>> near(m->clusters);
    for (std::size_t q = 0; q < m->clusters; ++q) {
      near[q] = {squared_distance(x, m->mean[q].data(), d), static_cast<uint32_t>(q)};
    }
    const std::size_t c = std::min(cand, near.size());
    std::partial_sort(near.begin(), near.begin() + c, near.end());
    std::vector<double> scratch(d);
    // The current cluster is always a candidate, so no vertex gets worse.
    double best = reconstruction_error(*m, m->assignment[v], x, scratch.data());
    uint32_t best_q = m->assignment[v];
    for (std::size_t i = 0; i < c; ++i) {
      const uint32_t q = near[i].second;
      if (q == best_q) continue;
      const double e = reconstruction_error(*m, q, x, scratch.data());
      if (e < best || (e == best && q < best_q)) {
        best = e;
        best_q = q;
      }
    }
    next[v] = best_q;
    m->error[v] = best;
  });
  std::size_t moved = 0;
  for (std::size_t v = 0; v < n; ++v) moved += next[v] != m->assignment[v];
  m->assignment.swap(next);
  // Empty clusters: re-seed each with the worst vertex of a cluster that keeps ≥ 1 member.
  std::vector<std::size_t> size(m->clusters, 0);
  for (uint32_t q : m->assignment) ++size[q];
  std::vector<uint32_t> by_error(n);
  for (std::size_t v = 0; v < n; ++v) by_error[v] = static_cast<uint32_t>(v);
  std::stable_sort(by_error.begin(), by_error.end(),
                   [&](uint32_t a, uint32_t b) { return m->error[a] > m->error[b]; });
  std::size_t next_worst = 0;
  for (std::size_t q = 0; q < m->clusters; ++q) {
    if (size[q] != 0) continue;
    while (next_worst < n && size[m->assignment[by_error[next_worst]]] < 2) ++next_worst;
    if (next_worst == n) break;
    const uint32_t v = by_error[next_worst++];
    --size[m->assignment[v]];
    m->assignment[v] = static_cast<uint32_t>(q);
    size[q] = 1;
    ++moved;
  }
  return moved;
}

// Rounds the model to floats — mapped back by W⁻¹ under a row metric — and computes the weights
// against the rounded mean and vectors, in the metric's inner product (a, G b).
CpcaTransfer to_transfer(const Problem& pb, const Model& m, uint32_t order, uint32_t channels) {
  CpcaTransfer t;
  t.order = order;
  t.channels = channels;
  t.cluster_count = static_cast<uint32_t>(m.clusters);
  t.vector_count = static_cast<uint32_t>(m.k);
  t.vertex_count = pb.n;
  const std::size_t d = pb.d, k = m.k;
  t.means.resize(m.clusters * d);
  t.basis.resize(m.clusters * k * d);
  const detail::RowMetric* g = pb.metric;
  std::vector<double> back(d);
  auto round_back = [&](const double* src, float* dst) {
    if (g != nullptr) g->apply(g->w_inv, src, back.data());
    const double* from = g != nullptr ? back.data() : src;
    for (std::size_t e = 0; e < d; ++e) dst[e] = static_cast<float>(from[e]);
  };
  for (std::size_t q = 0; q < m.clusters; ++q) {
    round_back(m.mean[q].data(), &t.means[q * d]);
    for (std::size_t j = 0; j < k; ++j) round_back(&m.basis[q][j * d], &t.basis[(q * k + j) * d]);
  }
  // Under a metric the weights are (x − μ)·(G U_k): G U_k per cluster, from the rounded U_k.
  std::vector<double> gu(g != nullptr ? m.clusters * k * d : 0);
  if (g != nullptr) {
    parallel_for(m.clusters * k, pb.options->threads,
                 [&](std::size_t qk) { g->apply(g->g, &t.basis[qk * d], &gu[qk * d]); });
  }
  t.cluster_of_vertex = m.assignment;
  t.weights.resize(pb.n * k);
  parallel_for(pb.n, pb.options->threads, [&](std::size_t v) {
    const uint32_t q = m.assignment[v];
    const float* x = pb.original + v * d;
    const float* mu = &t.means[q * d];
    for (std::size_t j = 0; j < k; ++j) {
      const float* u = &t.basis[(q * k + j) * d];
      double s = 0.0;
      if (g == nullptr) {
        for (std::size_t e = 0; e < d; ++e) s += (static_cast<double>(x[e]) - mu[e]) * u[e];
      } else {
        const double* gu_j = &gu[(q * k + j) * d];
        for (std::size_t e = 0; e < d; ++e) s += (static_cast<double>(x[e]) - mu[e]) * gu_j[e];
      }
      t.weights[v * k + j] = static_cast<float>(s);
    }
  });
  return t;
}

CpcaTransfer run_cpca(const Problem& pb, std::size_t k, uint32_t order, uint32_t channels) {
  Model m;
  m.d = pb.d;
  m.k = k;
  m.clusters = std::min<std::size_t>(pb.options->clusters, pb.n);
  seed_clusters(pb, &m);
  fit_clusters(pb, &m, false);
  for (uint32_t it = 0; it < pb.options->iterations; ++it) {
    if (reassign(pb, &m) == 0) break;
    fit_clusters(pb, &m, true);
  }
  return to_transfer(pb, m, order, channels);
}

// What a run holds besides the vectors themselves, charged before it is allocated: per vertex
// the cluster state (assignment, error, seeding distances, the next assignment, the order by
// error, the members lists: 40 bytes) and the weights; per cluster the double model twice (the
// warm start keeps the previous one) and the float result; the PCA's z (members · p doubles,
// at most n · p over the clusters in flight) and each thread's block of centred members.
uint64_t run_bytes(std::size_t n, std::size_t d, std::size_t k, std::size_t clusters,
                   unsigned threads) {
  const uint64_t p = std::min<uint64_t>(k + 8, d);
  return uint64_t(n) * (40 + 4 * k + 8 * p) + uint64_t(clusters) * (k + 1) * d * (16 + 4) +
         uint64_t(std::max(1u, threads)) * (256 + 4 * p) * d * 8;
}

Status check_input(uint32_t order, uint32_t channels, uint64_t n, const float* x,
                   const CpcaOptions& o) {
  if (order < 1 || order > kMaxCpcaOrder) {
    return Status::Error("cpca: SH order " + std::to_string(order) + " is outside [1, 16]");
  }
  if (channels != 1 && channels != 3) {
    return Status::Error("cpca: channel count " + std::to_string(channels) + " is not 1 or 3");
  }
  if (n == 0 || x == nullptr) return Status::Error("cpca: no vertices");
  if (o.clusters == 0 || o.clusters > kMaxCpcaClusters) {
    return Status::Error("cpca: cluster count " + std::to_string(o.clusters) +
                         " is outside [1, 65535]");
  }
  if (o.vectors > 4096 || o.max_vectors > 4096) {
    return Status::Error("cpca: more than 4096 vectors per cluster");
  }
  if (!(o.target_relative_rms >= 0.0) || !std::isfinite(o.target_relative_rms)) {
    return Status::Error("cpca: target error is not a finite non-negative number");
  }
  const std::size_t d = std::size_t(channels) * order * order * order * order;
  for (std::size_t i = 0; i < n * d; ++i) {
    if (!std::isfinite(x[i])) {
      return Status::Error("cpca: matrix entry " + std::to_string(i % d) + " of vertex " +
                           std::to_string(i / d) + " is not finite");
    }
  }
  return Status::Ok();
}

// sqrt(Σ_v (δ, G δ) / Σ_v (x, G x)), δ = x − x̃ (G = I when `g` is null).
double weighted_error(const CpcaTransfer& t, const float* x, const detail::RowMetric* g) {
  const std::size_t d = t.dimension(), n = static_cast<std::size_t>(t.vertex_count);
  std::vector<double> r(d), gr(d), gx(d);
  double err = 0.0, norm = 0.0;
  for (std::size_t v = 0; v < n; ++v) {
    cpca_reconstruct(t, v, r.data());
    const float* xv = x + v * d;
    for (std::size_t e = 0; e < d; ++e) r[e] = xv[e] - r[e];  // δ
    if (g == nullptr) {
      for (std::size_t e = 0; e < d; ++e) {
        err += r[e] * r[e];
        norm += double(xv[e]) * xv[e];
      }
      continue;
    }
    g->apply(g->g, r.data(), gr.data());
    g->apply(g->g, xv, gx.data());
    for (std::size_t e = 0; e < d; ++e) {
      err += r[e] * gr[e];
      norm += double(xv[e]) * gx[e];
    }
  }
  return norm > 0.0 ? std::sqrt(err / norm) : std::sqrt(err);
}

}  // namespace

Result<CpcaTransfer> cpca_compress(uint32_t order, uint32_t channels, uint64_t vertex_count,
                                   const float* matrices, const CpcaOptions& options) {
  Status s = check_input(order, channels, vertex_count, matrices, options);
  if (!s.ok()) return s;
  try {
    const std::size_t n = static_cast<std::size_t>(vertex_count);
    const std::size_t d = std::size_t(channels) * order * order * order * order;
    MemoryBudget budget(options.memory_limit, "cpca");
    const bool target = options.target_relative_rms > 0.0;
    const std::size_t k_max = target ? options.max_vectors : options.vectors;
    const std::size_t clusters = std::min<std::size_t>(options.clusters, n);
    // A targeted run keeps the largest run, its truncation and its own run: three results.
    budget.charge(run_bytes(n, d, k_max, clusters, options.threads) +
                      (target ? 2 * (uint64_t(n) * k_max * 4 + clusters * (k_max + 1) * d * 4) : 0),
                  "the clustering state and results");
    detail::RowMetric metric;
    const detail::RowMetric* w = nullptr;
    std::unique_ptr<FloatScratch> scaled;  // W x under a metric: in memory, or a mapped file
    if (!options.row_metric.empty()) {
      const std::string problem = metric.build(options.row_metric, channels, order * order);
      if (!problem.empty()) return Status::Error("cpca: " + problem);
      w = &metric;
      auto made = FloatScratch::create(n * d, budget, "the metric's scaled matrices");
      if (!made.ok()) return Status::Error("cpca: " + made.status().message());
      scaled = std::move(made).value();
      float* out = scaled->data();
      parallel_for(n, options.threads, [&](std::size_t v) {
        std::vector<double> y(d);
        metric.apply(metric.w, matrices + v * d, y.data());
        for (std::size_t e = 0; e < d; ++e) out[v * d + e] = static_cast<float>(y[e]);
      });
    }
    const Problem pb{w == nullptr ? matrices : scaled->data(), n, d, &options, matrices, w};
    if (options.target_relative_rms <= 0.0) {
      return run_cpca(pb, options.vectors, order, channels);
    }
    // The largest K once; its nested truncations give the smallest K that meets the target
    // under that clustering; a run at that K (clustered for it) is kept when it also meets it.
    const CpcaTransfer full = run_cpca(pb, options.max_vectors, order, channels);
    auto error_at = [&](uint32_t k) {
      return k >= full.vector_count ? weighted_error(full, matrices, w)
                                    : weighted_error(cpca_truncate(full, k), matrices, w);
    };
    uint32_t k = 0;
    while (k <= options.max_vectors && error_at(k) > options.target_relative_rms) ++k;
    if (k > options.max_vectors) {
      std::ostringstream os;
      os << "cpca: relative RMS error " << options.target_relative_rms << " not reached with "
         << options.max_vectors << " vectors and " << full.cluster_count << " clusters (got "
         << weighted_error(full, matrices, w) << ")";
      return Status::Error(os.str());
    }
    CpcaTransfer own = run_cpca(pb, k, order, channels);
    if (weighted_error(own, matrices, w) <= options.target_relative_rms) return own;
    return cpca_truncate(full, k);
  } catch (const MemoryBudgetExceeded& e) {
    return Status::Error(e.what());
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca: out of memory");
  }
}

Result<CpcaTransfer> cpca_compress(const GlossyTransferData& data, const CpcaOptions& options) {
  if (data.matrices.size() != data.vertex_count * data.channels * data.matrix_floats()) {
    return Status::Error("cpca: the matrix array has " + std::to_string(data.matrices.size()) +
                         " floats, expected vertex_count · channels · order⁴");
  }
  auto r =
      cpca_compress(data.order, data.channels, data.vertex_count, data.matrices.data(), options);
  if (r.ok()) r->fingerprint = data.fingerprint;
  return r;
}

double cpca_relative_rms_error_truncated(const CpcaTransfer& t, const float* x, uint32_t k) {
  if (k >= t.vector_count) return weighted_error(t, x, nullptr);
  return weighted_error(cpca_truncate(t, k), x, nullptr);
}

double cpca_metric_relative_rms_error(const CpcaTransfer& t, const float* x,
                                      const std::vector<double>& row_metric) {
  if (row_metric.empty()) return weighted_error(t, x, nullptr);
  detail::RowMetric metric;
  if (!metric.build(row_metric, t.channels, std::size_t(t.order) * t.order).empty()) return -1.0;
  return weighted_error(t, x, &metric);
}

double cpca_relative_rms_error(const CpcaTransfer& t, const float* x) {
  return cpca_relative_rms_error_truncated(t, x, t.vector_count);
}

}  // namespace prt
